// OpenFOAM ASCII field reader for FoamFluidSource (FluidSource.h).
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "Dictionary.h"
#include "FluidSource.h"
#include "FoamFieldFile.h"

namespace mixflow::mx {

namespace fs = std::filesystem;

namespace {

bool isTimeName(const std::string& s, double& t) {
  if (s.empty()) return false;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), t);
  return r.ec == std::errc() && r.ptr == s.data() + s.size() && std::isfinite(t);
}

// Cell values of one field, expanded to n cells (n < 0: take the length from the file).
std::vector<double> readField(const fs::path& file, int ncomp, long& n) {
  long len = 0;
  std::vector<double> v = readInternalField(file.string(), ncomp, len);
  if (len < 0) {
    if (n < 0)
      throw InputError(file.string() +
                       ": internalField is uniform, so the cell count must come from another field "
                       "(write C with postProcess -func writeCellCentres)");
    std::vector<double> e(static_cast<size_t>(n) * ncomp);
    for (long i = 0; i < n; ++i)
      for (int k = 0; k < ncomp; ++k) e[i * ncomp + k] = v[k];
    return e;
  }
  if (n >= 0 && len != n)
    throw InputError(file.string() + ": internalField has " + std::to_string(len) +
                     " cells, other fields of this time have " + std::to_string(n));
  n = len;
  return v;
}

std::vector<std::string> decompositionRoots(const std::string& caseDir) {
  std::vector<std::string> roots;
  if (fs::is_directory(caseDir))
    for (const auto& e : fs::directory_iterator(caseDir)) {
      const std::string name = e.path().filename().string();
      if (e.is_directory() && name.rfind("processor", 0) == 0 && name.size() > 9 &&
          std::all_of(name.begin() + 9, name.end(), [](char c) { return std::isdigit(c); }))
        roots.push_back(e.path().string());
    }
  std::sort(roots.begin(), roots.end(), [](const std::string& a, const std::string& b) {
    auto num = [](const std::string& s) { return std::stol(s.substr(s.rfind("processor") + 9)); };
    return num(a) < num(b);
  });
  if (roots.empty()) roots.push_back(caseDir);
  return roots;
}

void listTimes(const std::string& root, const std::string& velocity, std::vector<double>& times,
               std::vector<std::string>& names) {
  std::vector<std::pair<double, std::string>> found;
  if (fs::is_directory(root))
    for (const auto& e : fs::directory_iterator(root)) {
      double t = 0;
      const std::string name = e.path().filename().string();
      if (e.is_directory() && isTimeName(name, t) && fs::exists(e.path() / velocity))
        found.emplace_back(t, name);
    }
  std::sort(found.begin(), found.end());
  for (const auto& [t, n] : found) {
    times.push_back(t);
    names.push_back(n);
  }
}

}  // namespace

FoamFluidSource::FoamFluidSource(std::string caseDir, FoamFieldNames names)
    : caseDir_(std::move(caseDir)), names_(std::move(names)) {
  roots_ = decompositionRoots(caseDir_);
  listTimes(roots_.front(), names_.velocity, times_, timeNames_);
}

bool FoamFluidSource::present(const std::string& caseDir, const FoamFieldNames& names) {
  std::vector<double> t;
  std::vector<std::string> n;
  listTimes(decompositionRoots(caseDir).front(), names.velocity, t, n);
  return !t.empty();
}

std::string FoamFluidSource::describe() const {
  std::ostringstream s;
  s << "OpenFOAM ASCII time directories of " << caseDir_;
  if (roots_.size() > 1 || roots_.front() != caseDir_) s << " (" << roots_.size() << " processors)";
  s << "; fields " << names_.liquidFraction << ", " << names_.voidFraction << ", "
    << names_.velocity << ", " << names_.pressure << ", centres " << names_.centres << ", volumes "
    << names_.volumes;
  return s.str();
}

FluidCells FoamFluidSource::cells(double time) const {
  size_t k = 0;
  while (k < times_.size() && times_[k] != time) ++k;
  if (k == times_.size())
    throw InputError(caseDir_ + ": no fluid time directory for t = " + std::to_string(time));
  const std::string tn = timeNames_[k];
  FluidCells all;
  for (const auto& root : roots_) {
    const fs::path dir = fs::path(root) / tn;
    auto meshFile = [&](const std::string& f) {
      for (const fs::path& d : {dir, fs::path(root) / "0", fs::path(root) / "constant"})
        if (fs::exists(d / f)) return d / f;
      throw InputError((dir / f).string() +
                       ": cannot open file (missing; also looked in 0/ and "
                       "constant/). Write it with `postProcess -func " +
                       (f == names_.centres ? std::string("writeCellCentres")
                                            : std::string("writeCellVolumes")) +
                       "`");
    };
    long n = -1;
    const std::vector<double> C = readField(meshFile(names_.centres), 3, n);
    const std::vector<double> V = readField(meshFile(names_.volumes), 1, n);
    const std::vector<double> U = readField(dir / names_.velocity, 3, n);
    const std::vector<double> P = readField(dir / names_.pressure, 1, n);
    std::vector<double> A(static_cast<size_t>(n), 1.0), E(static_cast<size_t>(n), 1.0);
    if (names_.liquidFraction == "auto")
      A = readField(
          dir / (std::filesystem::exists(dir / "alpha.liquid") ? "alpha.liquid" : "alpha.water"), 1,
          n);
    else if (names_.liquidFraction != "none")
      A = readField(dir / names_.liquidFraction, 1, n);
    if (names_.voidFraction != "none") E = readField(dir / names_.voidFraction, 1, n);
    const size_t base = all.size();
    all.resize(base + static_cast<size_t>(n));
    for (long i = 0; i < n; ++i) {
      all.x[base + i] = C[3 * i];
      all.y[base + i] = C[3 * i + 1];
      all.volume[base + i] = V[i];
      all.ux[base + i] = U[3 * i];
      all.uy[base + i] = U[3 * i + 1];
      all.p[base + i] = P[i];
      all.alphaL[base + i] = A[i];
      all.epsF[base + i] = E[i];
    }
  }
  return all;
}

}  // namespace mixflow::mx
