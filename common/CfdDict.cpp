#include "CfdDict.h"

namespace mixflow {

namespace {
std::string num(double v) { return formatNumber(v, 6); }

Schema makeSchema() {
  const CfdNumerics m{};
  const ObservableSpec o{};
  return Schema(
      "system/cfdDict",
      {
          integerParam(
              "dimensions", m.dimensions, 2, 3,
              "3: the paper's channel, walls at z = 0, W. 2: one cell across W with empty "
              "front/back (a slab of thickness W, so volumes and energies are those of the "
              "W-wide scene; no side-wall friction) — about 20-30× cheaper"),
          autoScalar("cellSize", Range::positive(), "m",
                     "the channel is cut into round(length/cellSize) uniform cells per direction. "
                     "Mixtures: below")
              .alsoAllowed("≥ 4 cells over H, ≤ 5e7 cells; mixtures ≥ 1 d (warned below 3 d)")
              .shownDefault("auto = H/20"),
          // Above 1 the MULES-bounded VOF scheme loses boundedness; interFoam tutorials use 0.5
          // to 1.
          scalarParam("maxCo", m.maxCo, Range::openClosed(0.0, 1.0), "",
                      "flow Courant number of the adaptive time step"),
          scalarParam("maxAlphaCo", m.maxAlphaCo, Range::openClosed(0.0, 1.0), "",
                      "interface Courant number of the adaptive time step"),
          scalarParam("deltaT", m.deltaT, Range::positive(), "s", "first time step")
              .alsoAllowed("≤ maxDeltaT"),
          scalarParam(
              "maxDeltaT", m.maxDeltaT, Range::positive(), "s",
              "A liquid run (not a coupled one) uses at most the step at which the viscous "
              "number D = μmax Δt/(ρ Δx²) is 1.6e4, the largest measured to hold an arrested "
              "Bingham slump (τy 100 Pa on 2.5 mm cells, `cfd.liquid.yield_arrest_*`); "
              "`mixflowPrepare` says when it lowers the bound. A coupled run above that D gets "
              "a warning"),
          autoInteger(
              "nCorrectors", 1, 20,
              "PISO correctors. **Choice** (auto): 3 when the viscous number D = μmax Δt/(ρ "
              "Δx²) is at most 20, else 10 (μmax: the Newtonian viscosity or the yield-stress "
              "cap μ0; Δt: the coupled step, else maxDeltaT; Δx: the smallest cell side; "
              "`mixflowPrepare` prints D and the choice). PISO corrects pressure with the "
              "momentum diagonal only; the viscous neighbours' share, D against 1, is left to "
              "the next corrector. Measured on a 2-D Newtonian column at fixed Δt (`python3 "
              "bench/piso_correctors.py --mu 1,5,25,100,250,500,1000,2500,10000 --correctors "
              "2,3,4,10,20`, results/bench/piso_correctors.csv), error of the front advance "
              "against 20 correctors: 3 correctors 0.08-0.7 % for D = 0.04-20 at 30-50 % less "
              "CPU than 10, 38 % at D = 40, diverged at D ≥ 100; 10 correctors ≤ 0.6 % up to D "
              "= 100 and the calmest run at D = 400, where 20 correctors burst (kinetic energy "
              "0.45 J against 1e-6 J) and 2-4 diverged: PISO without outer iterations is no "
              "converging iteration there, and 10 is a measured, not a proven, choice. The "
              "viscous-number rule picks the same as a rule by rheology (10 for every "
              "yield-stress liquid, 3 otherwise) for every committed pure-liquid case (D = "
              "40-3900 for HB, B, HB-I, B-I and the tiers; 1e-5 for water), but gives 10 to a "
              "viscous Newtonian liquid (μ = 1e3 Pa s blew up with 3) and 3 to the coupled "
              "yield-stress mixtures, whose step is short (paper stiffness D = 0.14; quick tier "
              "2.2 / 1.6 for HB / B): their results with 3 and 10 correctors are compared in "
              "results/mixtures/n_correctors/ and bench/README.md"),
          integerParam("nOuterCorrectors", m.nOuterCorrectors, 1, 50,
                       "PIMPLE outer iterations (3 did not cure the above)"),
          switchParam(
              "momentumPredictor", m.momentumPredictor,
              "**Choice**: off (interFoam's damBreak) lags the viscous term in PISO's H(U); a "
              "capped yield-stress column then barely moves for 0.3 s (ρgH/τc = 58). Harmless "
              "for water (Martin & Moyce fronts within 0.02 a of the run without it)"),
          wordParam("momentumScheme", m.momentumScheme,
                    {"linearUpwind", "upwind", "limitedLinearV"}, "div(rhoPhi,U)"),
          autoScalar(
              "pressureTolerance", Range::positive(), "",
              "p_rgh absolute tolerance (GAMG, relTol 0.01, final 0). **Choice** (auto): 1e-7 · "
              "min(1, 20/D)², at least 1e-12 (`mixflowPrepare` prints it): 1e-7 up to D = 20 "
              "(every water and coupled case), 2.5e-12 for a capped yield-stress liquid on 5 mm "
              "cells at Δt 0.01 s (D = 4000). The solver's residual is normalised over the "
              "whole domain, where the air's fluxes dominate, so a fixed 1e-7 leaves a capped "
              "liquid's continuity unconverged: an arrested Bingham slump then restarts by "
              "itself (τy 100 Pa, D = 4000: kinetic energy after arrest 11 E_p0; 1e-9 holds "
              "it). At D = 1.6e4, 1.25e-10 lets the front creep 8 % past the theory and 1e-11 "
              "still restarts (2e-5 E_p0), 1e-12 holds: the need grows as D², hence the square "
              "(tests `cfd.liquid.yield_arrest_20/50/100/convergence`)"),
          scalarParam(
              "alphaTolerance", m.alphaTolerance, Range::positive(), "",
              "implicit alpha predictor (MULESCorr): its residual is the only liquid-volume "
              "error (balance 2e-9 to 1.5e-8 measured)"),
          wordParam("writeFormat", m.writeFormat, {"ascii", "binary"}, "fields"),
          wordParam("mixtureModel", m.mixtureModel, {"cfdDem", "bulk"},
                    "a mixture's model: cfdDem (grains by LIGGGHTS, mixflowCoupled) or bulk (the "
                    "quasi two-phase bulk model, mixflowBulkFoam; constant/bulkProperties, below)"),
          textParam("coarseCellsReason", m.coarseCellsReason,
                    "a mixture whose cells are below 3 particle diameters on purpose (e.g. a "
                    "quick case's coarse mesh) says why here, in quotes; the check's warning "
                    "about those cells is then one note that gives this reason. Cells below 1 d "
                    "are refused all the same")
              .shownDefault("(none: warned)"),
          dictParam("observables", "what the liquidObservables function object measures"),
          scalarParam("observables.frontThreshold", o.frontThreshold, {0.0, 1.0, true, true}, "",
                      "α ≥ this counts as liquid (docs/model.md §8)"),
          scalarParam("observables.sectionX", o.sectionX, Range::positive(), "m",
                      "Froude section; if the default lies outside a short channel the section is "
                      "dropped")
              .alsoAllowed("< channel length"),
          autoScalar("observables.minDepth", Range::positive(), "m",
                     "below this depth Fr at the section is not defined (nan)")
              .shownDefault("auto = half a cell height"),
          wordParam(
              "observables.froudeDepth", o.froudeDepth, {"surface", "volume"},
              "h in Fr = v/√(g h) at the section (docs/model.md §8, \"h the liquid depth\"). "
              "**Open choice**: `surface` = the liquid surface height Σ α V / column area (the "
              "pores of a saturated granular layer counted full: the flow depth one sees, the "
              "paper's \"flow height\"); `volume` = the liquid volume depth Σ ε_f α V / area "
              "(about ε_f ≈ 0.4 times the surface height in a saturated mixture, so Fr is about "
              "1.6x larger). v is the mean liquid velocity (discharge / volume depth) either "
              "way; the two agree without particles. Both depths are in timeSeries.csv "
              "(`section_surface_m`, `section_depth_m`; at the back wall `back_wall_surface_m`, "
              "`back_wall_depth_m`)"),
      });
}
}  // namespace

const Schema& CfdDict::schema() {
  static const Schema s = makeSchema();
  return s;
}

CfdDict CfdDict::read(const Dictionary& d) {
  const Schema& sc = schema();
  sc.allowOnly(d, "");
  CfdDict r;
  CfdNumerics& m = r.numerics;
  m.dimensions = static_cast<int>(sc.integer(d, "dimensions"));
  if (const auto v = sc.scalarOrAuto(d, "cellSize")) m.cellSize = *v;
  m.maxCo = sc.scalar(d, "maxCo");
  m.maxAlphaCo = sc.scalar(d, "maxAlphaCo");
  m.deltaT = sc.scalar(d, "deltaT");
  m.maxDeltaT = sc.scalar(d, "maxDeltaT");
  if (m.deltaT > m.maxDeltaT)
    d.fail("deltaT",
           "value " + num(m.deltaT) + " must not exceed maxDeltaT (" + num(m.maxDeltaT) + " s)");
  // `auto` (the default): chosen from the viscous number once mesh and step are known.
  if (const auto v = sc.integerOrAuto(d, "nCorrectors")) m.nCorrectors = static_cast<int>(*v);
  m.nOuterCorrectors = static_cast<int>(sc.integer(d, "nOuterCorrectors"));
  m.momentumPredictor = sc.flag(d, "momentumPredictor");
  m.momentumScheme = sc.word(d, "momentumScheme");
  if (const auto v = sc.scalarOrAuto(d, "pressureTolerance")) m.pressureTolerance = *v;
  m.alphaTolerance = sc.scalar(d, "alphaTolerance");
  m.writeFormat = sc.word(d, "writeFormat");
  m.mixtureModel = sc.word(d, "mixtureModel");
  m.coarseCellsReason = sc.text(d, "coarseCellsReason");

  const Dictionary ob = d.subDictOrEmpty("observables");
  sc.allowOnly(ob, "observables");
  ObservableSpec& o = r.observables;
  o.frontThreshold = sc.scalar(ob, "observables.frontThreshold");
  o.sectionX = sc.scalar(ob, "observables.sectionX");
  if (const auto v = sc.scalarOrAuto(ob, "observables.minDepth")) o.minDepth = *v;
  o.froudeDepth = sc.word(ob, "observables.froudeDepth");
  return r;
}

}  // namespace mixflow
