// The DEM side of the exchange: reads the particles a rank owns from LIGGGHTS and hands them the
// fluid force, which LIGGGHTS then adds at every DEM step until the next exchange.
//
// Mechanism: `fix mixflowFluidForce all external pf/array 1` (LIGGGHTS 3.8 / LAMMPS fix external):
// a per-atom array fexternal that the fix adds to f in post_force at every step; it migrates with
// its atoms between ranks and through atom sorting. The coupling writes it for all local atoms at
// each exchange, so the force is held constant over the exchange interval.
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
}

namespace mixflow::coupling {

class DemLink {
 public:
  // Defines the force fix; call after the scene's script, before the first run.
  explicit DemLink(dem::LiggghtsSession& session);

  // Local particles now (positions at the current DEM step).
  void pull(std::vector<ParticleState>& particles, std::vector<std::int64_t>& tags);
  // Force on local particle i (same order as the last pull) [N].
  void push(const std::vector<Vec3>& forces);

  double timeStep() const;
  long step() const { return session_.step(); }
  // The DEM box is periodic in z: true and its z bounds.
  bool periodicZ(double& lo, double& hi) const;
  // Sum of the `fix gravity` accelerations (valid after the first run's setup).
  Vec3 gravity() const;
  dem::LiggghtsSession& session() { return session_; }

 private:
  LAMMPS_NS::FixExternal* fix() const;
  dem::LiggghtsSession& session_;
  long lastGlobalCount_ = -1;
};

}  // namespace mixflow::coupling
