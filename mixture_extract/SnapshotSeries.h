// The particle snapshots of a case: the list in VTK/particles.vtk.series (ParaView's index of the
// .vtk files), and for each one the file to read: its binary twin particles_<step>.bin when the DEM
// wrote one (BinarySnapshot.h: faster, not rounded), else the .vtk file (VtkSnapshot.h).
#pragma once

#include <string>
#include <vector>

#include "ParticleSnapshot.h"

namespace mixflow::mx {

struct SnapshotEntry {
  std::string file;  // absolute or case-relative path of the .vtk file (listed in the series)
  double time = 0;
};

// Reads <caseDir>/VTK/particles.vtk.series, sorted by time. Throws InputError naming the file on
// any problem.
std::vector<SnapshotEntry> readSnapshotSeries(const std::string& caseDir);

// The snapshot of an entry, from its binary twin when there is one, else from the .vtk file.
ParticleSnapshot readSnapshot(const SnapshotEntry& e);

// True when the entry's .vtk or its binary twin is a file.
bool snapshotExists(const SnapshotEntry& e);

}  // namespace mixflow::mx
