// Where the particle snapshots of a run are and what each one holds. Every step writeInterval
// apart, LIGGGHTS dumps the same columns twice into <case>/VTK/particles/:
//   particles_<step>.vtk  dump custom/vtk: legacy VTK ASCII for ParaView, indexed by
//                         VTK/particles.vtk.series (numbers written with 6 significant digits)
//   particles_<step>.bin  dump custom with a .bin name: LAMMPS' binary dump, full precision,
//                         written when demDict binarySnapshots is on
// Binary layout (native byte order, as LIGGGHTS 3.8 DumpCustom::header_binary/write_binary):
//   int64 step, int64 natoms, int32 triclinic, int32 boundary[6], float64 box[6] (+3 if triclinic),
//   int32 columns (= kSnapshotColumnCount), int32 chunks (MPI ranks), then per chunk:
//   int32 n (values, a multiple of columns), n float64 (one row of columns per particle).
// The Python twin of this layout is python/mixflow/outputs.py (SNAPSHOT_*): keep them consistent.
#pragma once

#include <string>

namespace mixflow::dem {

// Column order of both dumps (the binary file names none, so the reader relies on it).
enum SnapshotColumn {
  kColId,
  kColType,
  kColX,
  kColY,
  kColZ,
  kColVx,
  kColVy,
  kColVz,
  kColFx,
  kColFy,
  kColFz,
  kColOmegaX,
  kColOmegaY,
  kColOmegaZ,
  kColRadius,
  kColMass,
  kColStress1,  // c_pstress[1..6]: xx yy zz xy xz yz
  kSnapshotColumnCount = kColStress1 + 6
};

// The dump custom argument list in SnapshotColumn order.
const std::string& snapshotColumns();

// <caseDir>/VTK/particles/particles_*.<ext> ('*' is LIGGGHTS' step placeholder); ext vtk or bin.
std::string snapshotPattern(const std::string& caseDir, const std::string& ext);

// The binary twin of a snapshot .vtk path (same directory and step, extension .bin).
std::string binarySnapshotPath(const std::string& vtkPath);

// Deletes <caseDir>/VTK/particles/particles_*.bin (left by an earlier run).
void removeBinarySnapshots(const std::string& caseDir);

}  // namespace mixflow::dem
