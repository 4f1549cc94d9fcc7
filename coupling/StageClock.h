// Wall time of the coupling's named stages (this rank, MPI_Wtime): one exchange's, plus the DEM
// interval before it and the fluid resampling after the fluid step before it.
#pragma once

#include <mpi.h>

#include <array>

namespace mixflow::coupling {

class StageClock {
 public:
  enum Stage {
    dem,           // the DEM interval (exchangeEvery steps)
    resample,      // pressureCoupling mixture: U sampled again after the fluid step
    pull,          // particles and the last interval's drag from LIGGGHTS
    locate,        // particles to the ranks whose mesh they touch (R1), cell search
    voidfraction,  // solid volume -> eps_f
    sample,        // the fluid at the particles' centres
    forces,        // force models and drag scheme
    gather,        // parts and forces to the owners, the reaction per particle
    toDem,         // the next interval's forces to LIGGGHTS
    deposit,       // the reaction to the cells: Ksl, Us, fSource, solidResponse
    totals,        // totals over ranks
    kStages
  };
  static constexpr const char* kNames[kStages] = {"dem",          "resample", "pull",   "locate",
                                                  "voidfraction", "sample",   "forces", "gather",
                                                  "toDem",        "deposit",  "totals"};

  template <class F>
  void time(Stage s, F&& f) {
    const double t0 = MPI_Wtime();
    f();
    seconds_[s] += MPI_Wtime() - t0;
  }
  const std::array<double, kStages>& seconds() const { return seconds_; }
  void clear() { seconds_.fill(0.0); }

 private:
  std::array<double, kStages> seconds_{};
};

}  // namespace mixflow::coupling
