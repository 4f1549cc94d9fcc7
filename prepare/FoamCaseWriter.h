// Writes the OpenFOAM files of a pure-liquid (or the liquid of a mixture) dam-break case for
// mixflowFoam from a validated LiquidCase. Files written (all overwritten; 0/ is recreated):
//   system/blockMeshDict   one uniform block [0, channel length] x [0, channel height] x [0, W]
//                          patches bottom, backWall, sideWalls (3-D walls) | sideFront/sideBack
//                          (3-D periodic) | frontAndBack (2-D empty), outlet (x = channel
//                          length), atmosphere (y = channel height)
//   system/controlDict.generated  everything but the case's own entries, from system/cfdDict,
//                          plus the liquidObservables function object (postProcessing/liquid/);
//                          system/controlDict (endTime, writeInterval: the user's) includes it
//                          and is not rewritten (the include is added once if missing)
//   system/fvSchemes, system/fvSolution, system/decomposeParDict (simple, ranks x 1 x 1)
//   constant/transportProperties (kinematic values from the SI input), constant/g,
//   constant/turbulenceProperties (laminar)
//   constant/fvOptions     a lifted gate (sceneProperties gate): mixflowFoam's liquidGate; removed
//                          when the gate is instant and the file is mixflowPrepare's
//   0/alpha.liquid (the sample box [0, L] x [0, H] filled exactly: partly covered cells get
//   their covered fraction), 0/U, 0/p_rgh
#pragma once

#include <ostream>
#include <string>

#include "LiquidCase.h"

namespace mixflow::cfd {

// Phase names in the OpenFOAM case: alpha.liquid is the liquid fraction of the fluid.
inline constexpr const char* kLiquidPhase = "liquid";
inline constexpr const char* kAirPhase = "air";

void writeFoamCase(const LiquidCase& c, int ranks);

// The solver the case runs: mixflowFoam (liquid), mixflowCoupled (mixture, cfdDem) or
// mixflowBulkFoam (mixture, bulk); controlDict's application and mixflowPrepare -solver.
std::string solverName(const LiquidCase& c);

// Liquid volume of the initial alpha field (sum alpha V over cells), for the report; equals
// L H W up to round-off because the sample box is filled exactly.
double initialLiquidVolume(const LiquidCase& c);

// One-paragraph summary: mesh, kinematic coefficients, time-step controls.
void describe(const LiquidCase& c, int ranks, std::ostream& os);

}  // namespace mixflow::cfd
