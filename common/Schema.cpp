#include "Schema.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>

namespace mixflow {

std::string Param::key() const {
  const size_t dot = path.rfind('.');
  return dot == std::string::npos ? path : path.substr(dot + 1);
}

std::string Param::section() const {
  const size_t dot = path.rfind('.');
  return dot == std::string::npos ? "" : path.substr(0, dot);
}

Param& Param::only(std::vector<std::string> selectors) {
  onlyFor = std::move(selectors);
  return *this;
}
Param& Param::alsoAllowed(std::string note) {
  allowedNote = std::move(note);
  return *this;
}
Param& Param::shownDefault(std::string note) {
  defaultNote = std::move(note);
  return *this;
}
Param& Param::plausible(Range r, std::string what, std::vector<UnitSlip> units, bool byReader) {
  plausibleRange = r;
  plausibleFor = std::move(what);
  slips = std::move(units);
  plausibleByReader = byReader;
  return *this;
}

namespace {
// "[1e5, 1.2e12]": a range with the numbers as the docs write them.
std::string plainRange(const Range& r) {
  return (r.loOpen ? "(" : "[") + docNumber(r.lo) + ", " + docNumber(r.hi) + (r.hiOpen ? ")" : "]");
}
}  // namespace

std::string Param::slipHint(double v) const {
  if (!plausibleRange || !std::isfinite(v)) return "";
  std::string hint;
  for (const auto& s : slips) {
    const double si = v * s.factor;
    if (!plausibleRange->contains(si)) continue;
    hint += (hint.empty() ? "" : ", or ") + std::string("typed in ") + s.unit + ", it is " +
            docNumber(si) + (unit.empty() ? "" : " " + unit);
  }
  return hint.empty() ? "" : " (a unit slip? " + hint + ")";
}

namespace {
Param make(std::string path, Param::Type type, std::string meaning) {
  Param p;
  p.path = std::move(path);
  p.type = type;
  p.meaning = std::move(meaning);
  return p;
}

// Ranges as the docs write them: "> 0", "≥ 0", "any", else the interval.
std::string docRange(const Range& r) {
  if (std::isinf(r.hi) && std::isinf(r.lo)) return "any";
  if (std::isinf(r.hi) && r.lo == 0) return r.loOpen ? "> 0" : "≥ 0";
  return r.str();
}

std::string docAllowed(const Param& p) {
  std::string s;
  switch (p.type) {
    case Param::Type::Scalar:
      s = (p.autoDefault ? "auto, " : "") + docRange(p.range);
      break;
    case Param::Type::Integer:
      s = (p.autoDefault ? "auto, [" : "[") + docNumber(p.range.lo) + ", " + docNumber(p.range.hi) +
          "]";
      break;
    case Param::Type::Word:
      s = joinWords(p.words);
      break;
    case Param::Type::Switch:
      s = "on, off";
      break;
    case Param::Type::Text:
      break;
    case Param::Type::Dict:
      s = "dictionary";
      break;
    case Param::Type::Any:
      s = "see meaning";
      break;
  }
  if (p.allowedNote.empty()) return s;
  return s.empty() ? p.allowedNote : s + ", " + p.allowedNote;
}

std::string docDefault(const Param& p) {
  if (!p.defaultNote.empty()) return p.defaultNote;
  if (p.required) return "(required)";
  if (p.autoDefault) return "auto";
  switch (p.type) {
    case Param::Type::Scalar:
    case Param::Type::Integer:
      return docNumber(p.number);
    case Param::Type::Word:
      return p.word;
    case Param::Type::Text:
      return "`" + p.word + "`";
    case Param::Type::Switch:
      return p.number != 0 ? "on" : "off";
    default:
      return "(none)";
  }
}
}  // namespace

std::string docNumber(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  std::string plain = buf;
  // The shortest exponent form that reads back as v: 1e4, 7e10, 1.48e-5.
  std::string expo;
  for (int digits = 0; digits < 6 && expo.empty(); ++digits) {
    std::snprintf(buf, sizeof buf, "%.*e", digits, v);
    if (std::stod(buf) == std::stod(plain)) expo = buf;
  }
  const size_t e = expo.find('e');
  const bool neg = expo[e + 1] == '-';
  std::string ex = expo.substr(e + 2);
  ex.erase(0, std::min(ex.find_first_not_of('0'), ex.size() - 1));
  expo = expo.substr(0, e) + "e" + (neg ? "-" : "") + ex;
  if (plain.find('e') != std::string::npos) return expo;
  return expo.size() < plain.size() ? expo : plain;
}

Param scalarParam(std::string path, double def, Range range, std::string unit,
                  std::string meaning) {
  Param p = make(std::move(path), Param::Type::Scalar, std::move(meaning));
  p.number = def;
  p.range = range;
  p.unit = std::move(unit);
  return p;
}
Param requiredScalar(std::string path, Range range, std::string unit, std::string meaning) {
  Param p = scalarParam(std::move(path), 0, range, std::move(unit), std::move(meaning));
  p.required = true;
  return p;
}
Param integerParam(std::string path, long def, long lo, long hi, std::string meaning) {
  Param p = make(std::move(path), Param::Type::Integer, std::move(meaning));
  p.number = static_cast<double>(def);
  p.range = Range::closed(static_cast<double>(lo), static_cast<double>(hi));
  return p;
}
Param wordParam(std::string path, std::string def, std::vector<std::string> words,
                std::string meaning) {
  Param p = make(std::move(path), Param::Type::Word, std::move(meaning));
  p.word = std::move(def);
  p.words = std::move(words);
  return p;
}
Param requiredWord(std::string path, std::vector<std::string> words, std::string meaning) {
  Param p = wordParam(std::move(path), "", std::move(words), std::move(meaning));
  p.required = true;
  return p;
}
Param switchParam(std::string path, bool def, std::string meaning) {
  Param p = make(std::move(path), Param::Type::Switch, std::move(meaning));
  p.number = def ? 1 : 0;
  return p;
}
Param autoScalar(std::string path, Range range, std::string unit, std::string meaning) {
  Param p = scalarParam(std::move(path), 0, range, std::move(unit), std::move(meaning));
  p.autoDefault = true;
  return p;
}
Param autoInteger(std::string path, long lo, long hi, std::string meaning) {
  Param p = integerParam(std::move(path), 0, lo, hi, std::move(meaning));
  p.autoDefault = true;
  return p;
}
Param textParam(std::string path, std::string def, std::string meaning) {
  Param p = make(std::move(path), Param::Type::Text, std::move(meaning));
  p.word = std::move(def);
  return p;
}
Param dictParam(std::string path, std::string meaning) {
  return make(std::move(path), Param::Type::Dict, std::move(meaning));
}
Param anyParam(std::string path, std::string meaning) {
  return make(std::move(path), Param::Type::Any, std::move(meaning));
}

Schema::Schema(std::string file, std::vector<Param> params)
    : file_(std::move(file)), params_(std::move(params)) {
  for (size_t i = 0; i < params_.size(); ++i)
    for (size_t j = 0; j < i; ++j)
      if (params_[i].path == params_[j].path)
        throw std::logic_error(file_ + ": entry '" + params_[i].path + "' declared twice");
}

const Param& Schema::param(const std::string& path) const {
  for (const auto& p : params_)
    if (p.path == path) return p;
  throw std::logic_error(file_ + ": entry '" + path + "' is not declared");
}

const Param& Schema::typed(const std::string& path, Param::Type type) const {
  const Param& p = param(path);
  if (p.type != type) throw std::logic_error(file_ + ": entry '" + path + "' read as another type");
  return p;
}

std::vector<std::string> Schema::keys(const std::string& section,
                                      const std::string& selector) const {
  std::vector<std::string> k;
  for (const auto& p : params_) {
    if (p.section() != section) continue;
    if (!selector.empty() && !p.onlyFor.empty() &&
        std::find(p.onlyFor.begin(), p.onlyFor.end(), selector) == p.onlyFor.end())
      continue;
    k.push_back(p.key());
  }
  return k;
}

void Schema::allowOnly(const Dictionary& d, const std::string& section) const {
  d.allowOnly(keys(section));
}

double Schema::scalar(const Dictionary& d, const std::string& path) const {
  const Param& p = typed(path, Param::Type::Scalar);
  const std::string k = p.key();
  if (p.required && !d.has(k))
    d.fail(k, "missing (required)" + (p.unit.empty() ? "" : " in " + p.unit) + ", allowed range " +
                  p.range.str());
  double v = 0;
  try {
    v = p.required ? d.scalar(k, p.range) : d.scalarOr(k, p.number, p.range);
  } catch (const InputError& e) {
    // Outside the allowed range: say which unit would explain it, when one would.
    double raw = 0;
    try {
      raw = d.scalar(k, Range::any());
    } catch (const InputError&) {
      throw e;
    }
    const std::string hint = p.slipHint(raw);
    if (hint.empty()) throw;
    throw InputError(e.what() + hint);
  }
  if (d.has(k) && !p.plausibleByReader) checkPlausible(d, path, v);
  return v;
}

void Schema::checkPlausible(const Dictionary& d, const std::string& path, double v) const {
  const Param& p = param(path);
  if (!p.plausibleRange || p.plausibleRange->contains(v)) return;
  const std::string u = p.unit.empty() ? "" : " " + p.unit;
  d.fail(p.key(), "value " + docNumber(v) + u + " is outside the plausible range " +
                      plainRange(*p.plausibleRange) + u + " of " + p.plausibleFor + p.slipHint(v) +
                      "; write it in " + (p.unit.empty() ? "SI units" : p.unit) +
                      " (docs/parameters.md, \"Plausible ranges\")");
}

long Schema::integer(const Dictionary& d, const std::string& path) const {
  const Param& p = typed(path, Param::Type::Integer);
  const long lo = std::lround(p.range.lo), hi = std::lround(p.range.hi);
  if (p.required) return d.integer(p.key(), lo, hi);
  return d.integerOr(p.key(), std::lround(p.number), lo, hi);
}

std::string Schema::word(const Dictionary& d, const std::string& path) const {
  const Param& p = typed(path, Param::Type::Word);
  if (p.required) return d.word(p.key(), p.words);
  return d.wordOr(p.key(), p.word, p.words);
}

bool Schema::flag(const Dictionary& d, const std::string& path) const {
  const Param& p = typed(path, Param::Type::Switch);
  return d.switchOr(p.key(), p.number != 0);
}

std::string Schema::text(const Dictionary& d, const std::string& path) const {
  const Param& p = typed(path, Param::Type::Text);
  return p.required || d.has(p.key()) ? d.text(p.key()) : p.word;
}

std::optional<double> Schema::scalarOrAuto(const Dictionary& d, const std::string& path) const {
  const Param& p = typed(path, Param::Type::Scalar);
  if (!p.autoDefault) throw std::logic_error(file_ + ": entry '" + path + "' has no auto");
  return d.scalarOrAuto(p.key(), p.range);
}

std::optional<long> Schema::integerOrAuto(const Dictionary& d, const std::string& path) const {
  const Param& p = typed(path, Param::Type::Integer);
  if (!p.autoDefault) throw std::logic_error(file_ + ": entry '" + path + "' has no auto");
  return d.integerOrAuto(p.key(), std::lround(p.range.lo), std::lround(p.range.hi));
}

std::string Schema::markdown(const std::vector<std::string>& sections) const {
  std::string s =
      "| entry | default | allowed | unit | meaning |\n"
      "|---|---|---|---|---|\n";
  for (const auto& p : params_) {
    if (p.type == Param::Type::Dict) continue;
    if (std::find(sections.begin(), sections.end(), p.section()) == sections.end()) continue;
    s += "| `" + p.path + "` | " + docDefault(p) + " | " + docAllowed(p) + " | " + p.unit + " | " +
         p.meaning + " |\n";
  }
  return s;
}

std::string Schema::plausibleRows() const {
  std::string s;
  for (const auto& p : params_) {
    if (!p.plausibleRange) continue;
    std::string slips;
    for (const auto& u : p.slips) slips += (slips.empty() ? "" : ", ") + u.unit;
    s += "| " + file_ + " | `" + p.path + "` | " + plainRange(*p.plausibleRange) + " | " + p.unit +
         " | " + p.plausibleFor + " | " + slips + " |\n";
  }
  return s;
}

}  // namespace mixflow
