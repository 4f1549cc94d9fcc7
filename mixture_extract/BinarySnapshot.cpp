#include "BinarySnapshot.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "Dictionary.h"
#include "SnapshotFiles.h"

namespace mixflow::mx {

namespace {

// Reads the file in blocks small enough to stay in the CPU cache while they are spread into the
// snapshot's arrays (a whole-file buffer would be copied through main memory once more).
class BlockReader {
 public:
  explicit BlockReader(const std::string& file) : file_(file) {
    f_ = std::fopen(file.c_str(), "rb");
    if (!f_) throw InputError(file + ": cannot open file (missing or unreadable)");
    std::setvbuf(f_, nullptr, _IONBF, 0);  // blocks go straight into our buffer
    std::error_code ec;
    size_ = std::filesystem::file_size(file, ec);
  }
  ~BlockReader() { std::fclose(f_); }
  BlockReader(const BlockReader&) = delete;
  BlockReader& operator=(const BlockReader&) = delete;

  void read(void* to, size_t n, const std::string& what) {
    if (std::fread(to, 1, n, f_) != n)
      fail("file ends inside " + what + " (" + std::to_string(size_) +
           " bytes; truncated snapshot?)");
    done_ += n;
  }
  template <class T>
  T get(const std::string& what) {
    T v;
    read(&v, sizeof v, what);
    return v;
  }
  uintmax_t left() const { return size_ > done_ ? size_ - done_ : 0; }
  uintmax_t size() const { return size_; }
  [[noreturn]] void fail(const std::string& why) const { throw InputError(file_ + ": " + why); }

 private:
  const std::string& file_;
  std::FILE* f_ = nullptr;
  uintmax_t size_ = 0, done_ = 0;
};

constexpr size_t kBlockRows = 1024;  // 176 kB a block

}  // namespace

ParticleSnapshot readBinarySnapshot(const std::string& path, double time) {
  using namespace dem;
  BlockReader in(path);
  ParticleSnapshot snap;
  snap.time = time;
  snap.file = path;
  const std::string header = "the header";
  in.get<int64_t>(header);  // LIGGGHTS step (the series gives the time)
  const int64_t natoms = in.get<int64_t>(header);
  const int32_t triclinic = in.get<int32_t>(header);
  if (natoms < 0 || (triclinic != 0 && triclinic != 1))
    in.fail("not a LIGGGHTS binary dump (particle count " + std::to_string(natoms) +
            ", triclinic flag " + std::to_string(triclinic) + ")");
  char skip[6 * sizeof(int32_t) + 9 * sizeof(double)];  // boundary flags, box
  in.read(skip, 6 * sizeof(int32_t) + (triclinic ? 9 : 6) * sizeof(double), header);
  const int32_t cols = in.get<int32_t>(header);
  const int32_t chunks = in.get<int32_t>(header);
  if (cols != kSnapshotColumnCount)
    in.fail(std::to_string(cols) + " values per particle, expected " +
            std::to_string(kSnapshotColumnCount) + " (" + snapshotColumns() +
            "): not a mixflowDem snapshot");
  if (chunks < 1) in.fail("no rank chunks (" + std::to_string(chunks) + ")");
  if (static_cast<uint64_t>(natoms) > in.left() / (cols * sizeof(double)))
    in.fail("the header says " + std::to_string(natoms) + " particles, the file holds " +
            std::to_string(in.size()) + " bytes (truncated snapshot?)");
  const size_t n = static_cast<size_t>(natoms);
  snap.resize(n);
  std::vector<double> block(kBlockRows * kSnapshotColumnCount);
  size_t i = 0;
  for (int32_t k = 0; k < chunks; ++k) {
    const std::string what =
        "rank chunk " + std::to_string(k + 1) + " of " + std::to_string(chunks);
    const int32_t values = in.get<int32_t>(what);
    if (values < 0 || values % cols != 0)
      in.fail(what + " holds " + std::to_string(values) + " values, not a multiple of " +
              std::to_string(cols));
    size_t rows = static_cast<size_t>(values / cols);
    if (rows > n - i)
      in.fail("the chunks hold more particles than the header's " + std::to_string(n));
    while (rows > 0) {
      const size_t m = std::min(rows, kBlockRows);
      in.read(block.data(), m * cols * sizeof(double), what);
      for (size_t j = 0; j < m; ++j, ++i) {
        const double* r = block.data() + j * kSnapshotColumnCount;
        snap.id[i] = std::lround(r[kColId]);
        snap.x[i] = r[kColX];
        snap.y[i] = r[kColY];
        snap.z[i] = r[kColZ];
        snap.vx[i] = r[kColVx];
        snap.vy[i] = r[kColVy];
        snap.vz[i] = r[kColVz];
        snap.mass[i] = r[kColMass];
        snap.radius[i] = r[kColRadius];
        for (int c = 0; c < 6; ++c) snap.stress[i][c] = r[kColStress1 + c];
      }
      rows -= m;
    }
  }
  if (i != n)
    in.fail("the chunks hold " + std::to_string(i) + " particles, the header says " +
            std::to_string(n) + " (truncated snapshot?)");
  if (in.left() != 0) in.fail(std::to_string(in.left()) + " bytes after the last chunk");
  checkParticles(snap);
  return snap;
}

}  // namespace mixflow::mx
