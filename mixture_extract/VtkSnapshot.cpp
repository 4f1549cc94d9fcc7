#include "VtkSnapshot.h"

#include <charconv>
#include <cmath>
#include <string_view>

#include "Dictionary.h"

namespace mixflow::mx {

namespace {

// Whitespace tokenizer over the whole file (legacy VTK ASCII is whitespace separated).
class Scanner {
 public:
  Scanner(const std::string& text, const std::string& file) : s_(text), file_(file) {}

  std::string_view token() {
    skip();
    const size_t b = p_;
    while (p_ < s_.size() && !space(s_[p_])) ++p_;
    return std::string_view(s_).substr(b, p_ - b);
  }
  bool atEnd() {
    skip();
    return p_ >= s_.size();
  }
  long integer(const char* what) {
    const std::string_view t = token();
    long v = 0;
    const auto r = std::from_chars(t.data(), t.data() + t.size(), v);
    if (r.ec != std::errc() || r.ptr != t.data() + t.size())
      fail(std::string("expected an integer for ") + what + ", found '" + std::string(t) + "'");
    return v;
  }
  double number(const char* what) {
    skip();
    if (p_ >= s_.size())
      fail(std::string("file ends inside array ") + what + " (truncated snapshot?)");
    const char* b = s_.data() + p_;
    const char* e = s_.data() + s_.size();
    double v = 0;
    auto r = std::from_chars(b, e, v);
    if (r.ec != std::errc() || (r.ptr < e && !space(*r.ptr))) {
      // from_chars rejects a leading '+' and inf/nan spellings; report the token.
      const std::string_view t = token();
      fail(std::string("bad number '") + std::string(t) + "' in array " + what);
    }
    p_ = static_cast<size_t>(r.ptr - s_.data());
    return v;
  }
  void skipTokens(long n) {
    for (long k = 0; k < n; ++k) {
      skip();
      if (p_ >= s_.size()) fail("file ends inside an array (truncated snapshot?)");
      while (p_ < s_.size() && !space(s_[p_])) ++p_;
    }
  }
  // Moves just past the next whole-word occurrence of key; false when absent.
  bool seek(std::string_view key) {
    for (;;) {
      const size_t f = s_.find(key, p_);
      if (f == std::string::npos) return false;
      const bool startOk = f == 0 || space(s_[f - 1]);
      const size_t end = f + key.size();
      const bool endOk = end >= s_.size() || space(s_[end]);
      p_ = end;
      if (startOk && endOk) return true;
    }
  }
  [[noreturn]] void fail(const std::string& why) const { throw InputError(file_ + ": " + why); }

 private:
  static bool space(char c) { return c == ' ' || c == '\n' || c == '\t' || c == '\r'; }
  void skip() {
    while (p_ < s_.size() && space(s_[p_])) ++p_;
  }
  const std::string& s_;
  const std::string& file_;
  size_t p_ = 0;
};

}  // namespace

ParticleSnapshot readVtkSnapshot(const std::string& path, double time) {
  const std::string text = readTextFile(path);
  Scanner sc(text, path);
  ParticleSnapshot snap;
  snap.time = time;
  snap.file = path;
  if (text.compare(0, 22, "# vtk DataFile Version") != 0)
    sc.fail("not a legacy VTK file (no '# vtk DataFile Version' header)");
  if (!sc.seek("ASCII")) sc.fail("not an ASCII legacy VTK file (binary dumps are not supported)");
  if (!sc.seek("POINTS")) sc.fail("no POINTS section");
  const long n = sc.integer("POINTS count");
  if (n < 0) sc.fail("negative POINTS count");
  sc.token();  // float | double
  snap.resize(static_cast<size_t>(n));
  for (long i = 0; i < n; ++i) {
    snap.x[i] = sc.number("POINTS");
    snap.y[i] = sc.number("POINTS");
    snap.z[i] = sc.number("POINTS");
  }
  if (n == 0) return snap;  // an empty dump (all particles left the channel)
  if (!sc.seek("POINT_DATA")) sc.fail("no POINT_DATA section");
  if (sc.integer("POINT_DATA count") != n) sc.fail("POINT_DATA count differs from POINTS count");
  if (sc.token() != "FIELD") sc.fail("expected 'FIELD FieldData k' after POINT_DATA");
  sc.token();
  const long arrays = sc.integer("FIELD array count");

  bool haveMass = false, haveRadius = false, haveV = false, haveS1 = false, haveS2 = false;
  for (long a = 0; a < arrays; ++a) {
    const std::string name(sc.token());
    if (name.empty()) sc.fail("file ends before all " + std::to_string(arrays) + " arrays");
    const long nc = sc.integer(name.c_str());
    const long nt = sc.integer(name.c_str());
    sc.token();  // data type
    if (nt != n)
      sc.fail("array '" + name + "' has " + std::to_string(nt) + " tuples, not " +
              std::to_string(n));
    auto need = [&](long comps) {
      if (nc != comps)
        sc.fail("array '" + name + "' has " + std::to_string(nc) + " components, expected " +
                std::to_string(comps));
    };
    const char* nm = name.c_str();
    if (name == "id") {
      need(1);
      for (long i = 0; i < n; ++i) snap.id[i] = std::lround(sc.number(nm));
    } else if (name == "mass") {
      need(1);
      for (long i = 0; i < n; ++i) snap.mass[i] = sc.number(nm);
      haveMass = true;
    } else if (name == "radius") {
      need(1);
      for (long i = 0; i < n; ++i) snap.radius[i] = sc.number(nm);
      haveRadius = true;
    } else if (name == "v") {
      need(3);
      for (long i = 0; i < n; ++i) {
        snap.vx[i] = sc.number(nm);
        snap.vy[i] = sc.number(nm);
        snap.vz[i] = sc.number(nm);
      }
      haveV = true;
    } else if (name == "c_pstress[1-3]" || name == "c_pstress[4-6]") {
      need(3);
      const int off = name == "c_pstress[1-3]" ? 0 : 3;
      for (long i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k) snap.stress[i][off + k] = sc.number(nm);
      (off == 0 ? haveS1 : haveS2) = true;
    } else {
      sc.skipTokens(nc * nt);
    }
  }
  std::string missing;
  if (!haveMass) missing += " mass";
  if (!haveRadius) missing += " radius";
  if (!haveV) missing += " v";
  if (!haveS1) missing += " c_pstress[1-3]";
  if (!haveS2) missing += " c_pstress[4-6]";
  if (!missing.empty())
    sc.fail("missing array(s):" + missing +
            " (the snapshot must come from mixflowDem's dump: id type x y z vx vy vz ... radius "
            "mass c_pstress[1..6])");
  checkParticles(snap);
  return snap;
}

}  // namespace mixflow::mx
