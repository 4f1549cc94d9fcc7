// Declaration table of one dictionary file: every entry once, with its type, default, allowed
// range or words, unit and meaning. The typed accessors read and validate an entry as declared
// (through Dictionary, whose messages name file, line, entry and allowed range), and markdown()
// prints the table docs/parameters.md shows, so reading and documentation share one declaration.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "Dictionary.h"

namespace mixflow {

// A unit a value is likely typed in by mistake: the value in SI is value x factor (g/cm³ for
// kg/m³: 1000; GPa for Pa: 1e9; mm for m: 1e-3).
struct UnitSlip {
  std::string unit;
  double factor = 1;
};

struct Param {
  enum class Type { Scalar, Integer, Word, Switch, Text, Dict, Any };
  std::string path;  // dotted path inside the file: "sample.length", "liquid.air.density"
  Type type = Type::Scalar;
  bool required = false;
  bool autoDefault = false;    // Scalar, Integer: absent or `auto` leaves the choice to the program
  double number = 0;           // default of Scalar, Integer, Switch (1 = on)
  std::string word;            // default of Word, Text
  Range range = Range::any();  // Scalar; Integer: closed [lo, hi]
  std::vector<std::string> words;  // Word: the allowed words
  std::string unit;
  std::string meaning;
  // Values of the dictionary's selector entry (e.g. liquid.rheology) this entry belongs to;
  // empty: every value.
  std::vector<std::string> onlyFor;
  std::string allowedNote;  // a cross-entry rule shown after the range, e.g. "≥ d"
  std::string defaultNote;  // shown in place of the default, e.g. "(required, Newtonian only)"
  // Plausibility (Scalar): the physical range of the material or object named (plausibleFor),
  // inside the allowed range; a value outside it is refused as a unit slip, suggesting the units
  // of `slips` that would put it inside. plausibleByReader: the reader checks it itself
  // (checkPlausible), e.g. where another entry decides what the material is.
  std::optional<Range> plausibleRange;
  std::string plausibleFor;
  std::vector<UnitSlip> slips;
  bool plausibleByReader = false;

  std::string key() const;      // last component of path
  std::string section() const;  // path without its last component ("" at top level)
  Param& only(std::vector<std::string> selectors);
  Param& alsoAllowed(std::string note);
  Param& shownDefault(std::string note);
  Param& plausible(Range range, std::string what, std::vector<UnitSlip> units,
                   bool byReader = false);
  // "; in g/cm³ that would be 2500 kg/m3" for the slips that put v inside the plausible range
  // (empty if none does).
  std::string slipHint(double v) const;
};

Param scalarParam(std::string path, double def, Range range, std::string unit, std::string meaning);
Param requiredScalar(std::string path, Range range, std::string unit, std::string meaning);
Param integerParam(std::string path, long def, long lo, long hi, std::string meaning);
Param wordParam(std::string path, std::string def, std::vector<std::string> words,
                std::string meaning);
Param requiredWord(std::string path, std::vector<std::string> words, std::string meaning);
Param switchParam(std::string path, bool def, std::string meaning);
// `auto` (the default) or a number in range; the program's rule for auto is in the meaning.
Param autoScalar(std::string path, Range range, std::string unit, std::string meaning);
Param autoInteger(std::string path, long lo, long hi, std::string meaning);
Param textParam(std::string path, std::string def, std::string meaning);  // raw tokens
Param dictParam(std::string path, std::string meaning);                   // a sub-dictionary
Param anyParam(std::string path, std::string meaning);  // read by another reader (Function1)

class Schema {
 public:
  Schema(std::string file, std::vector<Param> params);

  const std::string& file() const { return file_; }  // e.g. constant/sceneProperties
  const std::vector<Param>& params() const { return params_; }
  const Param& param(const std::string& path) const;  // std::logic_error when undeclared

  // Keys declared directly in `section` ("" top level), of every selector value or of `selector`.
  std::vector<std::string> keys(const std::string& section, const std::string& selector = "") const;
  // Refuses the entries of d (the dictionary at `section`) that are not declared there.
  void allowOnly(const Dictionary& d, const std::string& section) const;

  // The entry at `path` of d (the dictionary holding it), validated as declared; absent, its
  // default, or refused as missing (with unit and allowed range) when required.
  double scalar(const Dictionary& d, const std::string& path) const;
  long integer(const Dictionary& d, const std::string& path) const;
  std::string word(const Dictionary& d, const std::string& path) const;
  bool flag(const Dictionary& d, const std::string& path) const;
  std::string text(const Dictionary& d, const std::string& path) const;
  // Auto entries: empty when absent or `auto`.
  std::optional<double> scalarOrAuto(const Dictionary& d, const std::string& path) const;
  std::optional<long> integerOrAuto(const Dictionary& d, const std::string& path) const;

  // Markdown table (entry, default, allowed, unit, meaning) of the entries in `sections`, in
  // declaration order; sub-dictionaries themselves are not rows.
  std::string markdown(const std::vector<std::string>& sections) const;
  // Rows (file, entry, plausible range, unit, of what, unit slips suggested) of the entries with
  // a plausible range, for the table docs/parameters.md shows (mixflowSchema).
  std::string plausibleRows() const;

  // Refuses v (entry `path`, in d) outside its plausible range, naming file, entry, value, the
  // range and what it is the range of, and the unit slips that would explain it.
  void checkPlausible(const Dictionary& d, const std::string& path, double v) const;

 private:
  const Param& typed(const std::string& path, Param::Type type) const;
  std::string file_;
  std::vector<Param> params_;
};

// Markdown text of a number as a dictionary would write it: 70e9, 1.48e-5, 0.6056, 12345.
std::string docNumber(double v);

}  // namespace mixflow
