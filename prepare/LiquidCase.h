// The fluid half of a dam-break scene, read from the same case directory as the DEM half:
//   constant/sceneProperties  content, sample, channel (shared with mixflowDem), liquid { ... }
//   system/cfdDict            mesh and solver numerics of mixflowFoam, observables
//   system/controlDict        endTime, writeInterval (the user's; never rewritten)
// Every entry is validated on reading (file, entry, allowed range); defaults are listed in
// docs/parameters.md (liquid scenes; the sceneProperties and cfdDict tables are printed from
// their declarations in common/). Units are SI as in docs/model.md §5 (Pa, Pa s^n, kg/m3);
// OpenFOAM's kinematic inputs are derived from them by writeFoamCase (FoamCaseWriter.h).
#pragma once

#include <string>

#include "BulkModel.h"
#include "CfdDict.h"
#include "SceneProperties.h"

namespace mixflow::cfd {

// The scene's entries (sceneProperties) are common to both halves: SceneProperties.h.
using LiquidSample = SampleSpec;
using LiquidChannel = ChannelSpec;
using mixflow::AirProperties;
using mixflow::GateSpec;
using mixflow::Rheology;

// cfdDict's entries: CfdDict.h.
using mixflow::CfdNumerics;
using mixflow::ObservableSpec;

struct LiquidCase {
  std::string caseDir;
  std::string name;
  std::string content;  // liquid | mixture
  LiquidSample sample;
  LiquidChannel channel;
  Rheology liquid;
  AirProperties air;
  GateSpec gate;              // sceneProperties gate; thickness resolved (auto: two cells)
  double surfaceTension = 0;  // N/m (liquid.surfaceTension)
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

  // Cells along x of a lifted gate's plate, the least and the default (LiquidCase::read).
  static constexpr int kGatePlateCells = 2;

  static LiquidCase read(const std::string& caseDir);
};

}  // namespace mixflow::cfd
