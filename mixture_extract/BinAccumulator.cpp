#include "BinAccumulator.h"

#include "SphereBinVolume.h"

namespace mixflow::mx {

void BinSums::add(const BinSums& o) {
  particleVolume += o.particleVolume;
  particleVolumeU += o.particleVolumeU;
  particleVolumeW += o.particleVolumeW;
  particleEquivalents += o.particleEquivalents;
  particleSamples += o.particleSamples;
  for (int k = 0; k < 6; ++k) {
    contact[k] += o.contact[k];
    kinetic[k] += o.kinetic[k];
  }
  liquidVolume += o.liquidVolume;
  liquidVolumeU += o.liquidVolumeU;
  liquidVolumeW += o.liquidVolumeW;
  liquidVolumeP += o.liquidVolumeP;
  fluidVolume += o.fluidVolume;
  gasVolumeP += o.gasVolumeP;
  fluidSamples += o.fluidSamples;
}

BinAccumulator::BinAccumulator(const AveragingGrid& grid, bool stressHasKinetic)
    : grid_(grid), stressHasKinetic_(stressHasKinetic), bins_(grid.size()) {}

void BinAccumulator::addSnapshot(const ParticleSnapshot& s) {
  const size_t n = s.size();
  const int nb = grid_.size();
  split_.clear();
  splitStart_.assign(n + 1, 0);
  mass_.assign(nb, 0.0);
  momentum_.assign(3 * static_cast<size_t>(nb), 0.0);
  // Pass 1: exact volume split, volume-weighted velocity, contact stress, bin mass and momentum.
  for (size_t i = 0; i < n; ++i) {
    splitStart_[i] = split_.size();
    const double r = s.radius[i], vol = sphereVolume(r), m = s.mass[i];
    const double vx = s.vx[i], vy = s.vy[i], vz = s.vz[i];
    const double inside = grid_.splitSphere(s.x[i], s.y[i], r, split_);
    totalVolume_ += vol;
    outside_ += vol - inside;
    std::array<double, 6> c = s.stress[i];
    if (stressHasKinetic_) {
      c[0] += m * vx * vx;
      c[1] += m * vy * vy;
      c[2] += m * vz * vz;
      c[3] += m * vx * vy;
      c[4] += m * vx * vz;
      c[5] += m * vy * vz;
    }
    for (size_t k = splitStart_[i]; k < split_.size(); ++k) {
      const int b = split_[k].first;
      const double v = split_[k].second, w = v / vol;
      BinSums& bs = bins_[b];
      bs.particleVolume += v;
      bs.particleVolumeU += v * vx;
      bs.particleVolumeW += v * vy;
      bs.particleEquivalents += w;
      bs.particleSamples += 1;
      for (int q = 0; q < 6; ++q) bs.contact[q] += w * c[q];
      mass_[b] += w * m;
      momentum_[3 * b] += w * m * vx;
      momentum_[3 * b + 1] += w * m * vy;
      momentum_[3 * b + 2] += w * m * vz;
    }
  }
  splitStart_[n] = split_.size();
  // Bin mean velocity of this snapshot (mass weighted, the streaming stress's reference).
  for (int b = 0; b < nb; ++b)
    if (mass_[b] > 0)
      for (int q = 0; q < 3; ++q) momentum_[3 * b + q] /= mass_[b];
  // Pass 2: streaming (kinetic) stress -sum w m v' v' with v' about the bin mean.
  for (size_t i = 0; i < n; ++i) {
    const double r = s.radius[i], vol = sphereVolume(r), m = s.mass[i];
    for (size_t k = splitStart_[i]; k < splitStart_[i + 1]; ++k) {
      const int b = split_[k].first;
      const double w = split_[k].second / vol;
      const double ux = s.vx[i] - momentum_[3 * b], uy = s.vy[i] - momentum_[3 * b + 1],
                   uz = s.vz[i] - momentum_[3 * b + 2];
      std::array<double, 6>& K = bins_[b].kinetic;
      const double wm = w * m;
      K[0] -= wm * ux * ux;
      K[1] -= wm * uy * uy;
      K[2] -= wm * uz * uz;
      K[3] -= wm * ux * uy;
      K[4] -= wm * ux * uz;
      K[5] -= wm * uy * uz;
    }
  }
  particles_ += static_cast<double>(n);
  ++snapshots_;
  snapshotTimes.push_back(s.time);
}

void BinAccumulator::addFluid(const FluidCells& c) {
  for (size_t k = 0; k < c.size(); ++k) {
    const int b = grid_.locate(c.x[k], c.y[k]);
    if (b < 0) continue;
    const double fluid = c.epsF[k] * c.volume[k], liquid = c.alphaL[k] * fluid;
    BinSums& bs = bins_[b];
    bs.liquidVolume += liquid;
    bs.liquidVolumeU += liquid * c.ux[k];
    bs.liquidVolumeW += liquid * c.uy[k];
    bs.liquidVolumeP += liquid * c.p[k];
    bs.fluidVolume += fluid;
    bs.gasVolumeP += (fluid - liquid) * c.p[k];
    bs.fluidSamples += 1;
  }
  ++fluidTimes_;
}

}  // namespace mixflow::mx
