// The DEM side of the exchange: reads the particles a rank owns from LIGGGHTS and hands them the
// fluid force through `fix mixflowFluidForce all external` (an atom-migrating per-atom array that
// LIGGGHTS adds to f at every DEM step), held over the interval (`held`) or as a per-step backward
// Euler drag from a callback (`implicit`); the formulas are in coupling/README.md "Drag
// integration". The fix must be the last force fix (the callback reads the force summed so far).
// The drag state (the held forces, or the implicit drag's) goes into LIGGGHTS restarts
// (keepRestoredState). fix external does not initialise its array for atoms created during a
// run, so pull() stops a run whose atom count grew.
#pragma once

#include <cstdint>
#include <functional>
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
  // The fluid values of the drag laws (dragCoefficientUpdate slip): beta is the laws' at the
  // slip of every DEM step; voidfraction 0: beta held over the interval.
  DragFluidSample sample;
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
  // resuming, before the setup run: true if the particles' restart held the drag state a coupled
  // run wrote with it (on every particle, every rank: push and pushImplicit mark it), which is
  // then kept for the first interval instead of being zeroed (setups before it leave it as
  // read); false for a restart without it (e.g. the settled sample's).
  bool adoptRestoredState();
  // at the first exchange of a resumed run: the adopted state drives the next interval
  // as it would have without the stop (impulses restarted, as pushImplicit does; the interval's
  // setup repeats the write step's drag, as the uninterrupted run's setup after its write did);
  // false, and nothing changed, if none was adopted.
  bool keepRestoredState();
  // implicit, after pushImplicit and before the interval runs: replaces the fluid velocity U of
  // local particle i (same order as the last pull) where has[i]. step > 0: the drag sees the fluid
  // velocity go on changing as it did over the fluid step just taken, U + tau (U - U_held) / step.
  void setFluidVelocity(const std::vector<Vec3>& U, const std::vector<char>& has,
                        double step = 0.0);

  // dragCoefficientUpdate slip: the drag coefficient of a particle at a fluid sample (the sum of
  // the force models' beta), which the implicit drag evaluates at every DEM step.
  using DragLaw = std::function<double(const ParticleState&, const FluidAtParticle&)>;
  void setDragLaw(DragLaw law) { law_ = std::move(law); }

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
  DragLaw law_;                     // empty: beta held over the interval
  bool holdState_ = false;          // resuming: setups before the first interval leave the state
};

}  // namespace mixflow::coupling
