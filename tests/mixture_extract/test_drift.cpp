// Mixture variables and drift coefficients on synthetic particle and fluid fields
// (mixture_extract/BinAccumulator, DriftCoefficients, WindowResult).
//   u_f = 1.3 u_s gives lambda_u = 1.3 to round-off (and the Lambda of Eq. 36);
//   p_s of a static gravity-loaded packing equals the weight of the
//     material above the bin;
//   bins with u_s = 0 (and without particles, with p_s = 0) are masked and counted,
//     with floating-point traps on: nothing divides by zero;
//   u_f masked where the bin holds little liquid, p_s masked without particle samples;
//   streaming stress and the Eq. 9 residual on fields with known answers.
#include <fenv.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "AveragingGrid.h"
#include "BinAccumulator.h"
#include "DriftCoefficients.h"
#include "ExtractSettings.h"
#include "FluidSource.h"
#include "SphereBinVolume.h"
#include "WindowResult.h"

using namespace mixflow::mx;

namespace {

constexpr double g0 = 9.81;

void addParticle(ParticleSnapshot& s, double x, double y, double z, double r, double rho,
                 double vx = 0, double vy = 0, double vz = 0, std::array<double, 6> c = {}) {
  s.x.push_back(x);
  s.y.push_back(y);
  s.z.push_back(z);
  s.vx.push_back(vx);
  s.vy.push_back(vy);
  s.vz.push_back(vz);
  s.radius.push_back(r);
  s.mass.push_back(rho * sphereVolume(r));
  s.stress.push_back(c);
}

ExtractSettings baseSettings(const AveragingGrid& g) {
  ExtractSettings s;
  s.x0 = g.x0();
  s.x1 = g.x1();
  s.nx = g.nx();
  s.y0 = g.y0();
  s.y1 = g.y1();
  s.ny = g.ny();
  s.solidDensity = 2500;
  s.liquidDensity = 1000;
  s.regions.push_back({"all", g.x0(), g.x1(), g.y0(), g.y1()});
  return s;
}

// Floating-point traps for the scope: a division by zero or an invalid operation aborts the test.
struct FpTraps {
  FpTraps() {
    feclearexcept(FE_ALL_EXCEPT);
    feenableexcept(FE_DIVBYZERO | FE_INVALID | FE_OVERFLOW);
  }
  ~FpTraps() { fedisableexcept(FE_ALL_EXCEPT); }
};

}  // namespace

// Lambda_u: particles jittered across bin edges, uniform velocity per snapshot changing in
// time, fluid at 1.3 times the particle velocity. lambda_u = lambda_w = 1.3 to round-off.
TEST(Drift, LambdaOfUniformDriftIsExact) {
  const AveragingGrid g(0.0, 0.3, 6, 0.0, 0.2, 4, 0.05);
  const double d = 0.012, r = d / 2;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> jit(-0.2 * d, 0.2 * d);
  ParticleSnapshot base;
  for (double x = 0.5 * d; x < 0.3; x += 1.05 * d)
    for (double y = 0.5 * d; y < 0.2; y += 1.05 * d)
      for (double z = 0.5 * d; z < 0.05; z += 1.05 * d)
        addParticle(base, x + jit(rng), y + jit(rng), z, r, 2500);
  auto U = [](double t) { return 0.4 + 0.3 * std::sin(7 * t); };
  auto Wv = [](double t) { return -0.05 - 0.02 * std::cos(5 * t); };
  const std::vector<double> times = {0.0, 0.01, 0.02, 0.03, 0.04};
  SyntheticFluidSource fluid(0.0, 0.3, 12, 0.0, 0.2, 8, 0.05, times, [&](double, double, double t) {
    FluidState f;
    f.alphaL = 1;
    f.epsF = 0.45;
    f.ux = 1.3 * U(t);
    f.uy = 1.3 * Wv(t);
    f.p = 500;
    return f;
  });
  CoarseGrainKernel bins(g, "bins", 0);
  BinAccumulator acc(g, bins, true, 0);
  for (double t : times) {
    ParticleSnapshot s = base;
    s.time = t;
    for (size_t i = 0; i < s.size(); ++i) {
      s.vx[i] = U(t);
      s.vy[i] = Wv(t);
      // Static contacts (compressive, isotropic), dumped with the LAMMPS kinetic term -m v v.
      const double c = -200.0 * sphereVolume(r);
      s.stress[i] = {c - s.mass[i] * s.vx[i] * s.vx[i],
                     c - s.mass[i] * s.vy[i] * s.vy[i],
                     c,
                     -s.mass[i] * s.vx[i] * s.vy[i],
                     0,
                     0};
    }
    acc.addSnapshot(s);
    acc.addFluid(fluid.cells(t));
  }
  const ExtractSettings st = baseSettings(g);
  const WindowResult res = finaliseWindow({0.0, 0.05, "test"}, acc, g, st);
  double worst = 0;
  int checked = 0;
  for (const MixtureValues& m : res.bins) {
    ASSERT_TRUE(m.valid(fLambdaU)) << m.reasons;
    ASSERT_TRUE(m.valid(fLambdaW)) << m.reasons;
    worst =
        std::max({worst, std::fabs(m.value[fLambdaU] - 1.3), std::fabs(m.value[fLambdaW] - 1.3)});
    const double as = m.value[fAlphaS], af = 1 - as, l = 1.3;
    EXPECT_NEAR(m.value[fLu], 1 / (as + l * af), 1e-13);
    EXPECT_NEAR(m.value[fLuu], (as + l * l * af) / ((as + l * af) * (as + l * af)), 1e-13);
    EXPECT_NEAR(m.value[fLuw], (as + l * l * af) / ((as + l * af) * (as + l * af)), 1e-13);
    EXPECT_NEAR(m.value[fLetaMFluidCoeff], af * l / (as + l * af), 1e-13);
    EXPECT_NEAR(m.value[fUm], (as + l * af) * m.value[fUs], 1e-13);
    // Uniform velocity in a snapshot: no fluctuation, so p_s is the contact pressure 200 Pa x
    // alpha.
    EXPECT_NEAR(m.value[fPsKinetic], 0.0, 1e-12);
    EXPECT_NEAR(m.value[fPs], 200.0 * as, 1e-9);
    EXPECT_NEAR(m.value[fLambdaPRaw], 500.0 / (200.0 * as), 1e-9);
    EXPECT_NEAR(m.value[fLambdaPDensity], (500.0 / 1000) / (200.0 * as / 2500), 1e-9);
    ++checked;
  }
  std::printf("lambda_u, lambda_w: worst |lambda - 1.3| = %.3g over %d bins\n", worst, checked);
  EXPECT_LT(worst, 1e-13);
  EXPECT_NEAR(res.regions[0].values.value[fLambdaU], 1.3, 1e-13);
}

// Granular pressure (synthetic): simple cubic lattice of touching spheres (spacing d) on the floor,
// 12 layers; each particle carries the LIGGGHTS-like contact stress x volume of a hydrostatic-like
// column (K = 1): C_i = -P_i d^3 I with P_i = m g (n_above + 1/2) / d^2, the weight of the
// particles above its centre per unit area. The bins' p_s must equal the weight of material above
// the bin's centre, rho_s g int alpha_s dy (from the extracted alpha_s), to 1e-12 relative, for
// bins holding 1, 2, 3 or 4 whole layers and x edges cutting through the particles (3 bins over 20
// particles). (Bins that cut through a perfectly layered packing see alpha_s oscillate by +-8 %
// and p_s off the continuum weight by up to half a layer: a property of the layering, checked on
// a real random packing in extract.static_packing.)
TEST(Drift, StaticColumnPressureIsTheWeightAbove) {
  const double d = 0.01, r = d / 2, rho = 2500, m = rho * sphereVolume(r);
  const int layers = 12;
  ParticleSnapshot s;
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < layers; ++j)
      for (int k = 0; k < 3; ++k) {
        const double P = m * g0 * (layers - j - 1 + 0.5) / (d * d);
        const double c = -P * d * d * d;
        addParticle(s, (i + 0.5) * d, (j + 0.5) * d, (k + 0.5) * d, r, rho, 0, 0, 0,
                    {c, c, c, 0, 0, 0});
      }
  for (const int ny : {12, 6, 4, 3}) {
    const AveragingGrid g(0.0, 0.2, 3, 0.0, layers * d, ny, 3 * d);
    CoarseGrainKernel bins(g, "bins", 0);
    BinAccumulator acc(g, bins, false, 0);
    acc.addSnapshot(s);
    const WindowResult res = finaliseWindow({0, 1, "test"}, acc, g, baseSettings(g));
    double worst = 0;
    for (int i = 0; i < g.nx(); ++i)
      for (int j = 0; j < g.ny(); ++j) {
        double above = 0.5 * res.bins[g.index(i, j)].value[fAlphaS] * g.dy();
        for (int jj = j + 1; jj < g.ny(); ++jj)
          above += res.bins[g.index(i, jj)].value[fAlphaS] * g.dy();
        const double weight = rho * g0 * above;
        const double ps = res.bins[g.index(i, j)].value[fPs];
        worst = std::max(worst, std::fabs(ps - weight) / weight);
        EXPECT_NEAR(res.bins[g.index(i, j)].value[fSigmaYY], -ps, 1e-9 * weight);
      }
    std::printf(
        "static column, %d bins over the height: worst |p_s - weight above| / weight = %.3g\n", ny,
        worst);
    EXPECT_LT(worst, 1e-12);
  }
}

// Masks: a moving left half, a static right half (u_s = w_s = 0 exactly, no contact
// stress: p_s = 0), an empty top row, liquid everywhere. Static bins: lambda_u, lambda_w,
// lambda_p masked with their reasons and counted; empty bins: no_particles; nothing divides by
// zero (floating-point traps on while everything is computed).
TEST(Drift, ZeroVelocityBinsAreMaskedAndCounted) {
  const AveragingGrid g(0.0, 0.24, 4, 0.0, 0.12, 3, 0.03);  // bins 0.06 x 0.04
  const double d = 0.01, r = d / 2;
  ParticleSnapshot s;
  for (double x = r; x < 0.24; x += d)
    for (double y = r; y < 0.08; y += d)
      for (double z = r; z < 0.03; z += d) {
        const bool moving = x < 0.12 - r;  // whole particles on each side of x = 0.12
        const double c = moving ? -300 * sphereVolume(r) : 0.0;
        addParticle(s, x, y, z, r, 2500, moving ? 0.5 : 0.0, moving ? 0.1 : 0.0, 0,
                    {c, c, c, 0, 0, 0});
      }
  // Particles straddle x = 0.12? No: centres at 0.115 and 0.125 with r = 0.005 touch it only.
  SyntheticFluidSource fluid(0.0, 0.24, 8, 0.0, 0.12, 6, 0.03, {0.0}, [](double x, double, double) {
    FluidState f;
    f.epsF = 0.5;
    f.ux = x < 0.12 ? 0.6 : 0.01;
    f.p = 100;
    return f;
  });
  ExtractSettings st = baseSettings(g);
  WindowResult res;
  {
    FpTraps traps;
    CoarseGrainKernel bins(g, "bins", 0);
    BinAccumulator acc(g, bins, false, 0);
    acc.addSnapshot(s);
    acc.addFluid(fluid.cells(0.0));
    res = finaliseWindow({0, 1, "test"}, acc, g, st);
  }
  int maskedU = 0, maskedP = 0, noParticles = 0;
  for (int j = 0; j < g.ny(); ++j)
    for (int i = 0; i < g.nx(); ++i) {
      const MixtureValues& m = res.bins[g.index(i, j)];
      const bool empty = j == 2, moving = i < 2;
      if (empty) {
        EXPECT_TRUE(m.reasons & kNoParticles);
        EXPECT_FALSE(m.valid(fUs));
        EXPECT_TRUE(std::isnan(m.value[fUs]));
        // No particle sample: p_s and the stress are masked (kParticleMask), never a valid 0.
        for (FieldId f : {fPs, fPsContact, fPsKinetic, fSigmaXX, fSigmaYY, fSigmaZZ, fSigmaXY})
          EXPECT_FALSE(m.valid(f)) << fieldDef(f).name;
        EXPECT_TRUE(m.valid(fAlphaS));  // alpha_s = 0 is the answer, not a missing value
        EXPECT_FALSE(m.valid(fLambdaPRaw));
        ++noParticles;
      } else if (moving) {
        EXPECT_TRUE(m.valid(fLambdaU)) << m.reasons;
        EXPECT_NEAR(m.value[fLambdaU], 1.2, 1e-12);
        EXPECT_TRUE(m.valid(fLambdaPRaw));
      } else {
        EXPECT_EQ(m.value[fUs], 0.0);
        EXPECT_TRUE(m.reasons & kSmallUs);
        EXPECT_TRUE(m.reasons & kSmallWs);
        EXPECT_TRUE(m.reasons & kSmallPs);
        EXPECT_FALSE(m.valid(fLambdaU));
        EXPECT_FALSE(m.valid(fLuu));
        EXPECT_FALSE(m.valid(fLambdaPDensity));
        EXPECT_TRUE(std::isnan(m.value[fLambdaU]));
        EXPECT_TRUE(std::isnan(m.value[fLu]));
        EXPECT_TRUE(m.valid(fUm));  // the mixture velocity needs no ratio
        EXPECT_NEAR(m.value[fUm], (1 - m.value[fAlphaS]) * 0.01, 1e-15);
      }
      maskedU += !m.valid(fLambdaU);
      maskedP += (m.reasons & kSmallPs) != 0;
      for (int f = 0; f < kFieldCount; ++f) {
        if (m.valid(static_cast<FieldId>(f)) && f != fLetaU && f != fLetaW && f != fLetaM) {
          EXPECT_TRUE(std::isfinite(m.value[f])) << fieldDef(static_cast<FieldId>(f)).name;
        }
      }
    }
  std::printf("lambda_u masked in %d of %d bins (%d static, %d empty); small_p_s in %d\n", maskedU,
              g.size(), 4, noParticles, maskedP);
  EXPECT_EQ(maskedU, 8);
  EXPECT_EQ(noParticles, 4);
  EXPECT_EQ(maskedP, 4);
}

// u_f, w_f, p_f are masked (little_liquid) where the liquid share of the bin's fluid
// volume is below thresholds.minLiquidShare (default 0.01): a bin whose only "liquid" is a VOF
// interface's smeared tail (alpha_l = 5e-8) moving with the air (7.9 m/s) gives no u_f; a bin at
// the threshold keeps it. p_s needs thresholds.minParticleSamples samples (bins with one sample
// keep it when the threshold is 1, lose it when it is 2).
TEST(Drift, LittleLiquidAndFewParticlesAreMasked) {
  const AveragingGrid g(0.0, 0.3, 3, 0.0, 0.1, 1, 0.05);  // three bins side by side
  ParticleSnapshot s;
  const double r = 0.005, c = -300 * sphereVolume(r);
  for (double x : {0.05, 0.15, 0.25}) addParticle(s, x, 0.05, 0.025, r, 2500, 0.5, 0, 0, {c, c, c});
  const std::vector<double> alpha = {5e-8, 0.01, 1.0};
  SyntheticFluidSource fluid(0.0, 0.3, 3, 0.0, 0.1, 1, 0.05, {0.0}, [&](double x, double, double) {
    FluidState f;
    f.alphaL = alpha[static_cast<int>(x / 0.1)];
    f.ux = x < 0.1 ? 7.9 : 0.6;
    f.p = 100;
    return f;
  });
  CoarseGrainKernel bins(g, "bins", 0);
  BinAccumulator acc(g, bins, false, 0);
  acc.addSnapshot(s);
  acc.addFluid(fluid.cells(0.0));
  ExtractSettings st = baseSettings(g);
  const WindowResult res = finaliseWindow({0, 1, "test"}, acc, g, st);
  const MixtureValues &smear = res.bins[0], &edge = res.bins[1], &full = res.bins[2];
  EXPECT_NEAR(smear.value[fSaturation], 5e-8, 1e-20);
  EXPECT_TRUE(smear.valid(fSaturation));
  EXPECT_TRUE(smear.reasons & kLittleLiquid);
  for (FieldId f : {fUf, fWf, fPf, fUm, fLambdaU}) EXPECT_FALSE(smear.valid(f)) << fieldDef(f).name;
  EXPECT_FALSE(edge.reasons & kLittleLiquid) << "saturation 0.01 is at the threshold";
  EXPECT_TRUE(edge.valid(fUf));
  EXPECT_TRUE(full.valid(fUf));
  EXPECT_NEAR(full.value[fUf], 0.6, 1e-15);
  for (const MixtureValues& m : res.bins) EXPECT_TRUE(m.valid(fPs));
  st.thresholds.minParticleSamples = 2;
  const WindowResult few = finaliseWindow({0, 1, "test"}, acc, g, st);
  for (const MixtureValues& m : few.bins) {
    EXPECT_TRUE(m.reasons & kFewParticleSamples);
    EXPECT_FALSE(m.valid(fPs));
    EXPECT_FALSE(m.valid(fUs));
  }
  std::printf("u_f at saturation 5e-8: masked (reasons %u); at 0.01: %.3g m/s, valid\n",
              smear.reasons, edge.value[fUf]);
}

// Streaming stress: two particles in one bin moving at +-v0 along x on top of a mean drift, the
// dumped stress carrying only the LAMMPS kinetic term (no contacts): p_s = 2 m v0^2 / (3 V_bin).
TEST(Drift, StreamingStressUsesFluctuationsAboutTheBinMean) {
  const AveragingGrid g(0.0, 0.1, 1, 0.0, 0.1, 1, 0.1);
  const double r = 0.01, v0 = 0.3, drift = 2.0;
  ParticleSnapshot s;
  for (double sgn : {-1.0, 1.0}) {
    const double vx = drift + sgn * v0, m = 2500 * sphereVolume(r);
    addParticle(s, 0.05 + sgn * 0.02, 0.05, 0.05, r, 2500, vx, 0, 0, {-m * vx * vx, 0, 0, 0, 0, 0});
  }
  CoarseGrainKernel bins(g, "bins", 0);
  BinAccumulator acc(g, bins, true, 0);
  acc.addSnapshot(s);
  const WindowResult res = finaliseWindow({0, 1, "test"}, acc, g, baseSettings(g));
  const double m = 2500 * sphereVolume(r);
  EXPECT_NEAR(res.bins[0].value[fPsContact], 0.0, 1e-12);
  EXPECT_NEAR(res.bins[0].value[fPsKinetic], 2 * m * v0 * v0 / (3 * g.binVolume()), 1e-12);
  EXPECT_NEAR(res.bins[0].value[fSigmaXX], -2 * m * v0 * v0 / g.binVolume(), 1e-11);
}

// Eq. 9: a lattice (alpha_s uniform, bins whole multiples of the period) with particle and fluid
// velocities linear in position. A divergence-free field (u = c x, w = -c y) gives a zero
// residual to round-off; u = c x, w = 0 gives the divergence c.
TEST(Drift, MassBalanceResidual) {
  const double a = 0.01, r = 0.4 * a, W = 2 * a;
  const AveragingGrid g(0.0, 0.12, 6, 0.0, 0.08, 4, W);
  for (const double wSign : {-1.0, 0.0}) {
    const double c = 3.0;
    ParticleSnapshot s;
    for (int i = -1; i < 13; ++i)
      for (int j = -1; j < 9; ++j)
        for (int k = 0; k < 2; ++k) {
          const double x = (i + 0.5) * a, y = (j + 0.5) * a;
          addParticle(s, x, y, (k + 0.5) * a, r, 2500, c * x, wSign * c * y, 0);
        }
    SyntheticFluidSource fluid(0.0, 0.12, 6, 0.0, 0.08, 4, W, {0.0},
                               [&](double x, double y, double) {
                                 FluidState f;
                                 f.ux = c * x;
                                 f.uy = wSign * c * y;
                                 return f;
                               });
    CoarseGrainKernel bins(g, "bins", 0);
    BinAccumulator acc(g, bins, false, 0);
    acc.addSnapshot(s);
    acc.addFluid(fluid.cells(0.0));
    const WindowResult res = finaliseWindow({0, 1, "test"}, acc, g, baseSettings(g));
    double worst = 0;
    for (const auto& m : res.bins) {
      ASSERT_TRUE(m.valid(fMassResidual)) << m.reasons;
      worst = std::max(worst, std::fabs(m.value[fMassResidual] - (wSign == 0 ? c : 0.0)));
    }
    std::printf("Eq. 9 residual, %s field: worst error %.3g 1/s (scale %g 1/s)\n",
                wSign == 0 ? "divergent" : "divergence-free", worst, c);
    EXPECT_LT(worst, 1e-11);
  }
}

// The pore pressure's split on a column with a known answer: grains (the static column's contact
// stress) in liquid up to h = 0.13 m (the cell holding the surface half liquid), air above, the
// fluid's p offset by a gauge P0 = -5 Pa (the top boundary's zero, not the surface's) and, in the
// right column only, an excess E(y) = 0.3 rho_f g (h - y) on the liquid. Left column: p_f_excess
// = 0 and chi = 0 to the air's weight over 1.5 bins (rho_air g 0.03 m = 0.29 Pa); right column:
// p_f_excess = E at the bin centres, chi = E / (p_s + E). A column liquid to its top bin has no
// surface in the grid and is masked (no_liquid_surface).
TEST(Drift, PorePressureSplitsIntoHydrostaticAndExcess) {
  const double h = 0.13, rhoF = 1000, rhoAir = 1, p0 = -5, d = 0.01, r = d / 2;
  const AveragingGrid g(0.0, 0.06, 3, 0.0, 0.2, 10, 0.03);  // bins 0.02 x 0.02
  ParticleSnapshot s;
  const int layers = 8;  // grains to y = 0.08
  const double m = 2500 * sphereVolume(r);
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < layers; ++j)
      for (int k = 0; k < 3; ++k) {
        const double c = -m * g0 * (layers - j - 0.5) * d;  // the weight above times d, as above
        addParticle(s, (i + 0.5) * d, (j + 0.5) * d, (k + 0.5) * d, r, 2500, 0, 0, 0,
                    {c, c, c, 0, 0, 0});
      }
  auto excess = [&](double x, double y) {
    return x > 0.04 && y < h ? 0.3 * rhoF * g0 * (h - y) : 0;
  };
  SyntheticFluidSource fluid(
      0.0, 0.06, 3, 0.0, 0.2, 10, 0.03, {0.0}, [&](double x, double y, double) {
        FluidState f;
        // The third column is liquid to the top (its surface outside the grid).
        const bool full = x > 0.02 && x < 0.04;
        f.alphaL = full || y < 0.12 ? 1.0 : (y < 0.14 ? 0.5 : 0.0);
        f.p = p0 + (full ? rhoF * g0 * (0.2 - y)
                         : (y < h ? rhoF * g0 * (h - y) : rhoAir * g0 * (h - y)) + excess(x, y));
        return f;
      });
  CoarseGrainKernel bins(g, "bins", 0);
  BinAccumulator acc(g, bins, false, 0);
  acc.addSnapshot(s);
  acc.addFluid(fluid.cells(0.0));
  const ExtractSettings st = baseSettings(g);
  const WindowResult res = finaliseWindow({0, 1, "test"}, acc, g, st);
  const std::vector<double> yc = g.yCentres();
  for (int j = 0; j < 6; ++j) {  // the liquid rows below the surface's bin
    const MixtureValues &left = res.bins[g.index(0, j)], &right = res.bins[g.index(2, j)];
    ASSERT_TRUE(left.valid(fPfExcess) && right.valid(fPfExcess)) << "row " << j;
    EXPECT_NEAR(left.value[fPfHydrostatic], p0 + rhoF * g0 * (h - yc[j]), 0.3) << "row " << j;
    EXPECT_LE(std::fabs(left.value[fPfExcess]), rhoAir * g0 * 0.03) << "row " << j;
    EXPECT_NEAR(right.value[fPfExcess], excess(0.05, yc[j]), rhoAir * g0 * 0.03) << "row " << j;
    if (j < 4) {  // the grains' rows: the mixture
      ASSERT_TRUE(left.valid(fPoreRatio) && right.valid(fPoreRatio)) << "row " << j;
      EXPECT_LE(std::fabs(left.value[fPoreRatio]), 0.01) << "row " << j;
      const double e = right.value[fPfExcess];
      EXPECT_NEAR(right.value[fPoreRatio], e / (right.value[fPs] + e), 1e-12) << "row " << j;
      EXPECT_NEAR(right.value[fPTotal], right.value[fPs] + right.value[fPf], 1e-9);
    }
  }
  for (int j = 0; j < g.ny(); ++j) {
    const MixtureValues& full = res.bins[g.index(1, j)];
    EXPECT_TRUE(full.reasons & kNoLiquidSurface) << "row " << j;
    EXPECT_FALSE(full.valid(fPfExcess));
    EXPECT_FALSE(full.valid(fPoreRatio));
  }
  std::printf(
      "pore pressure: left column chi %.2e (bottom row), right %.4f (excess %.1f Pa, p_s %.1f "
      "Pa)\n",
      res.bins[g.index(0, 0)].value[fPoreRatio], res.bins[g.index(2, 0)].value[fPoreRatio],
      res.bins[g.index(2, 0)].value[fPfExcess], res.bins[g.index(2, 0)].value[fPs]);
}
