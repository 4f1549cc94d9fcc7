// The algebra of the quasi two-phase bulk mixture model (Pokhrel, Khattri, Tuladhar & Pudasaini
// 2017; docs/bulk_model.md): the drift coefficients, the Lambda coefficients they make, the
// reconstruction of the phase velocities and pressures, and the rheologies, pointwise and free
// of OpenFOAM so that tests/cfd/test_drift_algebra.cpp checks them against exact identities.
// Velocities are (x, y) = (along the channel, up); the paper's z is y here.
#pragma once

#include <algorithm>
#include <cmath>

namespace mixflow::bulk {

// Drifts u_f = lambdaU u_s, w_f = lambdaW w_s and kinematic pressures p_f = lambdaP p_s; chi is
// the pore-pressure ratio of the closure that replaces lambdaP (PorePressure below).
struct Drifts {
  double lambdaU = 1;
  double lambdaW = 1;
  double lambdaP = 1;
  double chi = 0;
};

// Lambda coefficients of P-Eqs. 23-24, 36 at solid fraction alphaS.
struct LambdaCoefficients {
  double uu = 1, ww = 1, uw = 1;  // inertial
  double u = 1, w = 1;            // u_s = Lambda_u u_m, w_s = Lambda_w w_m
  double p = 1;                   // p_m = Lambda_p p_s
};

// alpha_s + lambda alpha_f below this is refused by the input check (prepare/BulkModel.cpp)
// and clipped here: Lambda_u = 1 / (alpha_s + lambda_u alpha_f) is infinite at zero.
inline constexpr double kDriftDenominatorMin = 0.01;

// The smallest drift the input check allows: alpha_s + lambda alpha_f >= kDriftDenominatorMin,
// and not below FLOOR (the declared range's own bound).
inline double driftLowerBound(double alphaS, double floor) {
  return alphaS < 1 ? std::max(floor, (kDriftDenominatorMin - alphaS) / (1 - alphaS)) : floor;
}

inline double driftDenominator(double alphaS, double lambda) {
  return std::max(alphaS + lambda * (1.0 - alphaS), kDriftDenominatorMin);
}

inline LambdaCoefficients lambdaCoefficients(double alphaS, const Drifts& d) {
  const double af = 1.0 - alphaS;
  const double du = driftDenominator(alphaS, d.lambdaU);
  const double dw = driftDenominator(alphaS, d.lambdaW);
  LambdaCoefficients c;
  c.uu = (alphaS + d.lambdaU * d.lambdaU * af) / (du * du);
  c.ww = (alphaS + d.lambdaW * d.lambdaW * af) / (dw * dw);
  c.uw = (alphaS + d.lambdaU * d.lambdaW * af) / (du * dw);
  c.u = 1.0 / du;
  c.w = 1.0 / dw;
  c.p = alphaS + d.lambdaP * af;
  return c;
}

struct Vec2 {
  double x = 0, y = 0;
};

// u_s = (Lambda_u u_m, Lambda_w w_m); u_f = (lambda_u u_s, lambda_w w_s).
inline Vec2 solidVelocity(double alphaS, const Drifts& d, const Vec2& um) {
  const LambdaCoefficients c = lambdaCoefficients(alphaS, d);
  return {c.u * um.x, c.w * um.y};
}
inline Vec2 fluidVelocity(double alphaS, const Drifts& d, const Vec2& um) {
  const Vec2 us = solidVelocity(alphaS, d, um);
  return {d.lambdaU * us.x, d.lambdaW * us.y};
}
// The volumetric flux alpha_s u_s + alpha_f u_f, which the mixture velocity u_m is.
inline Vec2 mixtureVelocity(double alphaS, const Vec2& us, const Vec2& uf) {
  return {alphaS * us.x + (1 - alphaS) * uf.x, alphaS * us.y + (1 - alphaS) * uf.y};
}

// Drift stress tau_D = alpha_s alpha_f (u_s - u_f) (x) (u_s - u_f): the Lambda-weighted
// convection is div(u_m u_m) + div(tau_D) exactly (docs/bulk_model.md).
struct Sym2 {
  double xx = 0, xy = 0, yy = 0;
};
inline Sym2 driftStress(double alphaS, const Drifts& d, const Vec2& um) {
  const Vec2 us = solidVelocity(alphaS, d, um), uf = fluidVelocity(alphaS, d, um);
  const double k = alphaS * (1 - alphaS), rx = us.x - uf.x, ry = us.y - uf.y;
  return {k * rx * rx, k * rx * ry, k * ry * ry};
}

// Kinematic pressures from the mixture's p_m: p_s = p_m / Lambda_p, p_f = lambda_p p_s.
inline double solidPressure(double alphaS, const Drifts& d, double pm) {
  return pm / lambdaCoefficients(alphaS, d).p;
}
inline double fluidPressure(double alphaS, const Drifts& d, double pm) {
  return d.lambdaP * solidPressure(alphaS, d, pm);
}

// How the mixture's kinematic pressure p_m splits into the pore pressure P_f and the grains'
// effective stress sigma' (docs/bulk_model.md, "Pore pressure"):
// - lambdaP: the paper's P-Eqs. 8, 22, 48: p_s = p_m / Lambda_p, p_f = lambda_p p_s, yield
//   pressure kappa_y p_s, kappa_y = 1 - gamma lambda_p (buoyancyReduced) or 1 (paper); Lambda_p has
//   a pole at lambda_p = -alpha_s / alpha_f and kappa_y turns negative above 1 / gamma;
// - ratio: the excess pore-pressure ratio chi, P_f = rho_f p_m + chi L, sigma' = (1 - chi) L with
//   L = alpha_s (rho_s - rho_f) p_m the grains' buoyant load (total less hydrostatic): linear in
//   chi, neutral (hydrostatic pore liquid) at chi = 0, liquefied at chi = 1, no pole.
// Both leave alpha_s P_s + alpha_f P_f = (alpha_s rho_s + alpha_f rho_f) p_m at lambda_p = 1, chi
// = 0, where they coincide.
enum class PoreClosure { lambdaP, ratio };
struct PorePressure {
  PoreClosure closure = PoreClosure::ratio;
  bool buoyancyReduced = true;  // the yield on sigma' / (alpha_s rho_s), else on P_s / rho_s
  double rhoS = 1, rhoF = 0;    // phase densities (kg/m3)
};
// The kinematic pressure of the solid's yield stress (m2/s2) per p_m.
inline double yieldPressureFactor(double alphaS, const Drifts& d, const PorePressure& m) {
  const double gamma = m.rhoF / m.rhoS;
  if (m.closure == PoreClosure::lambdaP) {
    const double kappa = m.buoyancyReduced ? 1.0 - gamma * d.lambdaP : 1.0;
    return kappa / lambdaCoefficients(alphaS, d).p;
  }
  // sigma' / (alpha_s rho_s p_m) and P_s / (rho_s p_m) = (P_f + sigma' / alpha_s) / (rho_s p_m).
  return m.buoyancyReduced ? (1.0 - d.chi) * (1.0 - gamma)
                           : 1.0 - d.chi * (1.0 - alphaS) * (1.0 - gamma);
}
// P_s / p_m and P_f / p_m (kg/m3): the phase pressures (Pa) of the mixture pressure p_m.
inline double solidPressureFactor(double alphaS, const Drifts& d, const PorePressure& m) {
  if (m.closure == PoreClosure::lambdaP) return m.rhoS / lambdaCoefficients(alphaS, d).p;
  return m.rhoS - d.chi * (1.0 - alphaS) * (m.rhoS - m.rhoF);
}
inline double fluidPressureFactor(double alphaS, const Drifts& d, const PorePressure& m) {
  if (m.closure == PoreClosure::lambdaP)
    return m.rhoF * d.lambdaP / lambdaCoefficients(alphaS, d).p;
  return m.rhoF + d.chi * alphaS * (m.rhoS - m.rhoF);
}
// The ratio's bounds: chi < 1 keeps a positive effective stress (1 liquefies the grains); chi < -1
// is a suction beyond the grains' buoyant load, which a dilating column in a yield-stress liquid
// carries (B&P at the truth tier: -2.0 over its bins); -10 only bounds a mistyped value.
inline constexpr double kPoreRatioMin = -10.0;
inline constexpr double kPoreRatioMax = 1.0;  // excluded

// Mixture viscosity coefficients Lambda_eta_u = nu_s alpha_s + lambda_u nu_f alpha_f (and _w)
// and the diffusivity of u_m they give, Lambda_eta Lambda; with lambda_u != lambda_w the larger
// of the two components (the implicit operator must carry the stiffest one).
inline double mixtureDiffusivity(double alphaS, const Drifts& d, double nuS, double nuF) {
  const LambdaCoefficients c = lambdaCoefficients(alphaS, d);
  const double af = 1.0 - alphaS;
  const double etaU = nuS * alphaS + d.lambdaU * nuF * af;
  const double etaW = nuS * alphaS + d.lambdaW * nuF * af;
  return std::max(etaU * c.u, etaW * c.w);
}

// P-Eq. 44 (isotropic drift) and its inverse P-Eq. 46.
inline double isotropicMixtureViscosity(double alphaS, double lambdaU, double nuS, double nuF) {
  const double af = 1.0 - alphaS;
  return (nuS * alphaS + nuF * af * lambdaU) / (alphaS + lambdaU * af);
}
inline double lambdaFromMixtureViscosity(double alphaS, double etaM, double nuS, double nuF) {
  return (nuS - etaM) * alphaS / ((etaM - nuF) * (1.0 - alphaS));
}

// Residual of the interphase force after the kinematic reduction (P-Eq. 19): the drag terms
// M_s/rho_s + M_f/rho_f = -(1-gamma)^2/gamma C ((lambda_u-1) u_s, (lambda_w-1) w_s) for the linear
// drag (J = 1) with coefficient C = alpha_s alpha_f g / (U_T (P F + (1-P) G)) [1/s].
inline Vec2 dragResidual(double gamma, double coefficient, const Drifts& d, const Vec2& us) {
  const double k = -(1 - gamma) * (1 - gamma) / gamma * coefficient;
  return {k * (d.lambdaU - 1) * us.x, k * (d.lambdaW - 1) * us.y};
}

// Kinematic viscosity of the solid: Coulomb-viscoplastic with a pressure-dependent yield stress
// tau_ys = cohesion + tanPhi * pressure (kinematic, m2/s2), regularised as Domnik et al. (2013):
// nu_se = nu_s + tau_ys (1 - exp(-m_y |D|)) / |D|, which tends to nu_s + m_y tau_ys at rest.
struct SolidRheology {
  double viscosity = 0;       // nu_s (m2/s)
  double tanPhi = 0;          // tau_p: pressure coefficient of the yield stress
  double cohesion = 0;        // tau_c (m2/s2)
  double regularisation = 0;  // m_y (s)
};
inline double solidViscosity(const SolidRheology& r, double strainRate, double pressure) {
  const double tauY = r.cohesion + r.tanPhi * std::max(pressure, 0.0);
  const double x = r.regularisation * strainRate;
  // (1 - exp(-x)) / |D| = m_y (1 - exp(-x)) / x, with its limit m_y at x -> 0.
  const double shape = x > 1e-8 ? -std::expm1(-x) / x : 1.0 - 0.5 * x;
  return r.viscosity + tauY * r.regularisation * shape;
}

// Kinematic viscosity of the solid by the mu(I) law (Jop, Forterre & Pouliquen 2006): mu(I) =
// mu_s + (mu_2 - mu_s) / (I_0 / I + 1), I = |gamma| d / sqrt(P) with P the kinematic pressure of
// the Coulomb law (P_s / rho_s, m2/s2) and |gamma| = sqrt(2 D:D), the shear rate of a simple shear.
// nu_se = mu(I) P (1 - exp(-m_y |gamma|)) / |gamma|: the Coulomb law's regularisation, mu_s P m_y
// at rest.
struct MuIRheology {
  double muS = 0;             // static friction coefficient mu_s
  double mu2 = 0;             // limiting friction coefficient mu_2 (>= mu_s)
  double i0 = 1;              // I_0
  double diameter = 0;        // grain diameter d (m)
  double regularisation = 0;  // m_y (s)
};
inline double frictionCoefficient(const MuIRheology& r, double inertialNumber) {
  return r.muS + (r.mu2 - r.muS) * inertialNumber / (r.i0 + inertialNumber);
}
inline double solidViscosity(const MuIRheology& r, double strainRate, double pressure) {
  const double p = std::max(pressure, 0.0);
  if (p == 0) return 0;  // no confinement, no friction (I infinite, mu_2 times 0)
  const double inertial = strainRate * r.diameter / std::sqrt(p);
  const double x = r.regularisation * strainRate;
  const double shape = x > 1e-8 ? -std::expm1(-x) / x : 1.0 - 0.5 * x;
  return frictionCoefficient(r, inertial) * p * r.regularisation * shape;
}

// Kinematic viscosity of a Herschel-Bulkley pore liquid as the pure-liquid cases see it
// (OpenFOAM's HerschelBulkley): min(nu0, (tau0 + k sr^n) / sr); Newtonian for tau0 = 0, n = 1.
struct FluidRheology {
  double tau0 = 0;  // m2/s2
  double k = 0;     // m2/s^(2-n)
  double n = 1;
  double nu0 = 0;  // cap (m2/s); 0 = no cap (Newtonian only)
};
inline double fluidViscosity(const FluidRheology& r, double strainRate) {
  const double sr = std::max(strainRate, 1e-300);
  const double nu = (r.tau0 + r.k * std::pow(sr, r.n)) / sr;
  return r.nu0 > 0 ? std::min(r.nu0, nu) : nu;
}

}  // namespace mixflow::bulk
