// Unit tests of the bulk model's algebra (common/DriftAlgebra.h) against exact
// identities of the quasi two-phase model (docs/bulk_model.md) and the paper's own numbers.
#include <gtest/gtest.h>

#include <cmath>

#include "DriftAlgebra.h"

using namespace mixflow::bulk;

namespace {

// Lambda_uu - 1 = alpha_s alpha_f (1 - lambda_u)^2 Lambda_u^2, and its w and uw twins: the
// Lambda-weighted convection is u_m u_m plus the drift stress (checked at alpha_s 0.6, lambda 1.7:
// 0.07178 both ways).
TEST(DriftAlgebra, InertialCoefficientsAreOnePlusDriftStress) {
  const double a = 0.6, f = 0.4;
  const Drifts d{1.7, 0.8, 1.1};
  const LambdaCoefficients c = lambdaCoefficients(a, d);
  EXPECT_NEAR(c.uu - 1, a * f * std::pow(1 - d.lambdaU, 2) * c.u * c.u, 1e-14);
  EXPECT_NEAR(c.ww - 1, a * f * std::pow(1 - d.lambdaW, 2) * c.w * c.w, 1e-14);
  EXPECT_NEAR(c.uw - 1, a * f * (1 - d.lambdaU) * (1 - d.lambdaW) * c.u * c.w, 1e-14);
  EXPECT_NEAR(lambdaCoefficients(0.6, {1.7, 1.7, 1}).uu - 1, 0.07178, 5e-6);

  // The same as a stress: Lambda_ij u_mi u_mj = u_mi u_mj + tau_D,ij for any u_m.
  const Vec2 um{0.7, -0.3};
  const Sym2 t = driftStress(a, d, um);
  EXPECT_NEAR(c.uu * um.x * um.x, um.x * um.x + t.xx, 1e-14);
  EXPECT_NEAR(c.uw * um.x * um.y, um.x * um.y + t.xy, 1e-14);
  EXPECT_NEAR(c.ww * um.y * um.y, um.y * um.y + t.yy, 1e-14);
}

TEST(DriftAlgebra, Limits) {
  const Drifts d{2.5, 0.4, 0.7};
  // alpha_s = 0: every inertial Lambda is 1 and the diffusivity is the fluid's, for any lambda.
  const LambdaCoefficients c0 = lambdaCoefficients(0, d);
  EXPECT_DOUBLE_EQ(c0.uu, 1);
  EXPECT_DOUBLE_EQ(c0.ww, 1);
  EXPECT_DOUBLE_EQ(c0.uw, 1);
  EXPECT_NEAR(mixtureDiffusivity(0, d, 5.0, 1e-3), 1e-3, 1e-15);
  // alpha_s = 1: all Lambda 1, the diffusivity is the solid's.
  const LambdaCoefficients c1 = lambdaCoefficients(1, d);
  EXPECT_DOUBLE_EQ(c1.uu, 1);
  EXPECT_DOUBLE_EQ(c1.u, 1);
  EXPECT_DOUBLE_EQ(c1.p, 1);
  EXPECT_NEAR(mixtureDiffusivity(1, d, 5.0, 1e-3), 5.0, 1e-14);
  // lambda = 1: the reduced model, nu_s alpha_s + nu_f alpha_f (P-Eqs. 59-61).
  EXPECT_NEAR(mixtureDiffusivity(0.3, {}, 5.0, 1e-3), 0.3 * 5.0 + 0.7 * 1e-3, 1e-14);
}

// P-Eq. 44 equals the diffusivity for isotropic drifts, P-Eq. 46 inverts it, and the paper's fit
// P-Eq. 45 (Lambda0 = 4.99, chi = 0.5, xi = 0.97) follows P-Eq. 44 at alpha_s = 0.25 with
// nu_f = 1e-3 m2/s: 2.04, 1.30, 0.69, 0.26 against 2.00, 1.25, 0.71, 0.31 at lambda 0.5, 1, 2, 5.
TEST(DriftAlgebra, PaperMixtureViscosity) {
  const double nuS = 4.99, nuF = 1e-3, a = 0.25;
  const double lambdas[] = {0.5, 1, 2, 5};
  const double eq44[] = {2.00, 1.25, 0.71, 0.31};
  for (int i = 0; i < 4; ++i) {
    const double l = lambdas[i];
    const double m = isotropicMixtureViscosity(a, l, nuS, nuF);
    EXPECT_NEAR(m, mixtureDiffusivity(a, {l, l, 1}, nuS, nuF), 1e-12);
    EXPECT_NEAR(m, eq44[i], 0.006) << "lambda " << l;
    EXPECT_NEAR(lambdaFromMixtureViscosity(a, m, nuS, nuF), l, 1e-10);
    const double fit = nuS * (1 - 0.97 * std::tanh(std::sqrt(l)));
    EXPECT_NEAR(fit, m, 0.06) << "fit against P-Eq. 44 at lambda " << l;
  }
}

// u_m -> u_s, u_f -> alpha_s u_s + alpha_f u_f is the identity; pressures p_s = p_m / Lambda_p.
TEST(DriftAlgebra, ReconstructionRoundTrip) {
  const double a = 0.45;
  const Drifts d{1.3, 0.6, 0.9};
  const Vec2 um{1.2, -0.4};
  const Vec2 back = mixtureVelocity(a, solidVelocity(a, d, um), fluidVelocity(a, d, um));
  EXPECT_NEAR(back.x, um.x, 1e-14);
  EXPECT_NEAR(back.y, um.y, 1e-14);
  const double pm = 3.0;
  EXPECT_NEAR(a * solidPressure(a, d, pm) + (1 - a) * fluidPressure(a, d, pm), pm, 1e-14);
}

// P-Eq. 19: zero for gamma = 1 or lambda = 1, else -(1-gamma)^2/gamma C (lambda - 1) u_s.
TEST(DriftAlgebra, DragResidual) {
  const Vec2 us{0.5, 0.2};
  EXPECT_DOUBLE_EQ(dragResidual(1.0, 7.5, {1.4, 0.7, 1}, us).x, 0);
  EXPECT_DOUBLE_EQ(dragResidual(0.4, 7.5, {1, 1, 1}, us).y, 0);
  const Vec2 r = dragResidual(0.4, 7.5, {1.4, 0.7, 1}, us);
  EXPECT_NEAR(r.x, -0.36 / 0.4 * 7.5 * 0.4 * 0.5, 1e-14);
  EXPECT_NEAR(r.y, -0.36 / 0.4 * 7.5 * -0.3 * 0.2, 1e-14);
}

// The regularised Coulomb-viscoplastic stress nu_se |D| tends to the yield stress at high rates
// and the viscosity to nu_s + m_y tau_ys at rest; the pore liquid's law is OpenFOAM's
// HerschelBulkley with its cap.
TEST(DriftAlgebra, Rheologies) {
  const SolidRheology s{0.03, 0.5, 0.2, 100};
  const double p = 4.0, tauY = 0.2 + 0.5 * p;
  EXPECT_NEAR(solidViscosity(s, 0.0, p), 0.03 + 100 * tauY, 1e-12);
  EXPECT_NEAR(solidViscosity(s, 1e-12, p), 0.03 + 100 * tauY, 1e-6);
  const double rate = 50;  // m_y |D| = 5000: exp(-x) negligible
  EXPECT_NEAR(solidViscosity(s, rate, p) * rate, 0.03 * rate + tauY, 1e-12);
  EXPECT_NEAR(solidViscosity(s, 1, -3.0), 0.03 + 0.2 * -std::expm1(-100.0),
              1e-12);  // p < 0: cohesion only

  const FluidRheology hb{0.03, 4.279e-3, 0.479, 10};
  EXPECT_NEAR(fluidViscosity(hb, 2.0), (0.03 + 4.279e-3 * std::pow(2.0, 0.479)) / 2.0, 1e-15);
  EXPECT_DOUBLE_EQ(fluidViscosity(hb, 1e-9), 10);
  EXPECT_NEAR(fluidViscosity({0, 1e-6, 1, 0}, 3.0), 1e-6, 1e-20);
}

// The mu(I) law: mu_s at I = 0, the midpoint (mu_s + mu_2)/2 at I = I_0, mu_2 as I grows; the
// stress nu_se |gamma| is mu(I) P where m_y |gamma| is large, the viscosity mu_s P m_y at rest, and
// no stress without pressure.
TEST(DriftAlgebra, MuIRheology) {
  const MuIRheology r{0.38, 0.64, 0.279, 1e-3, 100};
  EXPECT_DOUBLE_EQ(frictionCoefficient(r, 0.0), 0.38);
  EXPECT_NEAR(frictionCoefficient(r, 0.279), 0.51, 1e-15);
  EXPECT_NEAR(frictionCoefficient(r, 1e12), 0.64, 1e-12);
  const double p = 0.2, rate = 80;  // I = 80 * 1e-3 / sqrt(0.2) = 0.1789; m_y |gamma| = 8000
  const double i = rate * 1e-3 / std::sqrt(p);
  EXPECT_NEAR(solidViscosity(r, rate, p) * rate, (0.38 + 0.26 / (0.279 / i + 1)) * p, 1e-14);
  EXPECT_NEAR(solidViscosity(r, 0.0, p), 0.38 * p * 100, 1e-12);
  EXPECT_NEAR(solidViscosity(r, 1e-12, p), 0.38 * p * 100, 1e-6);
  EXPECT_DOUBLE_EQ(solidViscosity(r, rate, 0.0), 0);
  EXPECT_DOUBLE_EQ(solidViscosity(r, rate, -1.0), 0);
}

// The pore-pressure ratio closure over its whole admissible range chi in [-10, 1), for solid
// fractions up to random close packing and the scenes' liquids (water, the Bingham liquid, air):
// the yield pressure per p_m is finite and positive under both yield-pressure forms, so the
// plastic friction alpha_s tanphi (yield factor) has no pole and never turns negative; the phase
// pressures keep the total alpha_s P_s + alpha_f P_f = (alpha_s rho_s + alpha_f rho_f) p_m (to
// 1e-12 relative: the identity is exact, the rest is rounding).
TEST(DriftAlgebra, PoreRatioAdmissibleRange) {
  const double rhoS = 2500, rhoFs[] = {1000, 1400, 1.2};
  for (double rhoF : rhoFs)
    for (double a : {0.01, 0.2, 0.45, 0.6056, 0.64})
      for (int k = 0; k < 200; ++k) {
        // 200 values from the lower bound to just below 1 (the open end).
        const double chi = kPoreRatioMin + (kPoreRatioMax - kPoreRatioMin) * k / 200.0;
        const Drifts d{1.3, 0.8, 1, chi};
        for (bool reduced : {true, false}) {
          const PorePressure m{PoreClosure::ratio, reduced, rhoS, rhoF};
          const double f = yieldPressureFactor(a, d, m);
          EXPECT_TRUE(std::isfinite(f) && f > 0) << "chi " << chi << " alpha_s " << a;
          // The friction is linear in chi: its bound is at an end of the range.
          EXPECT_LE(f, 1.0 - kPoreRatioMin) << "chi " << chi;
        }
        const PorePressure m{PoreClosure::ratio, true, rhoS, rhoF};
        const double ps = solidPressureFactor(a, d, m), pf = fluidPressureFactor(a, d, m);
        const double total = a * rhoS + (1 - a) * rhoF;
        EXPECT_NEAR(a * ps + (1 - a) * pf, total, 1e-12 * total) << "chi " << chi;
        // sigma' = alpha_s (P_s - P_f) = (1 - chi) alpha_s (rho_s - rho_f) p_m > 0.
        EXPECT_NEAR(a * (ps - pf), (1 - chi) * a * (rhoS - rhoF), 1e-9 * total);
        EXPECT_GT(a * (ps - pf), 0);
      }
}

// chi = 0 is the hydrostatic pore liquid: P_f = rho_f p_m, P_s = rho_s p_m, and the same yield as
// lambda_p = 1 (the lambdaP closure's neutral value) under both yield-pressure forms.
TEST(DriftAlgebra, PoreRatioNeutralIsLambdaPOne) {
  const double a = 0.6056, rhoS = 2500, rhoF = 1000;
  for (bool reduced : {true, false}) {
    const PorePressure r{PoreClosure::ratio, reduced, rhoS, rhoF};
    const PorePressure l{PoreClosure::lambdaP, reduced, rhoS, rhoF};
    const Drifts d{1.3, 0.8, 1, 0};
    EXPECT_NEAR(yieldPressureFactor(a, d, r), yieldPressureFactor(a, d, l), 1e-15);
    EXPECT_NEAR(fluidPressureFactor(a, d, r), rhoF, 1e-12);
    EXPECT_NEAR(fluidPressureFactor(a, d, l), rhoF, 1e-12);
    EXPECT_NEAR(solidPressureFactor(a, d, r), rhoS, 1e-12);
    EXPECT_NEAR(solidPressureFactor(a, d, l), rhoS, 1e-12);
  }
  // chi = 1: the pore liquid carries the grains' buoyant load, the effective stress is 0.
  EXPECT_DOUBLE_EQ(yieldPressureFactor(a, {1, 1, 1, 1.0}, {PoreClosure::ratio, true, rhoS, rhoF}),
                   0);
}

// The ratio is lambda_p re-parametrised (buoyancyReduced): the same yield for lambda_p(chi) =
// (1 - (1 - chi)(1 - gamma) alpha_s) / (gamma + (1 - chi)(1 - gamma) alpha_f), which maps chi in
// (-inf, 1] onto (-alpha_s / alpha_f, 1 / gamma]: the pole of Lambda_p sits at chi = -inf. The
// lambdaP closure's own admissible range (alpha_s + lambda_p alpha_f >= 0.01, lambda_p <= 1000)
// reaches both a factor 100 times the neutral one and a negative friction (lambda_p > 1 / gamma).
TEST(DriftAlgebra, PoreRatioAgainstLambdaP) {
  const double a = 0.6056, af = 1 - a, rhoS = 2500, rhoF = 1000, gamma = rhoF / rhoS;
  const PorePressure r{PoreClosure::ratio, true, rhoS, rhoF};
  const PorePressure l{PoreClosure::lambdaP, true, rhoS, rhoF};
  for (double chi : {-1.0, -0.5, 0.0, 0.3, 0.9, 0.999}) {
    const double q = (1 - chi) * (1 - gamma);
    const double lp = (1 - q * a) / (gamma + q * af);
    EXPECT_GT(lp, -a / af);
    EXPECT_LE(lp, 1 / gamma);
    EXPECT_NEAR(yieldPressureFactor(a, {1, 1, lp, 0}, l), yieldPressureFactor(a, {1, 1, 1, chi}, r),
                1e-12)
        << "chi " << chi;
  }
  const double neutral = yieldPressureFactor(a, {}, l);
  const double nearPole = driftLowerBound(a, -1e3);
  EXPECT_GT(yieldPressureFactor(a, {1, 1, nearPole, 0}, l), 100 * neutral);
  EXPECT_LT(yieldPressureFactor(a, {1, 1, 3.0, 0}, l), 0);  // 3 > 1 / gamma = 2.5
}

}  // namespace
