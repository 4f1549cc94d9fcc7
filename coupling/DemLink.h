// The DEM side of the exchange: reads the particles a rank owns from LIGGGHTS and hands them the
// fluid force, which LIGGGHTS then applies at every DEM step until the next exchange.
//
// Mechanism: `fix mixflowFluidForce all external` (LIGGGHTS 3.8 / LAMMPS fix external), a per-atom
// array fexternal that the fix adds to f in post_force at every step; it migrates with its atoms
// between ranks and through atom sorting. Two ways to integrate the drag (dragIntegration):
//   held      `pf/array`: the coupling writes F = beta (U - v) + F_explicit at each exchange and
//             the force is held over the interval (needs beta T / m < 2 to be stable: see
//             dragRelaxationLimit);
//   implicit  `pf/callback 1 1`: the exchange writes beta, U and F_explicit into a per-atom
//             `fix property/atom` (migrates like the atoms); at every DEM step a callback gives
//             F_d = beta_eff (U - v - dt (f_other + F_explicit) / m), beta_eff = beta / (1 +
//             beta dt / m): backward Euler for the drag in LIGGGHTS' velocity-Verlet half-step
//             update, stable for any beta, with the exact terminal slip f_other / beta. It adds
//             up the drag impulse it applied, which the next exchange returns to the fluid.
//             With a fluid share m_f (AppliedDrag::invFluidMass) the fluid velocity seen is
//             U - J / m_f (J the impulse so far) and backward Euler covers the pair:
//             F_d = beta (U - J/m_f - v - dt (f_other + F_explicit) / m) / (1 + beta dt (1/m +
//             1/m_f)), so particle and fluid share relax to their common velocity within the
//             interval, as they would if the fluid were solved alongside.
//             With a counterflow factor c (AppliedDrag::counterflow, dragFluidResponse
//             continuity) the fluid velocity seen is U - c (v - v_ref): the mixture volume flux
//             eps U + (1 - eps) v of the particle's cell is held over the interval instead of U,
//             v_ref being the particle's mean velocity over the interval whose displacement the
//             fluid step behind U saw (two intervals back: the exchange samples the fluid before
//             its step). Backward Euler: F_d = beta (U + c v_ref - (1 + c) v') with v' the
//             velocity after the step; the terminal slip stays f_other / beta.
//             f_other is the force LIGGGHTS has summed when this fix's post_force runs (pair,
//             gravity, walls: fixes defined before it), so this fix must be the last force fix.
//             Particles must be integrated by LIGGGHTS (a fixed bed without an integrator
//             needs `held`).
// The implicit state is written to LIGGGHTS restarts and read back with them (a resumed run's first
// interval then uses the forces the stopped run had set: keepRestoredState).
// Caveat (checked): fix external does not initialise the array for atoms created during a run
// (memory->grow), so particles must not be inserted during a coupled interval; pull() stops the
// run if the global atom count grew.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "ForceModel.h"
#include "LiggghtsSession.h"
#include "Vec3.h"

namespace LAMMPS_NS {
class FixExternal;
}  // namespace LAMMPS_NS

namespace mixflow::coupling {

// What the implicit drag of one particle used over the last interval, and the impulse it gave.
struct AppliedDrag {
  double beta = 0;     // drag coefficient of the force law [kg/s]
  Vec3 U;              // fluid velocity held over the interval [m/s]
  Vec3 explicitForce;  // held explicit force [N]
  Vec3 impulse;        // drag impulse applied over the interval [N s]
  // 1 / m_f of the particle's share of its cell's fluid, whose velocity U - impulse / m_f the
  // drag sees (dragFluidResponse share); 0: the fluid velocity is held at U.
  double invFluidMass = 0;
  // The share's acceleration by the fluid's own forces (the last fluid step's), so that its
  // velocity is U + a tau - impulse / m_f at tau into the interval.
  Vec3 fluidAcceleration;
  // c = (1 - eps) / eps of the particle's cell (dragFluidResponse continuity); 0: U held.
  double counterflow = 0;
};

class DemLink {
 public:
  enum class DragIntegration { held, implicit };

  // Defines the force fix; call after the scene's script, before the first run.
  DemLink(dem::LiggghtsSession& session, DragIntegration mode);

  // Local particles now (positions at the current DEM step).
  void pull(std::vector<ParticleState>& particles, std::vector<std::int64_t>& tags);
  // implicit: what each local particle's drag used and applied since the last pushImplicit (same
  // order as the last pull).
  void pullApplied(std::vector<AppliedDrag>& applied) const;
  // held: force on local particle i (same order as the last pull) [N].
  void push(const std::vector<Vec3>& forces);
  // implicit: the next interval's beta, U and explicit force; resets the impulses.
  void pushImplicit(const std::vector<AppliedDrag>& next);
  // implicit, resuming, before the setup run: true if the particles' restart held the drag state
  // a coupled run wrote with it (on every particle, every rank: pushImplicit marks it), which is
  // then kept for the first interval instead of being zeroed; false for a restart without it
  // (e.g. the settled sample's).
  bool adoptRestoredState();
  // implicit, at the first exchange of a resumed run: the adopted state drives the next interval
  // as it would have without the stop (impulses restarted, as pushImplicit does); false, and
  // nothing changed, if none was adopted.
  bool keepRestoredState();
  // implicit, after pushImplicit and before the interval runs: replaces the fluid velocity U of
  // local particle i (same order as the last pull) where has[i].
  void setFluidVelocity(const std::vector<Vec3>& U, const std::vector<char>& has);

  DragIntegration mode() const { return mode_; }
  double timeStep() const;
  long step() const { return session_.step(); }
  // The DEM box is periodic in z: true and its z bounds.
  bool periodicZ(double& lo, double& hi) const;
  // Sum of the `fix gravity` accelerations (valid after the first run's setup).
  Vec3 gravity() const;
  dem::LiggghtsSession& session() { return session_; }

  // fix external's per-step callback (implicit mode).
  void implicitDrag(std::int64_t step, int nlocal, double** fexternal);

 private:
  LAMMPS_NS::FixExternal* fix() const;
  double** state() const;  // the per-atom implicit-drag state (property/atom array)
  dem::LiggghtsSession& session_;
  DragIntegration mode_;
  long lastGlobalCount_ = -1;
  std::int64_t lastCallStep_ = -1;
  std::int64_t intervalStart_ = 0;  // DEM step of the last pushImplicit
  bool adopted_ = false;            // the restart's drag state is kept (adoptRestoredState)
};

}  // namespace mixflow::coupling
