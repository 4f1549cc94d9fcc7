// Coarse-graining of the extractor on cases with known answers (mixture_extract/CoarseGrainKernel,
// BinAccumulator with contact snapshots):
//   Lucy and Gaussian kernels integrate to 1 over the bins; an exact-bin contact line is split by
//     its length inside each bin;
//   a contact adds -f (x) b along its line, a wall contact from the centre to the plane, a wall's
//     stale force on a sphere no longer touching it adds nothing, and a pair across the periodic
//     width takes the nearest image;
//   a uniform velocity has no streaming stress under a kernel (the reference is the coarse-grained
//     velocity at the bin), and fluid cells are averaged with the particles' kernel.
#include <gtest/gtest.h>

#include <cmath>

#include "AveragingGrid.h"
#include "BinAccumulator.h"
#include "CoarseGrainKernel.h"
#include "ContactSnapshot.h"
#include "SphereBinVolume.h"

using namespace mixflow::mx;

namespace {

void addParticle(ParticleSnapshot& s, long id, double x, double y, double z, double r,
                 double vx = 0, double vy = 0) {
  s.id.push_back(id);
  s.x.push_back(x);
  s.y.push_back(y);
  s.z.push_back(z);
  s.vx.push_back(vx);
  s.vy.push_back(vy);
  s.vz.push_back(0);
  s.radius.push_back(r);
  s.mass.push_back(2500 * sphereVolume(r));
  s.stress.push_back({});
}

double weightSum(const std::vector<std::pair<int, double>>& w) {
  double s = 0;
  for (const auto& e : w) s += e.second;
  return s;
}

}  // namespace

TEST(CoarseGrainKernel, KernelsIntegrateToOne) {
  const AveragingGrid g(0, 0.4, 80, 0, 0.4, 80, 0.1);
  for (const char* shape : {"lucy", "gaussian"}) {
    const CoarseGrainKernel k(g, shape, 0.02);
    std::vector<std::pair<int, double>> w;
    const double sum = k.pointWeights(0.2013, 0.1987, w);
    EXPECT_NEAR(sum, 1.0, 2e-3) << shape;
    EXPECT_NEAR(weightSum(w), sum, 1e-12) << shape;
    // Near the grid's edge part of the kernel is outside: less than 1.
    w.clear();
    EXPECT_LT(k.pointWeights(0.001, 0.2, w), 0.6) << shape;
  }
}

TEST(CoarseGrainKernel, ExactBinsSplitASegmentByLength) {
  const AveragingGrid g(0, 4, 4, 0, 2, 2, 1);
  const CoarseGrainKernel k(g, "bins", 0);
  std::vector<std::pair<int, double>> w;
  k.segmentWeights(0.5, 0.5, 2.5, 0.5, w);
  ASSERT_EQ(w.size(), 3u);
  EXPECT_NEAR(w[0].second, 0.25, 1e-14);
  EXPECT_NEAR(w[1].second, 0.5, 1e-14);
  EXPECT_NEAR(w[2].second, 0.25, 1e-14);
  w.clear();
  k.segmentWeights(0.5, 0.5, 1.5, 1.5, w);  // through the corner (1, 1)
  EXPECT_NEAR(weightSum(w), 1.0, 1e-14);
  w.clear();
  k.segmentWeights(3.5, 1.5, 4.5, 1.5, w);  // half outside the grid
  EXPECT_NEAR(weightSum(w), 0.5, 1e-14);
}

TEST(ContactStress, PairAndWallContactsAlongTheirLines) {
  // Two bins stacked in y, each 1 cm high; grain 1 on the floor, grain 2 on top of it.
  const double r = 0.004, W = 0.01;
  const AveragingGrid g(0, 0.01, 1, 0, 0.02, 2, W);
  const CoarseGrainKernel k(g, "bins", 0);
  ParticleSnapshot s;
  s.file = "synthetic";
  addParticle(s, 7, 0.005, 0.0039, 0.005, r);  // overlaps the floor by 0.1 mm
  addParticle(s, 9, 0.005, 0.0117, 0.005, r);  // centre in the upper bin
  ContactSnapshot c;
  c.walls = {{"wBottom", 1, 0.0}};
  const double F = 0.05, Fw = 0.07;
  c.pairs.push_back({7, 9, {0.0, -F, 0.0}});          // on 7 by 9: pushed down
  c.wallContacts.push_back({7, 0, {0.0, Fw, 0.0}});   // the floor pushes 7 up
  c.wallContacts.push_back({9, 0, {0.0, 1.0, 0.0}});  // stale: 9 does not touch the floor
  BinAccumulator acc(g, k, false, 0);
  acc.addSnapshot(s, &c);
  const auto& b = acc.bins();
  // Pair: -f_y b_y = -(-F)(y7 - y9) = -F 0.0078, split 0.0061 / 0.0017 between the bins.
  const double lower = -F * (0.01 - 0.0039) - Fw * 0.0039, upper = -F * (0.0117 - 0.01);
  EXPECT_NEAR(b[0].contact[1], lower, 1e-15);
  EXPECT_NEAR(b[1].contact[1], upper, 1e-15);
  for (int q : {0, 2, 3, 4, 5}) EXPECT_EQ(b[0].contact[q] + b[1].contact[q], 0.0);
}

TEST(ContactStress, PeriodicPairTakesTheNearestImage) {
  const double W = 0.05;
  const AveragingGrid g(0, 0.02, 1, 0, 0.02, 1, W);
  const CoarseGrainKernel k(g, "bins", 0);
  ParticleSnapshot s;
  s.file = "synthetic";
  addParticle(s, 1, 0.01, 0.01, 0.001, 0.002);
  addParticle(s, 2, 0.01, 0.01, W - 0.002, 0.002);
  ContactSnapshot c;
  c.pairs.push_back({1, 2, {0.0, 0.0, 0.3}});  // 2 sits at z = -0.002 through the boundary
  BinAccumulator acc(g, k, false, W);
  acc.addSnapshot(s, &c);
  EXPECT_NEAR(acc.bins()[0].contact[2], -0.3 * 0.003, 1e-15);
}

TEST(Kinetic, UniformVelocityHasNoStreamingStressUnderAKernel) {
  const AveragingGrid g(0, 0.2, 10, 0, 0.2, 10, 0.02);
  const CoarseGrainKernel k(g, "lucy", 0.02);
  ParticleSnapshot s;
  s.file = "synthetic";
  long id = 0;
  for (double x = 0.011; x < 0.2; x += 0.0123)
    for (double y = 0.007; y < 0.2; y += 0.0117) addParticle(s, ++id, x, y, 0.01, 0.004, 0.3, -0.1);
  BinAccumulator acc(g, k, false, 0);
  acc.addSnapshot(s);
  for (const BinSums& b : acc.bins()) {
    ASSERT_GT(b.particleVolume, 0);
    EXPECT_NEAR(b.particleVolumeU / b.particleVolume, 0.3, 1e-12);
    for (double q : b.kinetic) EXPECT_NEAR(q, 0.0, 1e-15);
  }
}

TEST(Fluid, CellsAveragedWithTheParticlesKernel) {
  const AveragingGrid g(0, 0.2, 10, 0, 0.2, 10, 0.02);
  const CoarseGrainKernel k(g, "gaussian", 0.015);
  FluidCells c;
  for (double x = 0.0025; x < 0.2; x += 0.005)
    for (double y = 0.0025; y < 0.2; y += 0.005) {
      c.x.push_back(x);
      c.y.push_back(y);
      c.volume.push_back(0.005 * 0.005 * 0.02);
      c.alphaL.push_back(1);
      c.epsF.push_back(0.5);
      c.ux.push_back(1.5);
      c.uy.push_back(20 * y);  // linear: the kernel's symmetric average keeps it in the interior
      c.p.push_back(100);
    }
  BinAccumulator acc(g, k, false, 0);
  acc.addFluid(c);
  const BinSums& mid = acc.bins()[g.index(5, 5)];
  EXPECT_NEAR(mid.liquidVolumeU / mid.liquidVolume, 1.5, 1e-12);
  EXPECT_NEAR(mid.liquidVolumeW / mid.liquidVolume, 20 * 0.11, 1e-9);
  // The kernel holds the bin's fluid volume: eps_f V of the bin's area.
  EXPECT_NEAR(mid.fluidVolume / g.binVolume(), 0.5, 5e-3);
}
