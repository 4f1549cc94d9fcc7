#include "Dictionary.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <sstream>

namespace mixflow {

Range Range::positive() { return {0.0, std::numeric_limits<double>::infinity(), true, true}; }
Range Range::nonNegative() { return {0.0, std::numeric_limits<double>::infinity(), false, true}; }
Range Range::closed(double lo, double hi) { return {lo, hi, false, false}; }
Range Range::openClosed(double lo, double hi) { return {lo, hi, true, false}; }
Range Range::any() {
  const double inf = std::numeric_limits<double>::infinity();
  return {-inf, inf, true, true};
}

bool Range::contains(double v) const {
  if (!std::isfinite(v)) return false;
  const bool aboveLo = loOpen ? v > lo : v >= lo;
  const bool belowHi = hiOpen ? v < hi : v <= hi;
  return aboveLo && belowHi;
}

std::string formatNumber(double v, int precision) {
  std::ostringstream s;
  s.precision(precision);
  s << v;
  return s.str();
}

static std::string num(double v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return formatNumber(v, 6);  // the stream default
}

std::string Range::str() const {
  return (loOpen ? "(" : "[") + num(lo) + ", " + num(hi) + (hiOpen ? ")" : "]");
}

// Tokeniser + recursive-descent parser for the dictionary grammar above.
class DictionaryParser {
 public:
  DictionaryParser(const std::string& text, const std::string& file) : s_(text), file_(file) {}

  void parseInto(Dictionary& d, bool topLevel) {
    for (;;) {
      skipSpace();
      if (pos_ >= s_.size()) {
        if (!topLevel) error("missing '}' to close dictionary '" + d.path_ + "'");
        return;
      }
      if (s_[pos_] == '}') {
        if (topLevel) error("unexpected '}'");
        ++pos_;
        return;
      }
      const int line = line_;
      if (s_[pos_] == '#') {
        // An OpenFOAM directive (#include "file", #inputMode ...) runs to the end of its line;
        // mixflow reads only the entries written in the file itself.
        while (pos_ < s_.size() && s_[pos_] != '\n') ++pos_;
        continue;
      }
      std::string key = word();
      if (key.empty()) error("expected an entry name");
      skipSpace();
      Dictionary::Entry e;
      e.line = line;
      if (pos_ < s_.size() && s_[pos_] == '{') {
        ++pos_;
        auto sub = std::make_shared<Dictionary>();
        sub->file_ = file_;
        sub->path_ = d.path_.empty() ? key : d.path_ + "." + key;
        parseInto(*sub, false);
        e.dict = sub;
      } else {
        e.tokens = valueTokens(key);
      }
      if (d.entries_.count(key)) error("entry '" + key + "' is given twice");
      d.order_.push_back(key);
      d.entries_[key] = std::move(e);
    }
  }

 private:
  [[noreturn]] void error(const std::string& what) const {
    throw InputError(file_ + ":" + std::to_string(line_) + ": " + what);
  }

  void skipSpace() {
    while (pos_ < s_.size()) {
      const char c = s_[pos_];
      if (c == '\n') {
        ++line_;
        ++pos_;
      } else if (std::isspace(static_cast<unsigned char>(c))) {
        ++pos_;
      } else if (s_.compare(pos_, 2, "//") == 0) {
        while (pos_ < s_.size() && s_[pos_] != '\n') ++pos_;
      } else if (s_.compare(pos_, 2, "/*") == 0) {
        const size_t end = s_.find("*/", pos_ + 2);
        if (end == std::string::npos) error("unterminated /* comment");
        for (size_t i = pos_; i < end; ++i)
          if (s_[i] == '\n') ++line_;
        pos_ = end + 2;
      } else {
        return;
      }
    }
  }

  static bool isDelimiter(char c) {
    return std::isspace(static_cast<unsigned char>(c)) || c == ';' || c == '{' || c == '}' ||
           c == '(' || c == ')';
  }

  std::string word() {
    if (pos_ < s_.size() && s_[pos_] == '"') {
      const size_t end = s_.find('"', pos_ + 1);
      if (end == std::string::npos) error("unterminated string");
      std::string w = s_.substr(pos_ + 1, end - pos_ - 1);
      pos_ = end + 1;
      return w;
    }
    const size_t start = pos_;
    while (pos_ < s_.size() && !isDelimiter(s_[pos_]) && s_.compare(pos_, 2, "//") != 0) ++pos_;
    return s_.substr(start, pos_ - start);
  }

  // Tokens up to ';'. Parentheses are dropped so "(1 2 3)" reads as three scalars.
  std::vector<std::string> valueTokens(const std::string& key) {
    std::vector<std::string> toks;
    for (;;) {
      skipSpace();
      if (pos_ >= s_.size()) error("entry '" + key + "' has no terminating ';'");
      const char c = s_[pos_];
      if (c == ';') {
        ++pos_;
        return toks;
      }
      if (c == '(' || c == ')') {
        ++pos_;
        continue;
      }
      if (c == '{' || c == '}') error("entry '" + key + "' has no terminating ';'");
      toks.push_back(word());
    }
  }

  const std::string& s_;
  std::string file_;
  size_t pos_ = 0;
  int line_ = 1;
};

Dictionary Dictionary::parse(const std::string& text, const std::string& fileName) {
  Dictionary d;
  d.file_ = fileName;
  DictionaryParser(text, fileName).parseInto(d, true);
  // The OpenFOAM file header carries no simulation input.
  if (d.entries_.erase("FoamFile")) {
    d.order_.erase(std::find(d.order_.begin(), d.order_.end(), "FoamFile"));
  }
  return d;
}

// The whole file in one read (particle snapshots of many MB are parsed from memory too).
std::string readTextFile(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw InputError(path + ": cannot open file (missing or unreadable)");
  std::string s;
  std::fseek(f, 0, SEEK_END);
  const long n = std::ftell(f);
  std::fseek(f, 0, SEEK_SET);
  s.resize(n > 0 ? static_cast<size_t>(n) : 0);
  const size_t got = n > 0 ? std::fread(s.data(), 1, s.size(), f) : 0;
  std::fclose(f);
  if (got != s.size()) throw InputError(path + ": read error");
  return s;
}

Dictionary Dictionary::readFile(const std::string& path) { return parse(readTextFile(path), path); }

bool Dictionary::has(const std::string& key) const { return entries_.count(key) > 0; }

bool Dictionary::isDict(const std::string& key) const {
  auto it = entries_.find(key);
  return it != entries_.end() && it->second.dict;
}

std::string Dictionary::where(const std::string& key) const {
  std::string full = path_.empty() ? key : path_ + "." + key;
  std::string s = file_ + ": entry '" + full + "'";
  auto it = entries_.find(key);
  if (it != entries_.end()) s += " (line " + std::to_string(it->second.line) + ")";
  return s;
}

void Dictionary::fail(const std::string& key, const std::string& why) const {
  throw InputError(where(key) + ": " + why);
}

const Dictionary::Entry& Dictionary::entry(const std::string& key) const {
  auto it = entries_.find(key);
  if (it == entries_.end()) fail(key, "missing (required)");
  return it->second;
}

const Dictionary& Dictionary::subDict(const std::string& key) const {
  const Entry& e = entry(key);
  if (!e.dict) fail(key, "must be a dictionary { ... }");
  return *e.dict;
}

Dictionary Dictionary::subDictOrEmpty(const std::string& key) const {
  if (has(key)) return subDict(key);
  Dictionary empty;
  empty.file_ = file_;
  empty.path_ = path_.empty() ? key : path_ + "." + key;
  return empty;
}

double Dictionary::toScalar(const std::string& key, const std::string& tok) const {
  try {
    size_t used = 0;
    const double v = std::stod(tok, &used);
    if (used != tok.size()) throw std::invalid_argument(tok);
    return v;
  } catch (const std::exception&) {
    fail(key, "'" + tok + "' is not a number");
  }
}

double Dictionary::scalar(const std::string& key, const Range& range) const {
  const Entry& e = entry(key);
  if (e.dict) fail(key, "must be a single number in " + range.str() + ", not a dictionary");
  if (e.tokens.size() != 1)
    fail(key, "must be a single number in " + range.str() + "; found '" + text(key) +
                  "' (a missing ';'?)");
  const double v = toScalar(key, e.tokens[0]);
  if (!range.contains(v))
    fail(key, "value " + e.tokens[0] + " is outside the allowed range " + range.str());
  return v;
}

double Dictionary::scalarOr(const std::string& key, double def, const Range& range) const {
  return has(key) ? scalar(key, range) : def;
}

namespace {
bool isNumber(const std::string& tok) {
  char* end = nullptr;
  std::strtod(tok.c_str(), &end);
  return !tok.empty() && end == tok.c_str() + tok.size();
}
}  // namespace

bool Dictionary::absentOrAuto(const std::string& key, const std::string& number) const {
  if (!has(key)) return true;
  const Entry& e = entry(key);
  if (!e.dict && text(key) == "auto") return true;
  if (e.dict || e.tokens.size() != 1 || !isNumber(e.tokens[0]))
    fail(key,
         "'" + (e.dict ? std::string("{...}") : text(key)) + "' is not allowed: auto or " + number);
  return false;
}

std::optional<double> Dictionary::scalarOrAuto(const std::string& key, const Range& range) const {
  if (absentOrAuto(key, "a number in " + range.str())) return std::nullopt;
  return scalar(key, range);
}

std::optional<long> Dictionary::integerOrAuto(const std::string& key, long lo, long hi) const {
  if (absentOrAuto(key, "a whole number in [" + num(lo) + ", " + num(hi) + "]"))
    return std::nullopt;
  return integer(key, lo, hi);
}

long Dictionary::integer(const std::string& key, long lo, long hi) const {
  const double v = scalar(key, Range::closed(static_cast<double>(lo), static_cast<double>(hi)));
  if (v != std::floor(v)) fail(key, "must be a whole number in [" + num(lo) + ", " + num(hi) + "]");
  return static_cast<long>(v);
}

long Dictionary::integerOr(const std::string& key, long def, long lo, long hi) const {
  return has(key) ? integer(key, lo, hi) : def;
}

std::string joinWords(const std::vector<std::string>& w) {
  std::string s;
  for (size_t i = 0; i < w.size(); ++i) s += (i ? ", " : "") + w[i];
  return s;
}

std::string Dictionary::word(const std::string& key,
                             const std::vector<std::string>& allowed) const {
  const Entry& e = entry(key);
  if (e.dict || e.tokens.size() != 1)
    fail(key,
         (allowed.empty() ? "must be one word" : "must be one word of: " + joinWords(allowed)) +
             (e.dict ? "" : "; found '" + text(key) + "' (a missing ';'?)"));
  const std::string& w = e.tokens[0];
  if (!allowed.empty() && std::find(allowed.begin(), allowed.end(), w) == allowed.end())
    fail(key, "'" + w + "' is not allowed; choose one of: " + joinWords(allowed));
  return w;
}

std::string Dictionary::wordOr(const std::string& key, const std::string& def,
                               const std::vector<std::string>& allowed) const {
  return has(key) ? word(key, allowed) : def;
}

bool Dictionary::switchOr(const std::string& key, bool def) const {
  if (!has(key)) return def;
  const std::string w = word(key, {"on", "off", "yes", "no", "true", "false"});
  return w == "on" || w == "yes" || w == "true";
}

std::vector<double> Dictionary::scalars(const std::string& key, const Range& range) const {
  const Entry& e = entry(key);
  if (e.dict) fail(key, "must be a list of numbers");
  std::vector<double> out;
  for (const auto& t : e.tokens) {
    const double v = toScalar(key, t);
    if (!range.contains(v))
      fail(key, "value " + t + " is outside the allowed range " + range.str());
    out.push_back(v);
  }
  return out;
}

std::string Dictionary::text(const std::string& key) const {
  const Entry& e = entry(key);
  if (e.dict) fail(key, "must be a value, not a dictionary");
  std::string s;
  for (size_t i = 0; i < e.tokens.size(); ++i) s += (i ? " " : "") + e.tokens[i];
  return s;
}

void Dictionary::allowOnly(const std::vector<std::string>& keys) const {
  for (const auto& k : order_) {
    if (std::find(keys.begin(), keys.end(), k) == keys.end())
      fail(k, "unknown entry; allowed entries here: " + joinWords(keys));
  }
}

std::vector<std::string> Dictionary::keys() const { return order_; }

RunTimes readRunTimes(const Dictionary& control) {
  RunTimes t;
  t.endTime = control.scalar("endTime", Range::positive());
  t.writeInterval = control.scalar("writeInterval", Range::positive());
  if (t.writeInterval > t.endTime)
    control.fail("writeInterval",
                 "value " + formatNumber(t.writeInterval, 6) + " s exceeds endTime (" +
                     formatNumber(t.endTime, 6) +
                     " s): the run would end before its first field write, particle snapshot "
                     "and resume state; allowed range (0, " +
                     formatNumber(t.endTime, 6) + "]");
  return t;
}

}  // namespace mixflow
