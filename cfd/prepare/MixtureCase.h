// The mixture half of mixflowPrepare (content mixture, physics.md section 1): the settled particle
// sample (mixflowDem -settleOnly: dem/settled.state) saturated with liquid up to its top, the gate
// removed at t = 0, run by mixflowCoupled.
//   - the liquid fills [0, L] x [0, settled height] (c.sample.height is set to it);
//   - the CFD step is fixed at exchangeEvery (constant/couplingProperties) x the DEM step
//     (system/demDict), the controlDict then names mixflowCoupled;
//   - system/in.liggghts (the couplingProperties' demScript) restarts LIGGGHTS from the settled
//     sample (saved at step 0) with the scene's contacts and walls but no gate.
#pragma once

#include <ostream>
#include <string>

#include "LiquidCase.h"

namespace mixflow::cfd {

struct MixtureSetup {
  long particles = 0;
  double settledHeight = 0;   // m: the liquid's initial height
  double demTimeStep = 0;     // s
  long exchangeEvery = 0;     // DEM steps per CFD step
  std::string demScriptPath;  // where the DEM script is written
  std::string demScript;      // its text
};

// Reads the DEM scene, the settled state and couplingProperties; updates c (fill height, fixed
// CFD step). Throws InputError naming the file and entry when something is missing or invalid.
MixtureSetup prepareMixture(LiquidCase& c);
void writeMixtureDemScript(const MixtureSetup& m);
void describeMixture(const MixtureSetup& m, const LiquidCase& c, std::ostream& os);

}  // namespace mixflow::cfd
