// Particle snapshots as mixflowDem's LIGGGHTS `dump custom/vtk` writes them: legacy VTK 5.1 ASCII
// POLYDATA files VTK/particles/particles_<step>.vtk, numbers with 6 significant digits. Arrays
// read: POINTS, id, mass, radius, v, c_pstress[1-3], c_pstress[4-6] (ParticleSnapshot.h).
#pragma once

#include <string>

#include "ParticleSnapshot.h"

namespace mixflow::mx {

// Reads one snapshot file. Throws InputError naming the file and the missing/broken array.
ParticleSnapshot readVtkSnapshot(const std::string& path, double time);

}  // namespace mixflow::mx
