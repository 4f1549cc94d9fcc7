// system/demDict: the DEM numerics of a scene with grains (time step, softening, settling,
// observables). One declaration table (DemDict.cpp) gives every entry; the defaults are the
// initializers below. The rules that need the scene (the time step's stability limit,
// sampleInterval against writeInterval) are dem::Scene's.
#pragma once

#include <string>

#include "Dictionary.h"
#include "Schema.h"

namespace mixflow {

struct SettleSpec {
  // particle friction while settling behind the gate (sets the packing); with packingControl
  // friction, the first trial's
  double friction = 0.1;
  // rolling friction while settling (0: none, the default); with high sliding friction it
  // gives packings looser than sliding friction alone reaches
  double rollingFriction = 0;
  // m/s: grains settle against a drag -m g' v / speed (g' the settling gravity), so none falls
  // faster than this, as grains sedimenting in a liquid; 0: free fall (the default)
  double sedimentationSpeed = 0;
  // friction: the settling friction is searched in [minFriction, maxFriction], each trial settling
  // the same loose fill, until the sample's solid fraction is within packingTolerance of
  // sample.solidFraction (dem/PackingSearch.h); off: one settle at `friction`.
  std::string packingControl = "friction";
  double packingTolerance = 0.003;  // |phi - sample.solidFraction| allowed (absolute)
  double minFriction = 0;
  double maxFriction = 1.0;
  long maxSettles = 6;             // trials before the preparation stops
  double maxTime = 3.0;            // s of simulated settling at most
  double kineticTolerance = 1e-5;  // settled when mean KE per particle < tol * m g d
  double fillSpacing = 1.15;       // lattice spacing of the initial loose fill, in diameters
  double relaxTime = 0.05;         // s with the real friction before the gate opens
  long seed = 12345;
  // s of settling between checkpoints (dem/SettleCheckpoint.h); 0: none
  double checkpointInterval = 0;
  // buoyant: a mixture's grains settle under g (1 - rho_f / rho_s), the weight they keep once
  // saturated; in a yield-stress liquid a bed settled under g keeps its dry contact loads and a
  // pore suction (coupling.static_bed). full: under g. Dry scenes settle under g either way.
  std::string gravity = "buoyant";
  // youngModulusFactor the sample settles at before it is stiffened to demDict youngModulusFactor
  // (a stiff settle costs T_R^-1 steps); 0: it settles at youngModulusFactor.
  double stiffenFrom = 0;
  // The moduli rise geometrically in stiffenSteps steps, each held stiffenStepTime s: a step's
  // sudden stiffening releases about (ratio - 1) times the elastic energy of the contacts.
  long stiffenSteps = 10;
  double stiffenStepTime = 0.01;
  // The auto step of the whole settle (fill, stiffening, relaxation) as a fraction of T_R: the
  // sample does not depend on the collapse's step, so one sample serves a DEM-step ladder.
  double rayleighFraction = 0.1;
};

struct DemSpec {
  double youngModulusFactor = 1.0;  // softening: both moduli are multiplied by it (speed knob)
  double timeStep = 0;              // 0 = auto: rayleighFraction * T_R
  double rayleighFraction = 0.1;
  double maxRayleighFraction = 0.2;  // a requested step above this fraction of T_R is refused
  double maxHertzFraction = 0.1;     // ... or above this fraction of the fastest Hertz contact time
  bool limitForce = true;            // LIGGGHTS hertz option: no attractive normal force
  double sampleInterval = 0.01;      // s between time-series samples (and deletions at the outlet)
  double frontGapDiameters = 0.5;  // surface gap (in d) that still connects a particle to the mass
  double profileX = 0.8;           // velocity profile section (m)
  double profileTime = 0.5;        // velocity profile time (s)
  double profileBinDiameters = 1.0;
  bool stopWhenArrested = true;
  // Arrested when the front moved less than arrestFrontDiameters d over the last arrestWindow s and
  // the mean KE per particle is below arrestKineticTolerance m g d. (The kinetic energy alone never
  // reaches zero: a constant rolling torque (cdt) keeps grains at rest chattering.)
  double arrestKineticTolerance = 1e-3;
  double arrestFrontDiameters = 0.1;
  double arrestWindow = 0.25;
  double arrestMinTime = 0.3;  // never declare arrest before this time (s)
  // x slabs re-balanced by particles: the grains start in the channel's first metres, so equal
  // slabs would leave most ranks idle (results/bench/README.md, "Ranks").
  std::string processors = "* 1 1";  // LIGGGHTS processors grid
  double balanceInterval = 0.05;     // s between re-balances of x slabs by particles; 0: never
  // What a particle weighs when the slabs are re-balanced: particles (1 each), pairs (1 + half
  // its neighbours within r_i + r_j + skin) or contacts (1 + half the grains it touches).
  std::string balanceWeight = "pairs";
  bool binarySnapshots = true;  // a binary dump beside each VTK snapshot (dem/SnapshotFiles.h)
  // Contact and wall-contact forces beside each snapshot (dem/ContactDumps.h): the coarse-grained
  // stress of mixflowExtract; off by default, as they add about 30 % to the snapshots' disk space.
  bool contactSnapshots = false;
  // Savage number at the section x = savageX (docs/model.md §8): the shear rate is the
  // least-squares slope du/dy over the top savageLayers populated bins (height d each) of the
  // u(y) profile in the slab |x - savageX| <= d; tan(phi) is not given by the paper.
  double savageX = 0.8;
  int savageLayers = 3;
  double savageTanPhi = 0.7;
};

struct DemDict {
  DemSpec dem;
  SettleSpec settle;

  static const Schema& schema();
  static DemDict read(const Dictionary& demDict);
};

}  // namespace mixflow
