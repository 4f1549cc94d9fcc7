// One particle snapshot as the extractor bins it, whichever file it came from (VtkSnapshot.h,
// BinarySnapshot.h; SnapshotSeries.h picks the file).
//
// Quantities (LIGGGHTS quantity in brackets):
//   x, y, z [x y z]; id [id]; mass [mass]; radius [radius]; v [vx vy vz];
//   c_pstress[1-3], c_pstress[4-6] [compute stress/atom: xx yy zz, xy xz yz], units N m (stress x
//   volume), LAMMPS sign: the NEGATIVE of the per-atom pressure tensor times volume,
//   S_i = -(m v v + W_i) when the compute has the kinetic term (plain `compute ID all stress/atom`,
//   as mixflowDem issues it) and S_i = -W_i when it was created with `pair` only; W_i is particle
//   i's half of the pair virial sum_j r_ij (x) F_ij. Wall contacts (fix wall/gran) add no per-atom
//   virial in LIGGGHTS 3.8, so they are not in S_i.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace mixflow::mx {

struct ParticleSnapshot {
  double time = 0;
  std::string file;
  std::vector<double> x, y, z;                // centre (m)
  std::vector<double> vx, vy, vz;             // velocity (m/s)
  std::vector<double> mass;                   // kg
  std::vector<double> radius;                 // m
  std::vector<std::array<double, 6>> stress;  // c_pstress: xx yy zz xy xz yz (N m, LAMMPS sign)
  std::vector<long> id;                       // LIGGGHTS atom id (the contact dumps name these)
  size_t size() const { return x.size(); }
  void resize(size_t n);  // every per-particle array to n entries
};

// Throws InputError naming snap.file when a particle's radius or mass is not positive.
void checkParticles(const ParticleSnapshot& snap);

}  // namespace mixflow::mx
