// The fluid half of a dam-break scene, read from the same case directory as the DEM half:
//   constant/sceneProperties  content, sample, channel (shared with mixflowDem), liquid { ... }
//   system/cfdDict            mesh and solver numerics of mixflowFoam, observables
//   system/controlDict        endTime, writeInterval (the user's; never rewritten)
// Every entry is validated on reading (file, entry, allowed range); defaults are listed in
// docs/parameters.md (liquid scenes). Units are SI as in docs/model.md §5 (Pa, Pa s^n, kg/m3);
// OpenFOAM's kinematic inputs are derived from them by writeFoamCase (FoamCaseWriter.h).
#pragma once

#include <string>

#include "BulkModel.h"

namespace mixflow::cfd {

struct LiquidSample {
  double length = 0;              // L along x (m), from the back wall x = 0 to the gate
  double height = 0;              // H along y (m)
  double width = 0;               // W along z (m): the channel width (side walls at z = 0, W)
  double solidFraction = 0.6056;  // the grains of a mixture (the DEM half's, or the bulk model's)
};

struct LiquidChannel {
  double length = 0;                // x extent (m): outlet at x = length
  double height = 0;                // y extent (m): atmosphere at y = height
  std::string sideWalls = "walls";  // walls (no-slip) | periodic (cyclic z faces, 3-D only)
};

// Rheology in SI units (docs/model.md §5): tau = tau_c + kappa gamma_dot^n.
struct Rheology {
  std::string model;        // Newtonian | HerschelBulkley | Bingham
  double density = 0;       // rho (kg/m3)
  double viscosity = 0;     // Newtonian dynamic viscosity mu (Pa s)
  double yieldStress = 0;   // tau_c (Pa)
  double consistency = 0;   // kappa (Pa s^n); Bingham: the plastic viscosity (Pa s)
  double flowIndex = 1;     // n
  double viscosityCap = 0;  // regularisation mu_0 (Pa s): apparent viscosity never above it
  bool yieldStressModel() const { return model != "Newtonian"; }
  // OpenFOAM's kinematic coefficients (HerschelBulkley viscosity model).
  double nu() const { return viscosity / density; }
  double tau0() const { return yieldStress / density; }
  double k() const { return consistency / density; }
  double nu0() const { return viscosityCap / density; }
};

struct AirProperties {
  double density = 1.0;        // kg/m3 (docs/model.md §4)
  double viscosity = 1.48e-5;  // Pa s (Table 2 gives kappa = 1.48e-5 with n = 1)
};

struct CfdNumerics {
  int dimensions = 3;        // 3: the paper's channel with side walls; 2: one cell across W (empty)
  double cellSize = 0;       // m; 0 = auto (H / 20)
  double maxCo = 0.5;        // flow Courant number limit of the adaptive time step
  double maxAlphaCo = 0.5;   // interface Courant number limit
  double deltaT = 1e-4;      // first time step (s); adapted from then on
  double maxDeltaT = 0.01;   // largest time step (s)
  int nCorrectors = 0;       // PISO pressure correctors per outer iteration; 0 = auto (below)
  int nOuterCorrectors = 1;  // PIMPLE outer iterations
  // On: the viscous term is then implicit in U. Off (interFoam's damBreak) lags it in PISO's
  // H(U), which holds a capped yield-stress liquid (mu up to viscosityCap) nearly still.
  bool momentumPredictor = true;
  std::string momentumScheme = "linearUpwind";  // linearUpwind | upwind | limitedLinearV
  double pressureTolerance = 0;   // p_rgh absolute tolerance (final: relTol 0); 0 = auto (below)
  double alphaTolerance = 1e-10;  // implicit alpha predictor: its residual is the only volume error
  std::string writeFormat = "ascii";  // ascii | binary
  // A mixture's model: cfdDem (grains by LIGGGHTS, mixflowCoupled) or bulk (the quasi two-phase
  // bulk model, mixflowBulkFoam; constant/bulkProperties).
  std::string mixtureModel = "cfdDem";
};

struct ObservableSpec {
  double frontThreshold = 0.5;  // alpha_l >= this counts as liquid (docs/model.md §8)
  double sectionX = 1.38;  // Froude section x (m) (Li & Zhao Eq. 15); -1: none (outside channel)
  double minDepth = 0;     // m; below it the section Froude number is not defined; 0 = auto
  // h of Fr = v / sqrt(g h): the liquid surface height ("surface": the flow depth one sees, the
  // pores of a saturated granular layer counted full) or the liquid volume depth ("volume").
  // The two agree without particles.
  std::string froudeDepth = "surface";
};

struct LiquidCase {
  std::string caseDir;
  std::string name;
  std::string content;  // liquid | mixture
  LiquidSample sample;
  LiquidChannel channel;
  Rheology liquid;
  AirProperties air;
  double surfaceTension = 0.07;  // N/m (water-air; the paper gives none)
  CfdNumerics numerics;
  ObservableSpec observables;
  double endTime = 0;
  double writeInterval = 0;
  // Mixture scenes (set by mixflowPrepare from the settled sample and couplingProperties): the
  // CFD step is fixed at exchangeEvery x DEM step and the solver is mixflowCoupled. 0: liquid.
  double coupledDeltaT = 0;
  BulkModel bulk;  // mixtureModel bulk only
  bool bulkModel() const { return content == "mixture" && numerics.mixtureModel == "bulk"; }
  // Density of the non-air phase: the liquid's, or the bulk model's mixture density rho*.
  double phaseDensity() const { return bulkModel() ? bulk.mixtureDensity : liquid.density; }

  // Mesh derived from the cell size: uniform cells fitted to the channel.
  int nx = 0, ny = 0, nz = 0;
  double dx() const { return channel.length / nx; }
  double dy() const { return channel.height / ny; }
  double dz() const { return sample.width / nz; }
  // The viscous number D = mu_max dt / (rho dx_min^2): the viscous term's neighbour coefficients
  // over the unsteady diagonal, i.e. how much of the velocity correction PISO's diagonal-only
  // pressure step leaves to the next corrector. mu_max is the Newtonian viscosity or the
  // regularisation cap; dt the coupled step, else maxDeltaTUsed (the adaptive step's bound, reached
  // where a capped liquid is near rest).
  double viscousNumber() const;
  // Pa s: the Newtonian viscosity or the regularisation cap (bulk: BulkModel::maxViscosity)
  double maxViscosity() const;
  double minCellSize() const;  // m: the smallest cell edge (z only in 3-D)
  // nCorrectors as written to fvSolution: the user's, or for `auto` 3 up to
  // kViscousNumberFewCorrectors and 10 above (bench/piso_correctors.py, docs/parameters.md).
  int nCorrectorsUsed() const;
  static constexpr double kViscousNumberFewCorrectors = 20;
  // p_rgh tolerance as written to fvSolution: the user's, or for `auto`
  // kPressureTolerance x min(1, kViscousNumberFewCorrectors / D)^2, at least
  // kPressureToleranceMin. The solver's residual is normalised over the whole domain, where the
  // air's fluxes dominate; a capped yield-stress liquid's continuity is then left unconverged
  // and an arrested slump restarts by itself (measured: tests/cfd yield-arrest-*).
  double pressureToleranceUsed() const;
  static constexpr double kPressureTolerance = 1e-7;
  static constexpr double kPressureToleranceMin = 1e-12;
  // The largest viscous number measured to hold an arrested slump with the tolerance at its
  // floor (tau_y 100 Pa on 2.5 mm cells, D = 1.6e4); maxDeltaTUsed keeps a liquid run below it.
  static constexpr double kViscousNumberMax = 1.6e4;
  // maxDeltaT as written to controlDict: the user's, lowered for a liquid run so that the
  // viscous number stays <= kViscousNumberMax (a coupled run's step is exchangeEvery x the DEM
  // step; describe() warns there instead).
  double maxDeltaTUsed() const;
  double minDepthUsed() const {
    return observables.minDepth > 0 ? observables.minDepth : 0.5 * dy();
  }

  static LiquidCase read(const std::string& caseDir);
};

}  // namespace mixflow::cfd
