// Accumulates particle snapshots and fluid cells of one time window into the bins of the averaging
// grid. Every quantity is kept as an additive sum, so a region's sums are the sums of its bins'.
#pragma once

#include <array>
#include <utility>
#include <vector>

#include "AveragingGrid.h"
#include "CoarseGrainKernel.h"
#include "ContactSnapshot.h"
#include "FluidSource.h"
#include "ParticleSnapshot.h"

namespace mixflow::mx {

// Sums over the snapshots (particles) or fluid times (fluid) of one window, for one bin or region.
// Tensor order: xx yy zz xy xz yz. Stress sums are stress x volume (N m), tension positive.
struct BinSums {
  double particleVolume = 0;       // sum of V_i,bin (exact sphere-bin volumes)
  double particleVolumeU = 0;      // sum of V_i,bin v_x,i
  double particleVolumeW = 0;      // sum of V_i,bin v_y,i
  double particleEquivalents = 0;  // sum of V_i,bin / V_i
  double particleSamples = 0;      // number of (particle, snapshot) pairs overlapping the bin
  // Contact stress x volume: -sum over contacts of f (x) b times the contact line's weight (contact
  // snapshots), or sum of (V_i,bin / V_i) C_i with C_i each particle's virial (stress/atom).
  std::array<double, 6> contact{};
  std::array<double, 6>
      kinetic{};             // -sum of w_i m_i v'_i v'_i, v' about the coarse-grained velocity
  double liquidVolume = 0;   // sum of alpha_l eps_f V over cells whose centre is in the bin
  double liquidVolumeU = 0;  // ... times U_x
  double liquidVolumeW = 0;  // ... times U_y
  double liquidVolumeP = 0;  // ... times p
  double fluidVolume = 0;    // sum of eps_f V (liquid and gas)
  double gasVolumeP = 0;     // sum of (1 - alpha_l) eps_f V p: the gas's pressure
  double fluidSamples = 0;   // number of (cell, time) pairs
  void add(const BinSums& o);
};

// Weights: the kernel's (CoarseGrainKernel.h); with exact bins a particle's weight in a bin is its
// exact volume share V_i,bin / V_i.
class BinAccumulator {
 public:
  // stressHasKinetic: the dumped c_pstress includes -m v v (compute stress/atom with the ke term);
  // it is then added back so that C_i holds the contact part only. periodicWidth: the width W when
  // z is periodic (contact branch vectors take the nearest image), else 0.
  BinAccumulator(const AveragingGrid& grid, const CoarseGrainKernel& kernel, bool stressHasKinetic,
                 double periodicWidth);

  // contacts: the snapshot's contact forces (the contact stress along each contact line), or
  // null (each particle's virial c_pstress, spread as the particle).
  void addSnapshot(const ParticleSnapshot& s, const ContactSnapshot* contacts = nullptr);
  void addFluid(const FluidCells& c);

  const std::vector<BinSums>& bins() const { return bins_; }
  int snapshots() const { return snapshots_; }
  int fluidTimes() const { return fluidTimes_; }
  double volumeOutsideGrid() const { return outside_; }        // sum over snapshots (m3)
  double particleVolumeTotal() const { return totalVolume_; }  // sum over snapshots (m3)
  double particleCount() const { return particles_; }          // sum over snapshots
  std::vector<double> snapshotTimes;
  std::vector<double> fluidTimeList;

 private:
  void addContacts(const ParticleSnapshot& s, const ContactSnapshot& c);
  void addBranch(const std::array<double, 3>& f, const std::array<double, 3>& r1,
                 const std::array<double, 3>& r2);

  const AveragingGrid& grid_;
  const CoarseGrainKernel& kernel_;
  bool stressHasKinetic_;
  double periodicWidth_;
  std::vector<BinSums> bins_;
  int snapshots_ = 0, fluidTimes_ = 0;
  double outside_ = 0, totalVolume_ = 0, particles_ = 0;
  // Per-snapshot scratch: the splits of every particle and each bin's mass and momentum.
  std::vector<std::pair<int, double>> split_;
  std::vector<size_t> splitStart_;
  std::vector<double> mass_, momentum_;
  std::vector<std::pair<int, double>> segment_;
  std::vector<long> indexOfId_;
};

}  // namespace mixflow::mx
