#include "DemDict.h"

#include <sstream>

namespace mixflow {

namespace {
Schema makeSchema() {
  const DemSpec m{};
  const SettleSpec s{};
  return Schema(
      "system/demDict",
      {
          scalarParam("youngModulusFactor", m.youngModulusFactor, Range::openClosed(0.0, 1.0), "",
                      "softening: both moduli × factor; T_R ∝ factor^-1/2 (the main speed knob). "
                      "Recorded in summary.json"),
          autoScalar("timeStep", Range::positive(), "s",
                     "auto = rayleighFraction × T_R. Limit = min(maxRayleighFraction T_R, "
                     "maxHertzFraction t_Hertz(v = √(2 g H)))")
              .alsoAllowed("≤ limit"),
          scalarParam("rayleighFraction", m.rayleighFraction, Range::openClosed(0, 1), "",
                      "paper: 5e-7 s = 0.04 T_R at 70 GPa"),
          scalarParam("maxRayleighFraction", m.maxRayleighFraction, Range::openClosed(0, 1), "",
                      "stability limit (as LIGGGHTS' check/timestep/gran); the Hertz limit binds "
                      "first for soft grains (results/stability)"),
          scalarParam("maxHertzFraction", m.maxHertzFraction, Range::openClosed(0, 0.25), "",
                      "stability limit on the fastest elastic contact (particle-wall or "
                      "particle-particle). 0.1: restitution within 0.01; a settling pile "
                      "loses grains at 0.39 t_Hertz and holds at 0.28 (results/stability)"),
          switchParam("limitForce", m.limitForce,
                      "LIGGGHTS hertz option: no attractive normal force at the end of a contact; "
                      "actual restitution 0.718 for input 0.7 (off: 0.700)"),
          scalarParam("sampleInterval", m.sampleInterval, Range::positive(), "s",
                      "between time-series rows and outlet/top deletion passes")
              .alsoAllowed("≤ writeInterval"),
          scalarParam("frontGapDiameters", m.frontGapDiameters, Range::positive(), "d",
                      "**Open choice** (front rule): particles whose surface gap ≤ k d are "
                      "connected; the front is the largest x of the largest connected cluster, so "
                      "detached grains never move it (`front_x_m`). A second front is always "
                      "written: `front_thickness_x_m`, where the width-averaged deposit (top of "
                      "each 2d-wide column, bins of d) first thins below one grain beyond x = L; "
                      "a sparse one-grain tail moves the first, not the second"),
          dictParam("velocityProfile", "the u(y) profile written once"),
          scalarParam("velocityProfile.x", m.profileX, Range::any(), "m",
                      "u(y) section; slab half-width d"),
          scalarParam("velocityProfile.time", m.profileTime, Range::nonNegative(), "s",
                      "time of the profile"),
          scalarParam("velocityProfile.binDiameters", m.profileBinDiameters, Range::positive(), "d",
                      "bin height"),
          dictParam("savage", "the Savage number at a section"),
          scalarParam("savage.x", m.savageX, Range::any(), "m",
                      "**Open choice** (Savage number, docs/model.md §8): u(y) of the particles "
                      "in the slab \\|x − savage.x\\| ≤ d on bins of height d; the top of the "
                      "flow is the highest bin with ≥ 2 particles; γ̇ = least-squares du/dy over "
                      "that bin and the contiguous populated bins below it, `layers` in all (the "
                      "top 3 d). `savage_paper` = d ρs γ̇² / (g tanφ (ρs − ρf)) (Eq. 16 as "
                      "printed), `savage_iverson` = ρs d² γ̇² / ((ρs − ρf) g h tanφ), h = the top "
                      "bin's upper edge; ρf = 0 for a dry scene, the liquid's density for a "
                      "mixture. Blank cells when no flow reaches the section"),
          integerParam("savage.layers", m.savageLayers, 2, 50, "bins of the shear-rate fit"),
          scalarParam("savage.tanPhi", m.savageTanPhi, Range::positive(), "",
                      "tanφ; not given by the paper"),
          switchParam("stopWhenArrested", m.stopWhenArrested,
                      "stop once arrested: the front moved ≤ arrestFrontDiameters × d over the "
                      "last arrestWindow and the mean KE per particle < arrestKineticTolerance × "
                      "m g d (after arrestMinTime). KE alone never vanishes: the cdt rolling "
                      "torque keeps grains at rest chattering"),
          scalarParam("arrestKineticTolerance", m.arrestKineticTolerance, Range::positive(),
                      "m g d", "per particle"),
          scalarParam("arrestFrontDiameters", m.arrestFrontDiameters, Range::nonNegative(), "d",
                      "front motion over arrestWindow"),
          scalarParam("arrestWindow", m.arrestWindow, Range::positive(), "s", ""),
          scalarParam("arrestMinTime", m.arrestMinTime, Range::nonNegative(), "s", ""),
          textParam("processors", m.processors, "LIGGGHTS processor grid")
              .alsoAllowed("three of * or positive integers"),
          scalarParam(
              "balanceInterval", m.balanceInterval, Range::nonNegative(), "s",
              "of the collapse between re-balances of the DEM's x slabs so that each "
              "rank holds about the same weight of particles (`balanceWeight`; at the start of "
              "the settling, "
              "at the gate opening and then at this interval; needs an N × 1 × 1 grid, "
              "`processors \"* 1 1\"`). In a mixture the fluid keeps its own decomposition and "
              "the exchange routes each particle to the ranks of its cells; 0: the equal "
              "slabs LIGGGHTS makes"),
          wordParam("balanceWeight", m.balanceWeight, {"particles", "pairs", "contacts"},
                    "what a particle weighs when the x slabs are re-balanced: `particles` 1 each; "
                    "`pairs` 1 + half the grains within r_i + r_j + the neighbour skin (its share "
                    "of the contact model's pair list: a grain of the dense column costs more pair "
                    "work than one of the spread tail); `contacts` 1 + half the grains it touches. "
                    "Counted from the positions, so a resumed run re-balances as the uninterrupted "
                    "one. LIGGGHTS compute imbalance (max/mean) of the reference W&P at 8 ranks: "
                    "1.22 / 1.13 / 1.12 (results/bench/README.md, \"Ranks\")"),
          switchParam(
              "binarySnapshots", m.binarySnapshots,
              "beside each VTK snapshot, the same columns in LIGGGHTS' binary dump "
              "(VTK/particles/particles_N.bin at step N, full precision), which mixflowExtract "
              "reads without parsing text; costs 176 bytes a particle, about 0.55× the VTK's "
              "disk space, and less write time than the VTK"),
          switchParam(
              "contactSnapshots", m.contactSnapshots,
              "beside each snapshot, every contact's force (VTK/contacts/pairs_N.txt, LIGGGHTS "
              "compute pair/gran/local: the two particle ids and the force) and the wall forces "
              "of the particles touching a wall (VTK/contacts/walls_N.txt, fix wall/gran "
              "store_force): mixflowExtract's coarse-grained stress along the contact lines, "
              "wall contacts included (mixture_extract/README.md). Text dumps of about 155 bytes "
              "a particle (3 contacts of 51 bytes; the VTK and binary snapshot take about 500), "
              "so a case's snapshots grow by about 30 %; off: the extractor takes each "
              "particle's stress/atom virial, without the wall contacts"),
          dictParam("settle", "the settling of the sample behind the gate"),
          scalarParam("settle.friction", s.friction, Range::nonNegative(), "",
                      "**Open choice** (sample preparation): particle friction while settling "
                      "(more friction, looser packing). With packingControl friction the first "
                      "trial's; off: the friction. W&P: 0.1 gives φ = 0.606 at the reference "
                      "tier and 0.629 at the quick tier, 0.7 gives 0.569 and 0.586"),
          scalarParam("settle.rollingFriction", s.rollingFriction, Range::closed(0.0, 2.0), "",
                      "**Open choice** (sample preparation): rolling friction coefficient while "
                      "settling (particles rollingModel; off: no effect). With friction 2 and "
                      "sedimentationSpeed 0.1 m/s the grains' own 0.1 settles W&P's column at a "
                      "bulk fraction 0.526, loose against the critical 0.565 "
                      "(results/critical_packing); 0.5 holds an open structure (0.46) that does "
                      "not come to rest. The packing control searches the sliding friction with "
                      "this held"),
          scalarParam("settle.sedimentationSpeed", s.sedimentationSpeed, Range::nonNegative(),
                      "m/s",
                      "**Open choice** (sample preparation): while settling every grain feels a "
                      "drag -m g' v / speed (g' the settling gravity, LIGGGHTS fix viscous), so "
                      "that it falls no faster than this, as grains sedimenting in a liquid do. "
                      "Free-falling grains compact the pile: sliding friction alone stops at a "
                      "bulk 0.57 (friction 1-2), with 0.1 m/s and friction 2 it is 0.560. 0: free "
                      "fall"),
          wordParam("settle.packingControl", s.packingControl, {"friction", "off"},
                    "**Open choice** (sample preparation): friction settles the same loose fill "
                    "at trial frictions in [minFriction, maxFriction] (a secant search on "
                    "ln(μ + 0.05), dem/PackingSearch.h) until the sample fraction N V_p / (L W h) "
                    "is within packingTolerance of sample.solidFraction, whatever the tier and "
                    "softening; a miss after maxSettles trials stops the preparation. off: one "
                    "settle at settle.friction, whose fraction moves with the softening "
                    "(0.59-0.64). The friction found is recorded in dem/settled.state and "
                    "summary.json"),
          scalarParam("settle.packingTolerance", s.packingTolerance, Range::closed(1e-4, 0.05), "",
                      "largest distance of the settled sample's fraction from "
                      "sample.solidFraction that a controlled settle accepts"),
          scalarParam("settle.minFriction", s.minFriction, Range::closed(0.0, 2.0), "",
                      "smallest settling friction the packing control tries"),
          scalarParam("settle.maxFriction", s.maxFriction, Range::closed(0.0, 2.0), "",
                      "largest settling friction the packing control tries")
              .alsoAllowed("> minFriction"),
          integerParam("settle.maxSettles", s.maxSettles, 1, 50,
                       "settles of the loose fill the packing control may run (each costs a "
                       "whole settle)"),
          scalarParam("settle.maxTime", s.maxTime, Range::positive(), "s",
                      "of settling at most (reported as not converged if reached)"),
          scalarParam("settle.kineticTolerance", s.kineticTolerance, Range::positive(), "m g d",
                      "settled when mean KE per particle < tol × m g d"),
          // Below 1.02 d there is no room for the jitter; above 2 d the fill column is very tall.
          scalarParam("settle.fillSpacing", s.fillSpacing, Range::closed(1.02, 2.0), "d",
                      "lattice spacing of the loose fill before settling"),
          scalarParam("settle.relaxTime", s.relaxTime, Range::nonNegative(), "s",
                      "with the real friction before the gate opens"),
          integerParam("settle.seed", s.seed, 1, 900000000, "jitter of the loose fill"),
          scalarParam("settle.checkpointInterval", s.checkpointInterval, Range::nonNegative(), "s",
                      "of settling between checkpoints (0: none): an interrupted settle continues "
                      "from the last to the sample an uninterrupted one gives; Allrun keeps it"),
          wordParam("settle.gravity", s.gravity, {"full", "buoyant"},
                    "**Open choice** (sample preparation, mixtures): the grains settle under "
                    "their buoyant weight g (1 − ρ_f/ρ_s) (buoyant), so that the saturated column "
                    "starts with the contact forces it keeps in the liquid, or dry under g (full): "
                    "in the HB and Bingham liquids such a bed keeps its dry contact loads and a "
                    "pore suction of 34 % of ρ_f g at rest (coupling.static_bed, "
                    "results/convergence); dry scenes: full"),
          scalarParam("settle.stiffenFrom", s.stiffenFrom, Range::closed(0.0, 1.0), "",
                      "youngModulusFactor the sample settles at (with its own auto step, "
                      "rayleighFraction × T_R) before it is stiffened to youngModulusFactor; 0: it "
                      "settles at youngModulusFactor. Recorded in dem/settled.inputs")
              .alsoAllowed("< youngModulusFactor"),
          // One sudden step releases (ratio − 1) × the contacts' elastic energy: 1000× at once
          // throws a settled column apart; ratios 1.6-2 leave it at rest (docs/parameters.md).
          integerParam("settle.stiffenSteps", s.stiffenSteps, 1, 100,
                       "geometric steps from stiffenFrom to youngModulusFactor (ratio (factor / "
                       "stiffenFrom)^(1/steps)); each modulus at its own auto step, the last at "
                       "the settle's step (settle.rayleighFraction)"),
          scalarParam("settle.stiffenStepTime", s.stiffenStepTime, Range::positive(), "s",
                      "at each modulus of the stiffening, with the settling friction"),
          scalarParam("settle.rayleighFraction", s.rayleighFraction, Range::openClosed(0, 1), "",
                      "the settle's auto step (fill, stiffening, relaxation) as a fraction of T_R "
                      "at each of its moduli, within the stability limit; a set timeStep is used "
                      "as is. The collapse runs at rayleighFraction: one settled sample serves "
                      "every collapse step"),
      });
}

void readSettle(const Schema& sc, const Dictionary& d, SettleSpec& s) {
  sc.allowOnly(d, "settle");
  s.friction = sc.scalar(d, "settle.friction");
  s.packingControl = sc.word(d, "settle.packingControl");
  s.packingTolerance = sc.scalar(d, "settle.packingTolerance");
  s.minFriction = sc.scalar(d, "settle.minFriction");
  s.maxFriction = sc.scalar(d, "settle.maxFriction");
  s.maxSettles = sc.integer(d, "settle.maxSettles");
  if (s.maxFriction <= s.minFriction)
    d.fail("maxFriction", "value " + formatNumber(s.maxFriction, 4) +
                              " must be above minFriction (" + formatNumber(s.minFriction, 4) +
                              "); allowed range (" + formatNumber(s.minFriction, 4) + ", 2]");
  if (s.packingControl == "friction" && (s.friction < s.minFriction || s.friction > s.maxFriction))
    d.fail("friction", "value " + formatNumber(s.friction, 4) +
                           " is the packing control's first trial and must lie in [minFriction, "
                           "maxFriction]; allowed range [" +
                           formatNumber(s.minFriction, 4) + ", " + formatNumber(s.maxFriction, 4) +
                           "] (or packingControl off)");
  s.rollingFriction = sc.scalar(d, "settle.rollingFriction");
  s.sedimentationSpeed = sc.scalar(d, "settle.sedimentationSpeed");
  s.maxTime = sc.scalar(d, "settle.maxTime");
  s.kineticTolerance = sc.scalar(d, "settle.kineticTolerance");
  s.fillSpacing = sc.scalar(d, "settle.fillSpacing");
  s.relaxTime = sc.scalar(d, "settle.relaxTime");
  s.seed = sc.integer(d, "settle.seed");
  s.checkpointInterval = sc.scalar(d, "settle.checkpointInterval");
  s.gravity = sc.word(d, "settle.gravity");
  s.stiffenFrom = sc.scalar(d, "settle.stiffenFrom");
  s.stiffenSteps = sc.integer(d, "settle.stiffenSteps");
  s.stiffenStepTime = sc.scalar(d, "settle.stiffenStepTime");
  s.rayleighFraction = sc.scalar(d, "settle.rayleighFraction");
}

void readProcessors(const Schema& sc, const Dictionary& d, std::string& grid) {
  grid = sc.text(d, "processors");
  std::istringstream in(grid);
  std::string t;
  int n = 0;
  while (in >> t) {
    ++n;
    if (t != "*" && (t.find_first_not_of("0123456789") != std::string::npos || t == "0"))
      d.fail("processors", "each of the three entries must be * or a positive integer");
  }
  if (n != 3) d.fail("processors", "needs three entries (x y z), e.g. \"* 1 1\"");
}
}  // namespace

const Schema& DemDict::schema() {
  static const Schema s = makeSchema();
  return s;
}

DemDict DemDict::read(const Dictionary& d) {
  const Schema& sc = schema();
  sc.allowOnly(d, "");
  DemDict r;
  DemSpec& m = r.dem;
  m.youngModulusFactor = sc.scalar(d, "youngModulusFactor");
  if (const auto v = sc.scalarOrAuto(d, "timeStep")) m.timeStep = *v;
  m.rayleighFraction = sc.scalar(d, "rayleighFraction");
  m.maxRayleighFraction = sc.scalar(d, "maxRayleighFraction");
  m.maxHertzFraction = sc.scalar(d, "maxHertzFraction");
  m.limitForce = sc.flag(d, "limitForce");
  m.sampleInterval = sc.scalar(d, "sampleInterval");
  m.frontGapDiameters = sc.scalar(d, "frontGapDiameters");
  const Dictionary vp = d.subDictOrEmpty("velocityProfile");
  sc.allowOnly(vp, "velocityProfile");
  m.profileX = sc.scalar(vp, "velocityProfile.x");
  m.profileTime = sc.scalar(vp, "velocityProfile.time");
  m.profileBinDiameters = sc.scalar(vp, "velocityProfile.binDiameters");
  const Dictionary sv = d.subDictOrEmpty("savage");
  sc.allowOnly(sv, "savage");
  m.savageX = sc.scalar(sv, "savage.x");
  m.savageLayers = static_cast<int>(sc.integer(sv, "savage.layers"));
  m.savageTanPhi = sc.scalar(sv, "savage.tanPhi");
  m.stopWhenArrested = sc.flag(d, "stopWhenArrested");
  m.arrestKineticTolerance = sc.scalar(d, "arrestKineticTolerance");
  m.arrestMinTime = sc.scalar(d, "arrestMinTime");
  m.arrestFrontDiameters = sc.scalar(d, "arrestFrontDiameters");
  m.arrestWindow = sc.scalar(d, "arrestWindow");
  readProcessors(sc, d, m.processors);
  m.balanceInterval = sc.scalar(d, "balanceInterval");
  m.balanceWeight = sc.word(d, "balanceWeight");
  m.binarySnapshots = sc.flag(d, "binarySnapshots");
  m.contactSnapshots = sc.flag(d, "contactSnapshots");
  readSettle(sc, d.subDictOrEmpty("settle"), r.settle);
  return r;
}

}  // namespace mixflow
