// OpenFOAM ASCII field reader (FoamFieldFile.h).
#include "FoamFieldFile.h"

#include <cctype>
#include <charconv>

#include "Dictionary.h"

namespace mixflow {

namespace {

// internalField of an OpenFOAM vol field: ncomp values per cell (1 scalar, 3 vector).
class FoamFieldParser {
 public:
  FoamFieldParser(std::string text, std::string file)
      : s_(std::move(text)), file_(std::move(file)) {}

  // Returns n x ncomp values; n = -1 for a uniform field (one value, to be repeated).
  std::vector<double> internalField(int ncomp, long& n) {
    const size_t fmt = s_.find("format");
    if (fmt != std::string::npos && fmt < s_.find("internalField")) {
      p_ = fmt + 6;
      if (word() == "binary")
        fail("binary format; write the fields in ascii (controlDict writeFormat ascii)");
    }
    p_ = s_.find("internalField");
    if (p_ == std::string::npos) fail("no internalField entry");
    p_ += 13;
    const std::string kind = word();
    std::vector<double> v;
    if (kind == "uniform") {
      n = -1;
      readItem(ncomp, v);
      return v;
    }
    if (kind != "nonuniform") fail("internalField must be 'uniform' or 'nonuniform'");
    const std::string type = word();  // List<scalar> / List<vector>
    const bool vec = type.find("vector") != std::string::npos;
    if (vec != (ncomp == 3))
      fail("internalField is " + type + ", expected a " + (ncomp == 3 ? "vector" : "scalar") +
           " field");
    n = integer();
    ws();
    expect('(');
    v.reserve(static_cast<size_t>(n) * ncomp);
    for (long i = 0; i < n; ++i) readItem(ncomp, v);
    ws();
    expect(')');
    return v;
  }

 private:
  [[noreturn]] void fail(const std::string& why) const {
    throw InputError(file_ + ": internalField: " + why);
  }
  void ws() {
    while (p_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[p_]))) ++p_;
  }
  std::string word() {
    ws();
    const size_t b = p_;
    while (p_ < s_.size() && !std::isspace(static_cast<unsigned char>(s_[p_])) && s_[p_] != ';' &&
           s_[p_] != '(')
      ++p_;
    return s_.substr(b, p_ - b);
  }
  void expect(char c) {
    if (p_ >= s_.size() || s_[p_] != c)
      fail(std::string("expected '") + c + "' (file truncated or not an OpenFOAM field?)");
    ++p_;
  }
  long integer() {
    ws();
    long v = 0;
    const auto r = std::from_chars(s_.data() + p_, s_.data() + s_.size(), v);
    if (r.ec != std::errc()) fail("expected the list length");
    p_ = static_cast<size_t>(r.ptr - s_.data());
    return v;
  }
  double number() {
    ws();
    double v = 0;
    const auto r = std::from_chars(s_.data() + p_, s_.data() + s_.size(), v);
    if (r.ec != std::errc()) fail("bad number near offset " + std::to_string(p_));
    p_ = static_cast<size_t>(r.ptr - s_.data());
    return v;
  }
  void readItem(int ncomp, std::vector<double>& v) {
    if (ncomp == 1) {
      v.push_back(number());
      return;
    }
    ws();
    expect('(');
    for (int k = 0; k < ncomp; ++k) v.push_back(number());
    ws();
    expect(')');
  }

  std::string s_, file_;
  size_t p_ = 0;
};

}  // namespace

std::vector<double> readInternalField(const std::string& file, int ncomp, long& n) {
  return FoamFieldParser(readTextFile(file), file).internalField(ncomp, n);
}

}  // namespace mixflow
