// Reader for OpenFOAM-style dictionaries (the convention users of this simulator already know):
//   key value;   key v1 v2 v3;   key (1 2 3);   name { ... }   // and /* */ comments.
// Directives (#include "file" ...) are skipped to the end of their line: only the entries written
// in the file itself are read.
// Every lookup validates its value and throws InputError with the file, the dotted entry path and
// the allowed range, so bad input stops before any run starts.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace mixflow {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The whole file as text; InputError naming the file if it cannot be opened.
std::string readTextFile(const std::string& path);

// v with `precision` significant digits (messages, CSV, JSON, state files, LIGGGHTS commands).
std::string formatNumber(double v, int precision = 10);

// Words as the messages and docs list them: "a, b, c".
std::string joinWords(const std::vector<std::string>& words);

// Closed or open interval for a scalar entry; printed in error messages.
struct Range {
  double lo;
  double hi;
  bool loOpen = false;
  bool hiOpen = false;

  static Range positive();
  static Range nonNegative();
  static Range closed(double lo, double hi);
  static Range openClosed(double lo, double hi);  // (lo, hi]
  static Range any();
  bool contains(double v) const;
  std::string str() const;
};

class Dictionary {
 public:
  static Dictionary readFile(const std::string& path);
  static Dictionary parse(const std::string& text, const std::string& fileName);

  bool has(const std::string& key) const;
  bool isDict(const std::string& key) const;
  const Dictionary& subDict(const std::string& key) const;
  // Empty dictionary (same file/path) when the sub-dictionary is absent: all entries take defaults.
  Dictionary subDictOrEmpty(const std::string& key) const;

  double scalar(const std::string& key, const Range& range) const;
  double scalarOr(const std::string& key, double def, const Range& range) const;
  long integer(const std::string& key, long lo, long hi) const;
  long integerOr(const std::string& key, long def, long lo, long hi) const;
  // Entries whose default is chosen by the program (`auto`): empty when absent or `auto`, else the
  // number, checked like scalar()/integer(); anything else is refused naming both choices.
  std::optional<double> scalarOrAuto(const std::string& key, const Range& range) const;
  std::optional<long> integerOrAuto(const std::string& key, long lo, long hi) const;
  std::string word(const std::string& key, const std::vector<std::string>& allowed) const;
  std::string wordOr(const std::string& key, const std::string& def,
                     const std::vector<std::string>& allowed) const;
  bool switchOr(const std::string& key, bool def) const;
  std::vector<double> scalars(const std::string& key, const Range& range) const;
  std::string text(const std::string& key) const;  // raw tokens joined by spaces

  // Unknown entries are errors (a typo must not silently fall back to a default).
  void allowOnly(const std::vector<std::string>& keys) const;
  std::vector<std::string> keys() const;

  const std::string& fileName() const { return file_; }
  std::string where(const std::string& key) const;  // "file: entry 'a.b.key' (line N)"
  [[noreturn]] void fail(const std::string& key, const std::string& why) const;

 private:
  struct Entry {
    std::vector<std::string> tokens;
    std::shared_ptr<Dictionary> dict;
    int line = 0;
  };
  const Entry& entry(const std::string& key) const;
  // scalarOrAuto/integerOrAuto: true when key is absent or `auto`; anything but one number is
  // refused as "not allowed: auto or <number>".
  bool absentOrAuto(const std::string& key, const std::string& number) const;
  double toScalar(const std::string& key, const std::string& tok) const;

  std::string file_;
  std::string path_;  // dotted path of this dictionary inside the file ("" at top level)
  std::map<std::string, Entry> entries_;
  std::vector<std::string> order_;

  friend class DictionaryParser;
};

// endTime and writeInterval (s) of a case's system/controlDict, as every program reads them.
// writeInterval must not exceed endTime: a run would otherwise end before its first field write,
// particle snapshot and resume state (InputError naming the entry and the allowed range).
struct RunTimes {
  double endTime = 0;
  double writeInterval = 0;
};
RunTimes readRunTimes(const Dictionary& controlDict);

}  // namespace mixflow
