// Exact sphere / bin volumes (mixture_extract/SphereBinVolume.h, AveragingGrid::splitSphere).
//   corner function against an independent quadrature of the circle-segment areas (1e-13 r^3);
//   slabs against dem::sphereSlabVolume; the pieces sum to the particle volume
//   (1e-12 relative); a uniform lattice gives its exact alpha_s in every bin, with
//   particles straddling the bin edges (1e-12).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "AveragingGrid.h"
#include "BinAccumulator.h"
#include "Observables.h"
#include "SphereBinVolume.h"

using namespace mixflow::mx;

namespace {

// Gauss-Legendre nodes and weights on [-1, 1] (Newton on P_n).
void gaussLegendre(int n, std::vector<double>& x, std::vector<double>& w) {
  x.resize(n);
  w.resize(n);
  for (int i = 0; i < n; ++i) {
    double z = std::cos(kPi * (i + 0.75) / (n + 0.5)), dp = 0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1, p1 = z;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (z * p1 - p0) / (z * z - 1);
      const double dz = p1 / dp;
      z -= dz;
      if (std::fabs(dz) < 1e-16) break;
    }
    x[i] = z;
    w[i] = 2 / ((1 - z * z) * dp * dp);
  }
}

// Area of the disc of radius rho below the chord y = Y (the textbook circular-segment formula).
double segmentBelow(double rho, double Y) {
  if (Y >= rho) return kPi * rho * rho;
  if (Y <= -rho) return 0;
  const double h = rho - Y;  // height of the segment above the chord
  const double above =
      rho * rho * std::acos((rho - h) / rho) - (rho - h) * std::sqrt(2 * rho * h - h * h);
  return kPi * rho * rho - above;
}

// Q(X, Y) by quadrature of the section areas over x: pieces split at the kinks x = +-c (the chord
// touches the section), the piece |x| < c mapped by x = c sin(phi) to remove the square roots.
double cornerByQuadrature(double X, double Y, double r) {
  static std::vector<double> gx, gw;
  if (gx.empty()) gaussLegendre(32, gx, gw);
  auto S = [&](double x) { return segmentBelow(std::sqrt(std::max(r * r - x * x, 0.0)), Y); };
  auto plain = [&](double a, double b) {  // smooth (polynomial) integrand
    if (b <= a) return 0.0;
    double s = 0;
    for (size_t k = 0; k < gx.size(); ++k) s += gw[k] * S(0.5 * (a + b) + 0.5 * (b - a) * gx[k]);
    return 0.5 * (b - a) * s;
  };
  const double Xh = std::min(std::max(X, -r), r);
  if (std::fabs(Y) >= r) return plain(-r, Xh);
  const double c = std::sqrt(r * r - Y * Y);
  double v = plain(-r, std::min(Xh, -c));
  if (Xh > -c) {
    // asin(Y / rho) = atan(Y / (c cos(phi))) turns over a width ~ |Y| / c near phi = +-pi/2:
    // panels graded geometrically towards both ends resolve it for any Y.
    const double p1 = std::asin(std::min(Xh, c) / c);
    std::vector<double> edges;
    for (int k = 50; k >= 1; --k) edges.push_back(-kPi / 2 + kPi / 2 * std::ldexp(1.0, -k));
    edges.push_back(0.0);
    for (int k = 1; k <= 50; ++k) edges.push_back(kPi / 2 - kPi / 2 * std::ldexp(1.0, -k));
    edges.push_back(kPi / 2);
    double lo = -kPi / 2;
    for (double hi : edges) {
      const double b = std::min(hi, p1);
      if (b > lo) {
        double s = 0;
        for (size_t k = 0; k < gx.size(); ++k) {
          const double phi = 0.5 * (lo + b) + 0.5 * (b - lo) * gx[k];
          s += gw[k] * S(c * std::sin(phi)) * c * std::cos(phi);
        }
        v += 0.5 * (b - lo) * s;
      }
      lo = hi;
      if (lo >= p1) break;
    }
  }
  if (Xh > c) v += plain(c, Xh);
  return v;
}

}  // namespace

TEST(SphereBinVolume, CornerFunctionMatchesQuadrature) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.3, 1.3);
  const double r = 0.012;
  double worst = 0;
  for (int k = 0; k < 2000; ++k) {
    const double X = u(rng) * r, Y = u(rng) * r;
    worst = std::max(worst, std::fabs(sphereCornerVolume(X, Y, r) - cornerByQuadrature(X, Y, r)));
  }
  // Special points: the chord through the centre, tangent chords, corners at the sphere's edge.
  for (double X : {-r, -0.5 * r, 0.0, 0.7 * r, r})
    for (double Y : {-r, -0.999999 * r, 0.0, 1e-9 * r, 0.999999 * r, r})
      worst = std::max(worst, std::fabs(sphereCornerVolume(X, Y, r) - cornerByQuadrature(X, Y, r)));
  std::printf("worst |Q - quadrature| = %.3g r^3\n", worst / (r * r * r));
  EXPECT_LT(worst, 1e-13 * r * r * r);
  EXPECT_NEAR(sphereCornerVolume(2 * r, 2 * r, r), sphereVolume(r), 1e-16);
  EXPECT_NEAR(sphereCornerVolume(0, 2 * r, r), 0.5 * sphereVolume(r), 1e-17);
  EXPECT_NEAR(sphereCornerVolume(0, 0, r), 0.25 * sphereVolume(r), 1e-17);
}

TEST(SphereBinVolume, SymmetricInXAndY) {
  const double r = 1.0;
  for (double X : {-0.8, -0.1, 0.3, 0.95})
    for (double Y : {-0.6, 0.2, 0.9})
      EXPECT_NEAR(sphereCornerVolume(X, Y, r), sphereCornerVolume(Y, X, r), 4e-15 * r * r * r);
}

TEST(SphereBinVolume, SlabsMatchDemObservable) {
  const double r = 0.012, yc = 0.3;
  for (double a : {0.28, 0.29, 0.2995, 0.3, 0.305}) {
    for (double b : {0.3001, 0.305, 0.311, 0.32}) {
      const double ref = mixflow::dem::sphereSlabVolume(yc, r, a, b);
      const double v = sphereRectVolume(1.0, yc, r, 0.0, 2.0, a, b);
      EXPECT_NEAR(v, ref, 1e-15 * sphereVolume(r) + 1e-13 * ref) << a << " " << b;
    }
  }
}

// Volume conservation: the pieces of every particle sum to its volume, and the binned total equals
// the particles' total volume, to 1e-12 relative (bins smaller and larger than the particles).
TEST(SphereBinVolume, TotalParticleVolumeIsConserved) {
  std::mt19937_64 rng(11);
  for (const auto& [nx, ny] : std::vector<std::pair<int, int>>{{7, 5}, {40, 30}, {160, 90}}) {
    const AveragingGrid g(0.0, 0.8, nx, 0.0, 0.45, ny, 0.1);
    std::uniform_real_distribution<double> ux(0.06, 0.74), uy(0.06, 0.39), ur(0.002, 0.05);
    ParticleSnapshot s;
    double total = 0;
    std::vector<std::pair<int, double>> pieces;
    double worstOne = 0;
    for (int k = 0; k < 3000; ++k) {
      const double x = ux(rng), y = uy(rng), r = ur(rng);
      pieces.clear();
      const double in = g.splitSphere(x, y, r, pieces);
      double sum = 0;
      for (const auto& p : pieces) sum += p.second;
      worstOne = std::max(worstOne, std::fabs(sum - sphereVolume(r)) / sphereVolume(r));
      EXPECT_EQ(in, sum);
      s.x.push_back(x);
      s.y.push_back(y);
      s.z.push_back(0.05);
      s.vx.push_back(0);
      s.vy.push_back(0);
      s.vz.push_back(0);
      s.radius.push_back(r);
      s.mass.push_back(2500 * sphereVolume(r));
      s.stress.push_back({});
      total += sphereVolume(r);
    }
    CoarseGrainKernel bins(g, "bins", 0);
    BinAccumulator acc(g, bins, true, 0);
    acc.addSnapshot(s);
    double binned = 0;
    for (const auto& b : acc.bins()) binned += b.particleVolume;
    std::printf("grid %d x %d: worst single-particle error %.3g, total relative error %.3g\n", nx,
                ny, worstOne, std::fabs(binned - total) / total);
    EXPECT_LT(worstOne, 1e-12);
    EXPECT_LT(std::fabs(binned - total) / total, 1e-12);
    EXPECT_LT(acc.volumeOutsideGrid(), 1e-12 * total);
  }
}

// Uniform lattice: a simple cubic lattice (spacing a, r = 0.45 a, offset so that particles
// straddle every bin edge) gives alpha_s = (4/3 pi r^3) / a^3 in every bin when the bins are whole
// multiples of the lattice period.
TEST(SphereBinVolume, UniformLatticeGivesExactAlphaInEveryBin) {
  const double a = 0.01, r = 0.45 * a, W = 4 * a;
  const AveragingGrid g(0.0, 0.2, 10, 0.0, 0.12, 4, W);  // bins 2a x 3a x 4a
  ParticleSnapshot s;
  for (int i = -2; i < 23; ++i)
    for (int j = -2; j < 15; ++j)
      for (int k = 0; k < 4; ++k) {
        s.x.push_back((i + 0.3) * a);
        s.y.push_back((j + 0.17) * a);
        s.z.push_back((k + 0.5) * a);
        s.vx.push_back(0);
        s.vy.push_back(0);
        s.vz.push_back(0);
        s.radius.push_back(r);
        s.mass.push_back(1.0);
        s.stress.push_back({});
      }
  CoarseGrainKernel bins(g, "bins", 0);
  BinAccumulator acc(g, bins, false, 0);
  acc.addSnapshot(s);
  const double exact = sphereVolume(r) / (a * a * a);
  double worst = 0;
  for (const auto& b : acc.bins())
    worst = std::max(worst, std::fabs(b.particleVolume / g.binVolume() - exact) / exact);
  std::printf("lattice alpha_s = %.15f, worst relative deviation over %d bins %.3g\n", exact,
              g.size(), worst);
  EXPECT_LT(worst, 1e-12);
}

TEST(AveragingGrid, LocateUsesHalfOpenBins) {
  const AveragingGrid g(0.0, 1.0, 10, 0.0, 0.3, 3, 0.1);
  EXPECT_EQ(g.locate(0.0, 0.0), 0);
  EXPECT_EQ(g.locate(0.1, 0.0), 1);
  EXPECT_EQ(g.locate(0.3, 0.1), g.index(3, 1));
  EXPECT_EQ(g.locate(0.999999, 0.299999), g.index(9, 2));
  EXPECT_EQ(g.locate(1.0, 0.1), -1);
  EXPECT_EQ(g.locate(-1e-12, 0.1), -1);
  EXPECT_EQ(g.locate(0.5, 0.3), -1);
}
