#include "BinAccumulator.h"

#include <cmath>
#include <string>

#include "Dictionary.h"
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

BinAccumulator::BinAccumulator(const AveragingGrid& grid, const CoarseGrainKernel& kernel,
                               bool stressHasKinetic, double periodicWidth)
    : grid_(grid),
      kernel_(kernel),
      stressHasKinetic_(stressHasKinetic),
      periodicWidth_(periodicWidth),
      bins_(grid.size()) {}

void BinAccumulator::addBranch(const std::array<double, 3>& f, const std::array<double, 3>& r1,
                               const std::array<double, 3>& r2) {
  std::array<double, 3> b = {r1[0] - r2[0], r1[1] - r2[1], r1[2] - r2[2]};
  if (periodicWidth_ > 0) b[2] -= periodicWidth_ * std::round(b[2] / periodicWidth_);
  // Stress x volume of the contact, tension positive, symmetric part of -f (x) b.
  const std::array<double, 6> t = {-f[0] * b[0],
                                   -f[1] * b[1],
                                   -f[2] * b[2],
                                   -0.5 * (f[0] * b[1] + f[1] * b[0]),
                                   -0.5 * (f[0] * b[2] + f[2] * b[0]),
                                   -0.5 * (f[1] * b[2] + f[2] * b[1])};
  segment_.clear();
  kernel_.segmentWeights(r1[0], r1[1], r1[0] - b[0], r1[1] - b[1], segment_);
  for (const auto& [bin, w] : segment_)
    for (int q = 0; q < 6; ++q) bins_[bin].contact[q] += w * t[q];
}

void BinAccumulator::addContacts(const ParticleSnapshot& s, const ContactSnapshot& c) {
  if (s.id.size() != s.size())
    throw InputError(s.file + ": no particle ids, which the contact dumps refer to");
  indexOfId_.clear();
  for (size_t i = 0; i < s.size(); ++i) {
    const long id = s.id[i];
    if (id < 0) continue;
    if (static_cast<size_t>(id) >= indexOfId_.size()) indexOfId_.resize(id + 1, -1);
    indexOfId_[id] = static_cast<long>(i);
  }
  auto index = [&](long id) -> long {
    if (id < 0 || static_cast<size_t>(id) >= indexOfId_.size() || indexOfId_[id] < 0)
      throw InputError(s.file + ": the contact dumps name particle id " + std::to_string(id) +
                       ", which the snapshot does not hold (contact files of another step?)");
    return indexOfId_[id];
  };
  auto at = [&](long i) { return std::array<double, 3>{s.x[i], s.y[i], s.z[i]}; };
  for (const PairContact& p : c.pairs) addBranch(p.force, at(index(p.id1)), at(index(p.id2)));
  for (const WallContact& w : c.wallContacts) {
    const long i = index(w.id);
    const dem::WallPlane& plane = c.walls[w.wall];
    std::array<double, 3> r = at(i), contact = r;
    // LIGGGHTS keeps a wall's last force after the contact ends: count touching spheres only.
    if (std::fabs(r[plane.axis] - plane.position) >= s.radius[i]) continue;
    contact[plane.axis] = plane.position;
    addBranch(w.force, r, contact);
  }
}

void BinAccumulator::addSnapshot(const ParticleSnapshot& s, const ContactSnapshot* contacts) {
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
    double inside = 0;
    if (kernel_.exactBins()) {
      inside = grid_.splitSphere(s.x[i], s.y[i], r, split_);
    } else {
      // Weights as volumes, so both routes share the loops below.
      const size_t first = split_.size();
      inside = vol * kernel_.pointWeights(s.x[i], s.y[i], split_);
      for (size_t k = first; k < split_.size(); ++k) split_[k].second *= vol;
    }
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
      if (!contacts)
        for (int q = 0; q < 6; ++q) bs.contact[q] += w * c[q];
      mass_[b] += w * m;
      momentum_[3 * b] += w * m * vx;
      momentum_[3 * b + 1] += w * m * vy;
      momentum_[3 * b + 2] += w * m * vz;
    }
  }
  splitStart_[n] = split_.size();
  if (contacts) addContacts(s, *contacts);
  // Coarse-grained velocity at each bin of this snapshot (mass weighted, with the same weights:
  // the bin mean for exact bins), the streaming stress's reference.
  for (int b = 0; b < nb; ++b)
    if (mass_[b] > 0)
      for (int q = 0; q < 3; ++q) momentum_[3 * b + q] /= mass_[b];
  // Pass 2: streaming (kinetic) stress -sum w m v' v' with v' about that velocity.
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
    // The same kernel as the particles' (exact bins: the cell's centre picks its bin).
    segment_.clear();
    kernel_.pointWeights(c.x[k], c.y[k], segment_);
    for (const auto& [b, w] : segment_) {
      const double fluid = w * c.epsF[k] * c.volume[k], liquid = c.alphaL[k] * fluid;
      BinSums& bs = bins_[b];
      bs.liquidVolume += liquid;
      bs.liquidVolumeU += liquid * c.ux[k];
      bs.liquidVolumeW += liquid * c.uy[k];
      bs.liquidVolumeP += liquid * c.p[k];
      bs.fluidVolume += fluid;
      bs.gasVolumeP += (fluid - liquid) * c.p[k];
      bs.fluidSamples += 1;
    }
  }
  ++fluidTimes_;
}

}  // namespace mixflow::mx
