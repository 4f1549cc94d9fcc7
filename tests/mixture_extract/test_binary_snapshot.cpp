// Binary snapshot reader (mixture_extract/BinarySnapshot.cpp) against files written here with the
// layout of dem/SnapshotFiles.h: one and two rank chunks, the binary twin preferred over the .vtk
// (SnapshotSeries.cpp), and broken files (truncated, another column count, chunks against the
// header) refused with the file named. Values are copied bytes, so they compare exactly.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <vector>

#include "BinarySnapshot.h"
#include "Dictionary.h"
#include "SnapshotFiles.h"
#include "SnapshotSeries.h"

using namespace mixflow::mx;
using namespace mixflow::dem;
namespace fs = std::filesystem;

namespace {

// Particle i's row: every column a distinct value that no decimal text keeps exactly.
std::vector<double> row(int i) {
  std::vector<double> r(kSnapshotColumnCount);
  for (int c = 0; c < kSnapshotColumnCount; ++c) r[c] = (i + 1) * 1.0 / 3.0 + c * 0.1;
  r[kColId] = i + 1;
  r[kColType] = 1;
  r[kColRadius] = 0.006 + 1e-9 * i;
  r[kColMass] = 2.1e-6 + 1e-12 * i;
  return r;
}

template <class T>
void put(std::ofstream& f, T v) {
  f.write(reinterpret_cast<const char*>(&v), sizeof v);
}

// A dump of particles 0..n-1 split into the given rank chunk sizes; cols: values per particle.
fs::path writeDump(const std::string& name, const std::vector<int>& chunks, int triclinic = 0,
                   int cols = kSnapshotColumnCount) {
  const fs::path p = fs::temp_directory_path() / ("mixflow_binsnap_" + name);
  std::ofstream f(p, std::ios::binary);
  int64_t n = 0;
  for (int c : chunks) n += c;
  put<int64_t>(f, 4000);
  put<int64_t>(f, n);
  put<int32_t>(f, triclinic);
  for (int k = 0; k < 6; ++k) put<int32_t>(f, 1);
  for (int k = 0; k < (triclinic ? 9 : 6); ++k) put<double>(f, k * 0.5);
  put<int32_t>(f, cols);
  put<int32_t>(f, static_cast<int32_t>(chunks.size()));
  int i = 0;
  for (int c : chunks) {
    put<int32_t>(f, c * cols);
    for (int j = 0; j < c; ++j, ++i) {
      std::vector<double> r = row(i);
      r.resize(cols, 0.5);
      for (double v : r) put<double>(f, v);
    }
  }
  return p;
}

void expectRows(const ParticleSnapshot& s, int n) {
  ASSERT_EQ(s.size(), static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    const std::vector<double> r = row(i);
    EXPECT_EQ(s.x[i], r[kColX]);
    EXPECT_EQ(s.y[i], r[kColY]);
    EXPECT_EQ(s.z[i], r[kColZ]);
    EXPECT_EQ(s.vx[i], r[kColVx]);
    EXPECT_EQ(s.vy[i], r[kColVy]);
    EXPECT_EQ(s.vz[i], r[kColVz]);
    EXPECT_EQ(s.radius[i], r[kColRadius]);
    EXPECT_EQ(s.mass[i], r[kColMass]);
    for (int k = 0; k < 6; ++k) EXPECT_EQ(s.stress[i][k], r[kColStress1 + k]);
  }
}

// The InputError message of reading path, "" when it reads.
std::string errorOf(const fs::path& path) {
  try {
    readBinarySnapshot(path.string(), 0.1);
  } catch (const mixflow::InputError& e) {
    return e.what();
  }
  return "";
}

void truncate(const fs::path& p, uintmax_t bytesOff) {
  fs::resize_file(p, fs::file_size(p) - bytesOff);
}

}  // namespace

TEST(BinarySnapshot, OneChunk) {
  const ParticleSnapshot s = readBinarySnapshot(writeDump("one.bin", {7}).string(), 0.25);
  EXPECT_EQ(s.time, 0.25);
  expectRows(s, 7);
}

TEST(BinarySnapshot, TwoRankChunksInFileOrder) {
  expectRows(readBinarySnapshot(writeDump("two.bin", {5, 3}).string(), 0), 8);
}

TEST(BinarySnapshot, EmptyRankChunkAndEmptyDump) {
  expectRows(readBinarySnapshot(writeDump("gap.bin", {0, 4}).string(), 0), 4);
  expectRows(readBinarySnapshot(writeDump("none.bin", {0, 0}).string(), 0), 0);
}

TEST(BinarySnapshot, TriclinicHeaderSkipped) {
  expectRows(readBinarySnapshot(writeDump("tri.bin", {2, 2}, 1).string(), 0), 4);
}

TEST(BinarySnapshot, TruncatedFileNamedNotACrash) {
  // Cut inside the second chunk's values, inside its count, and inside the header.
  for (uintmax_t cut : {8u, 3u * 8 * kSnapshotColumnCount + 2, 100u}) {
    const fs::path p = writeDump("cut.bin", {3, 3});
    truncate(p, cut);
    const std::string e = errorOf(p);
    EXPECT_NE(e.find(p.string()), std::string::npos) << e;
    EXPECT_NE(e.find("truncated"), std::string::npos) << e;
  }
  const fs::path empty = fs::temp_directory_path() / "mixflow_binsnap_empty.bin";
  std::ofstream(empty).close();
  EXPECT_NE(errorOf(empty).find(empty.string() + ": file ends inside the header"),
            std::string::npos);
}

TEST(BinarySnapshot, OtherColumnsAndBadChunksRefused) {
  const fs::path p = writeDump("cols.bin", {2}, 0, 9);
  EXPECT_NE(errorOf(p).find("9 values per particle, expected 22"), std::string::npos) << errorOf(p);
  // A file with one byte more than its chunks hold.
  const fs::path extra = writeDump("extra.bin", {2, 1});
  std::ofstream(extra, std::ios::binary | std::ios::app).put('x');
  EXPECT_NE(errorOf(extra).find("1 bytes after the last chunk"), std::string::npos);
  EXPECT_THROW(readBinarySnapshot("/nonexistent/particles_0.bin", 0), mixflow::InputError);
}

TEST(BinarySnapshot, TwinPreferredOverVtk) {
  const fs::path dir = fs::temp_directory_path() / "mixflow_binsnap_case";
  fs::create_directories(dir);
  const fs::path vtk = dir / "particles_40.vtk";
  std::ofstream(vtk) << "# vtk DataFile Version 5.1\nnot read\nASCII\n";
  fs::copy_file(writeDump("twin.bin", {2, 2}), binarySnapshotPath(vtk.string()),
                fs::copy_options::overwrite_existing);
  EXPECT_EQ(fs::path(binarySnapshotPath(vtk.string())), dir / "particles_40.bin");
  const SnapshotEntry e{vtk.string(), 0.4};
  EXPECT_TRUE(snapshotExists(e));
  expectRows(readSnapshot(e), 4);
  // Without the twin, the (broken) .vtk is read and its error names it.
  fs::remove(dir / "particles_40.bin");
  try {
    readSnapshot(e);
    ADD_FAILURE() << "the .vtk stand-in has no POINTS and must be refused";
  } catch (const mixflow::InputError& err) {
    EXPECT_NE(std::string(err.what()).find(vtk.string()), std::string::npos);
  }
}
