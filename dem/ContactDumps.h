// Contact-level snapshots for the coarse-grained stress of mixflowExtract, written at the steps of
// the particle snapshots when demDict contactSnapshots is on, into <case>/VTK/contacts/:
//   pairs_<step>.txt  LIGGGHTS `dump local` of `compute pair/gran/local id force`: per contact
//                     id1 id2 periodic fx fy fz, the force on particle id1 by id2 (periodic: 1 when
//                     the pair meets across a periodic boundary); positions come from the snapshot
//   walls_<step>.txt  `dump custom`: id and f_force_<wall>[1-3] for each wall of wallPlanes(), the
//                     force of that wall on the particle (fix wall/gran store_force), for particles
//                     whose centre is within a radius of a wall plane. LIGGGHTS keeps a wall's last
//                     force after the contact ends, so a reader counts a wall's force only where
//                     the sphere overlaps that plane.
// (compute wall/gran/local of LIGGGHTS 3.8 takes mesh walls only; the channel's walls are
// primitive.)
#pragma once

#include <string>
#include <vector>

#include "Scene.h"

namespace mixflow::dem {

struct WallPlane {
  std::string id;  // the fix wall/gran id
  int axis;        // 0 x, 1 y, 2 z: the plane axis = position
  double position;
};

// The walls standing while snapshots are written (after the gate opens).
std::vector<WallPlane> wallPlanes(const Scene& s);

// Appended to a fix wall/gran command when contact snapshots are on: stores the wall's force.
std::string wallForceOption(const Scene& s);

// The compute issued with the contact model; LIGGGHTS needs it before the first run.
std::string pairContactCompute(const Scene& s);

// The dump commands, every `every` steps (the particle snapshots' interval).
std::vector<std::string> contactDumpCommands(const Scene& s, long every);

// Deletes <case>/VTK/contacts/{pairs,walls}_*.txt left by an earlier run (the extractor would
// read them beside the new snapshots).
void removeContactDumps(const std::string& caseDir);

// Files of the snapshot whose .vtk (or .bin) path is given: VTK/particles/particles_<step>.vtk ->
// VTK/contacts/pairs_<step>.txt and walls_<step>.txt.
std::string pairContactPath(const std::string& snapshotPath);
std::string wallContactPath(const std::string& snapshotPath);

}  // namespace mixflow::dem
