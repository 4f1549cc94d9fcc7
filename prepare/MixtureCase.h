// The mixture half of mixflowPrepare (content mixture, docs/model.md §1): the settled particle
// sample (mixflowDem -settleOnly: dem/settled.state) saturated with liquid up to its top, the gate
// removed at t = 0, run by mixflowCoupled.
//   - the liquid fills [0, L] x [0, settled height] (c.sample.height is set to it);
//   - the CFD step is fixed at exchangeEvery (constant/couplingProperties) x the DEM step
//     (system/demDict), the controlDict then names mixflowCoupled;
//   - system/in.liggghts (the couplingProperties' demScript) restarts LIGGGHTS from the settled
//     sample (saved at step 0) with the scene's contacts and walls but no gate.
// Rules checked before anything runs (docs/parameters.md, "Mixture scenes"; each refusal names
// file, entry and allowed range, each warning its reason):
//   - cells against grains: the smallest cell edge (z only in 3-D) below kCellDiametersMin
//     particle diameters is refused, below kCellDiametersWarn warned (unresolved coupling averages
//     the grains over cells of a few diameters);
//   - the coupled step's Courant number estimate Co = dt U / min(dx, dy), dt = exchangeEvery x DEM
//     step and U = 2 sqrt(g H) the dam-break front speed (Ritter), H the fill height: above
//     kCourantMax refused, above cfdDict maxCo warned; the CFD step must not exceed writeInterval;
//   - the held drag's relaxation number s = beta T / m of a lone grain settling at its Di Felice
//     terminal velocity u_t in the liquid (beta = (m - m_f) g / u_t; a yield-stress liquid at its
//     viscosity cap): with dragIntegration held and no dragRelaxationLimit, s above
//     kHeldRelaxationMax / n (n = d ln F / d ln u at the terminal Reynolds number) is refused for a
//     Newtonian liquid and warned for a capped one (the settling speed oscillates and grows,
//     results/stability); with a limit, s above it is warned (the drag is clamped to limit x m / T
//     and the grain settles too fast). The implicit drag is stable at any s.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "LiquidCase.h"

namespace mixflow::cfd {

inline constexpr double kCellDiametersMin = 1.0;
inline constexpr double kCellDiametersWarn = 3.0;
inline constexpr double kCourantMax = 1.0;
// The largest linearised relaxation number n beta T / m (n = d ln F / d ln u of the drag) at
// which a drag held over the exchange interval settles a lone grain at its terminal velocity
// (results/stability/drag_interval.csv).
inline constexpr double kHeldRelaxationMax = 2.0;

struct MixtureSetup {
  bool settled = false;      // false: checked before the settling (the scene's nominal sample)
  long particles = 0;        // settled count, else the nominal phi L H W / V_p
  double settledHeight = 0;  // m: the liquid's initial height (the nominal H before settling)
  double diameter = 0;       // m: particle diameter
  double demTimeStep = 0;    // s
  long exchangeEvery = 0;    // DEM steps per CFD step
  double frontSpeed = 0;     // m/s: 2 sqrt(g H), the velocity scale of the Courant estimate
  double courant = 0;        // CFD step x frontSpeed / min(dx, dy)
  double relaxation = 0;     // beta T / m of a lone grain at its terminal velocity
  std::vector<std::string> warnings;
  std::vector<std::string> notes;  // departures the case states a reason for (coarseCellsReason)
  std::string demScriptPath;       // where the DEM script is written
  std::string demScript;           // its text (prepareMixture only)
  std::string gateStl;             // a lifted gate's plate, else empty
  std::string gateStlPath;         // where it is written: <case>/dem/gate.stl
};

// Everything of a mixture scene that does not need the settled sample, at the fill height
// c.sample.height (the scene's nominal H): the DEM scene (sceneProperties particles, demDict),
// couplingProperties with the force and void-fraction models it names (built as mixflowCoupled
// builds them), the coupled step (writeInterval, Courant estimate) and the cells against the
// grains. Sets c.coupledDeltaT. Throws InputError naming the file and entry.
MixtureSetup checkMixture(LiquidCase& c);
// The same at the settled sample's height (dem/settled.state, settled from the case's DEM
// inputs), and the DEM restart script. Updates c (fill height, fixed CFD step).
MixtureSetup prepareMixture(LiquidCase& c);
void writeMixtureDemScript(const MixtureSetup& m);
void describeMixture(const MixtureSetup& m, const LiquidCase& c, std::ostream& os);

}  // namespace mixflow::cfd
