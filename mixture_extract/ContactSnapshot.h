// Contact forces of one particle snapshot (dem/ContactDumps.h): every particle pair in contact and
// every particle's contact with a wall plane, as the coarse-grained contact stress needs them.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "ContactDumps.h"

namespace mixflow::mx {

struct PairContact {
  long id1 = 0, id2 = 0;
  std::array<double, 3> force{};  // on id1 by id2 (N)
};

struct WallContact {
  long id = 0;
  int wall = 0;                   // index into ContactSnapshot::walls
  std::array<double, 3> force{};  // on the particle by the wall (N)
};

struct ContactSnapshot {
  std::vector<dem::WallPlane> walls;
  std::vector<PairContact> pairs;
  std::vector<WallContact> wallContacts;  // non-zero stored wall forces (overlap not yet checked)
};

// True when both contact files of the snapshot (its .vtk path) exist.
bool contactSnapshotExists(const std::string& snapshotPath);

// Reads pairs_<step>.txt and walls_<step>.txt beside the snapshot; walls are the planes the DEM
// wrote the forces of (dem::wallPlanes). Throws InputError naming the file on any problem.
ContactSnapshot readContactSnapshot(const std::string& snapshotPath,
                                    const std::vector<dem::WallPlane>& walls);

}  // namespace mixflow::mx
