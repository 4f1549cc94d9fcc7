#include "BinarySnapshot.h"

#include <cstdint>
#include <cstring>

#include "Dictionary.h"
#include "SnapshotFiles.h"

namespace mixflow::mx {

namespace {

// Reads fixed-size values off the file's bytes; running past the end is a truncated file.
class Cursor {
 public:
  Cursor(const std::string& bytes, const std::string& file) : b_(bytes), file_(file) {}

  template <class T>
  T get(const std::string& what) {
    T v;
    std::memcpy(&v, take(sizeof(T), what), sizeof(T));
    return v;
  }
  const char* take(size_t n, const std::string& what) {
    if (n > b_.size() - p_)
      fail("file ends inside " + what + " (" + std::to_string(b_.size()) +
           " bytes; truncated snapshot?)");
    const char* at = b_.data() + p_;
    p_ += n;
    return at;
  }
  size_t left() const { return b_.size() - p_; }
  [[noreturn]] void fail(const std::string& why) const { throw InputError(file_ + ": " + why); }

 private:
  const std::string& b_;
  const std::string& file_;
  size_t p_ = 0;
};

}  // namespace

ParticleSnapshot readBinarySnapshot(const std::string& path, double time) {
  using namespace dem;
  const std::string bytes = readFileBytes(path);
  Cursor c(bytes, path);
  ParticleSnapshot snap;
  snap.time = time;
  snap.file = path;
  const std::string header = "the header";
  c.get<int64_t>(header);  // LIGGGHTS step (the series gives the time)
  const int64_t natoms = c.get<int64_t>(header);
  const int32_t triclinic = c.get<int32_t>(header);
  if (natoms < 0 || (triclinic != 0 && triclinic != 1))
    c.fail("not a LIGGGHTS binary dump (particle count " + std::to_string(natoms) +
           ", triclinic flag " + std::to_string(triclinic) + ")");
  c.take(6 * sizeof(int32_t) + (triclinic ? 9 : 6) * sizeof(double), header);  // boundary, box
  const int32_t cols = c.get<int32_t>(header);
  const int32_t chunks = c.get<int32_t>(header);
  if (cols != kSnapshotColumnCount)
    c.fail(std::to_string(cols) + " values per particle, expected " +
           std::to_string(kSnapshotColumnCount) + " (" + snapshotColumns() +
           "): not a mixflowDem snapshot");
  if (chunks < 1) c.fail("no rank chunks (" + std::to_string(chunks) + ")");
  if (static_cast<uint64_t>(natoms) > c.left() / (cols * sizeof(double)))
    c.fail("the header says " + std::to_string(natoms) + " particles, the file holds " +
           std::to_string(bytes.size()) + " bytes (truncated snapshot?)");
  const size_t n = static_cast<size_t>(natoms);
  for (auto* a :
       {&snap.x, &snap.y, &snap.z, &snap.vx, &snap.vy, &snap.vz, &snap.mass, &snap.radius})
    a->resize(n);
  snap.stress.resize(n);
  size_t i = 0;
  for (int32_t k = 0; k < chunks; ++k) {
    const std::string what =
        "rank chunk " + std::to_string(k + 1) + " of " + std::to_string(chunks);
    const int32_t values = c.get<int32_t>(what);
    if (values < 0 || values % cols != 0)
      c.fail(what + " holds " + std::to_string(values) + " values, not a multiple of " +
             std::to_string(cols));
    const size_t rows = static_cast<size_t>(values / cols);
    if (rows > n - i)
      c.fail("the chunks hold more particles than the header's " + std::to_string(n));
    const char* data = c.take(rows * cols * sizeof(double), what);
    double r[kSnapshotColumnCount];
    for (size_t j = 0; j < rows; ++j, ++i) {
      std::memcpy(r, data + j * sizeof(r), sizeof(r));
      snap.x[i] = r[kColX];
      snap.y[i] = r[kColY];
      snap.z[i] = r[kColZ];
      snap.vx[i] = r[kColVx];
      snap.vy[i] = r[kColVy];
      snap.vz[i] = r[kColVz];
      snap.mass[i] = r[kColMass];
      snap.radius[i] = r[kColRadius];
      for (int s = 0; s < 6; ++s) snap.stress[i][s] = r[kColStress1 + s];
    }
  }
  if (i != n)
    c.fail("the chunks hold " + std::to_string(i) + " particles, the header says " +
           std::to_string(n) + " (truncated snapshot?)");
  if (c.left() != 0) c.fail(std::to_string(c.left()) + " bytes after the last chunk");
  checkParticles(snap);
  return snap;
}

}  // namespace mixflow::mx
