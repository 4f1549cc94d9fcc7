// system/cfdDict: the mesh and solver numerics of mixflowFoam and the observables of a liquid or
// mixture scene. One declaration table (CfdDict.cpp) gives every entry; the defaults are the
// initializers below. The rules that need the scene (cells over H, the section inside the channel)
// are cfd::LiquidCase's.
#pragma once

#include <string>

#include "Dictionary.h"
#include "Schema.h"

namespace mixflow {

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
  // Why a mixture's cells are below the advised 3 particle diameters on purpose (empty: not on
  // purpose); the check then gives a note with this reason instead of a warning.
  std::string coarseCellsReason;
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

struct CfdDict {
  CfdNumerics numerics;
  ObservableSpec observables;

  static const Schema& schema();
  static CfdDict read(const Dictionary& cfdDict);
};

}  // namespace mixflow
