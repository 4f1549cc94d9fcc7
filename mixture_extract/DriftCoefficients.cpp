#include "DriftCoefficients.h"

#include <cmath>
#include <limits>

namespace mixflow::mx {

namespace {

constexpr std::uint16_t kLu = kOutsideMixture | kSmallUs;
constexpr std::uint16_t kLw = kOutsideMixture | kSmallWs;
constexpr std::uint16_t kLp = kOutsideMixture | kSmallPs;
constexpr std::uint16_t kLuD = kLu | kSmallDenominatorU;
constexpr std::uint16_t kLwD = kLw | kSmallDenominatorW;

// Order must follow FieldId.
const FieldDef kFields[kFieldCount] = {
    {fAlphaS, "alpha_s", "1",
     "particle volume fraction: sum of exact sphere-bin volumes / bin volume, averaged over the "
     "window's snapshots",
     0},
    {fAlphaF, "alpha_f", "1", "fluid volume fraction 1 - alpha_s", 0},
    {fUs, "u_s", "m/s", "particle velocity along x (down-channel), particle-volume weighted",
     kParticleMask},
    {fWs, "w_s", "m/s",
     "particle velocity along y (vertical, the paper's w), particle-volume weighted",
     kParticleMask},
    {fUf, "u_f", "m/s",
     "liquid velocity along x, weighted by the liquid volume alpha_l eps_f V of the cells whose "
     "centre is in the bin; masked where the liquid share of the bin's fluid volume is below "
     "thresholds.minLiquidShare",
     kLiquidMask},
    {fWf, "w_f", "m/s", "liquid velocity along y (vertical), liquid-volume weighted", kLiquidMask},
    {fPf, "p_f", "Pa", "liquid pressure (fluid field p), liquid-volume weighted", kLiquidMask},
    {fPs, "p_s", "Pa",
     "granular pressure -tr(sigma)/3, sigma = (1/V_bin)[sum_i w_i C_i - sum_i w_i m_i v'_i v'_i], "
     "C_i contact stress x volume from LIGGGHTS compute stress/atom (c_pstress, kinetic term "
     "removed), w_i = V_i,bin / V_i, v' about the snapshot's bin-mean velocity; averaged over the "
     "window's snapshots; positive in compression; masked where the bin holds fewer than "
     "thresholds.minParticleSamples particle samples",
     kParticleMask},
    {fPsContact, "p_s_contact", "Pa", "contact part of p_s", kParticleMask},
    {fPsKinetic, "p_s_kinetic", "Pa", "streaming (velocity fluctuation) part of p_s",
     kParticleMask},
    {fSigmaXX, "sigma_s_xx", "Pa", "particle-phase stress xx (tension positive)", kParticleMask},
    {fSigmaYY, "sigma_s_yy", "Pa", "particle-phase stress yy (vertical normal, tension positive)",
     kParticleMask},
    {fSigmaZZ, "sigma_s_zz", "Pa", "particle-phase stress zz (across the width, tension positive)",
     kParticleMask},
    {fSigmaXY, "sigma_s_xy", "Pa", "particle-phase shear stress xy", kParticleMask},
    {fSaturation, "saturation", "1",
     "liquid share of the fluid volume in the bin: sum alpha_l eps_f V / sum eps_f V (cells by "
     "centre)",
     kNoLiquid},
    {fLambdaU, "lambda_u", "1", "lambda_u = u_f / u_s (Eq. 8)", kLu},
    {fLambdaW, "lambda_w", "1", "lambda_w = w_f / w_s (Eq. 8)", kLw},
    {fLambdaPRaw, "lambda_p_raw", "1", "lambda_p = p_f / p_s (raw pressures, Eq. 8)", kLp},
    {fLambdaPDensity, "lambda_p_density", "1",
     "lambda_p = (p_f / rho_f) / (p_s / rho_s) (pressures divided by phase densities, the "
     "paper's convention)",
     kLp},
    {fUm, "u_m", "m/s",
     "mixture velocity (alpha_s + lambda_u alpha_f) u_s = alpha_s u_s + alpha_f u_f (Eq. 22)",
     kOutsideMixture},
    {fWm, "w_m", "m/s", "mixture velocity (alpha_s + lambda_w alpha_f) w_s (Eq. 22)",
     kOutsideMixture},
    {fPmRaw, "p_m_raw", "Pa", "mixture pressure (alpha_s + lambda_p alpha_f) p_s, raw (Eq. 22)",
     kOutsideMixture},
    {fPmDensity, "p_m_density", "m2/s2",
     "mixture pressure alpha_s p_s / rho_s + alpha_f p_f / rho_f (density convention, Eq. 22)",
     kOutsideMixture},
    {fLuu, "Lambda_uu", "1",
     "(alpha_s + lambda_u^2 alpha_f) / (alpha_s + lambda_u alpha_f)^2 (Eq. 36)", kLuD},
    {fLww, "Lambda_ww", "1",
     "(alpha_s + lambda_w^2 alpha_f) / (alpha_s + lambda_w alpha_f)^2 (Eq. 36)", kLwD},
    {fLuw, "Lambda_uw", "1",
     "(alpha_s + lambda_u lambda_w alpha_f) / ((alpha_s + lambda_u alpha_f)(alpha_s + lambda_w "
     "alpha_f)) (Eq. 36)",
     kLuD | kLwD},
    {fLu, "Lambda_u", "1", "1 / (alpha_s + lambda_u alpha_f) (Eq. 36)", kLuD},
    {fLw, "Lambda_w", "1", "1 / (alpha_s + lambda_w alpha_f) (Eq. 36)", kLwD},
    {fLpRaw, "Lambda_p_raw", "1", "alpha_s + lambda_p_raw alpha_f (Eq. 36)", kLp},
    {fLpDensity, "Lambda_p_density", "1", "alpha_s + lambda_p_density alpha_f (Eq. 36)", kLp},
    {fLetaUFluidCoeff, "Lambda_eta_u_fluid_coeff", "1",
     "lambda_u alpha_f: Lambda_eta_u = nu_s alpha_s + nu_f * this (Eq. 36)", kLu},
    {fLetaWFluidCoeff, "Lambda_eta_w_fluid_coeff", "1",
     "lambda_w alpha_f: Lambda_eta_w = nu_s alpha_s + nu_f * this (Eq. 36)", kLw},
    {fLetaMSolidCoeff, "Lambda_eta_m_solid_coeff", "1",
     "(1/2) alpha_s (Lambda_u + Lambda_w): Lambda_eta_m = nu_s * this + nu_f * "
     "Lambda_eta_m_fluid_coeff (Eqs. 40, 43)",
     kLuD | kLwD},
    {fLetaMFluidCoeff, "Lambda_eta_m_fluid_coeff", "1",
     "(1/2) alpha_f (lambda_u Lambda_u + lambda_w Lambda_w) (Eqs. 40, 43)", kLuD | kLwD},
    {fLetaU, "Lambda_eta_u", "m2/s", "nu_s alpha_s + lambda_u nu_f alpha_f (Eq. 36)", kLu},
    {fLetaW, "Lambda_eta_w", "m2/s", "nu_s alpha_s + lambda_w nu_f alpha_f (Eq. 36)", kLw},
    {fLetaM, "Lambda_eta_m", "m2/s",
     "(1/2) nu_s alpha_s (Lambda_u + Lambda_w) + (1/2) nu_f alpha_f (lambda_u Lambda_u + lambda_w "
     "Lambda_w) (Eqs. 40, 43)",
     kLuD | kLwD},
    {fMassResidual, "mass_balance_residual", "1/s",
     "Eq. 9: d/dx[(alpha_s + lambda_u alpha_f) u_s] + d/dy[(alpha_s + lambda_w alpha_f) w_s] = "
     "div(alpha_s u_s + alpha_f u_f), central differences between mixture bins (one-sided at the "
     "mixture's edge)",
     kOutsideMixture | kNoGradient},
    {fMassScale, "mass_balance_scale", "1/s",
     "|d/dx(u_m)| + |d/dy(w_m)|, the size the residual is to be compared with",
     kOutsideMixture | kNoGradient},
    {fPfHydrostatic, "p_f_hydrostatic", "Pa",
     "p_gas + rho_f g (h_l - y): the liquid column above the bin centre y, h_l the column's liquid "
     "surface y0 + sum_j saturation_j dy (rows without a fluid cell take the saturation "
     "interpolated between their neighbours), p_gas the gas pressure of the lowest bin wholly "
     "above it; masked where the surface is not inside the grid",
     kLiquidMask | kNoLiquidSurface},
    {fPfExcess, "p_f_excess", "Pa",
     "excess pore pressure p_f - p_f_hydrostatic (0 for a liquid at rest)",
     kLiquidMask | kNoLiquidSurface},
    {fPTotal, "p_total", "Pa",
     "total mean normal stress p_s + p_f: the effective stress sigma' (p_s, the grains' contact "
     "share per bulk volume) plus the pore pressure",
     kOutsideMixture},
    {fPoreRatio, "pore_pressure_ratio", "1",
     "chi = p_f_excess / (p_s + p_f_excess): the excess pore pressure over the grains' load "
     "(total less hydrostatic), sigma' = (1 - chi)(p_total - p_f_hydrostatic); 0 at rest, 1 "
     "liquefied (the bulk model's drifts.porePressureRatio)",
     kOutsideMixture | kNoLiquidSurface | kSmallLoad},
    {fLambdaPKinematic, "lambda_p_kinematic", "1",
     "(P_f / rho_f) / (P_s / rho_s), P_s = p_f + p_s / alpha_s the solid's partial total "
     "pressure (the bulk model's lambda_p: 1 at rest for an isotropic sigma')",
     kLp},
};

const std::vector<MaskBitInfo> kBits = {
    {kNoParticles, "no_particles", "no particle volume in the bin during the window"},
    {kFewParticleSamples, "few_particle_samples",
     "particle samples (particle-snapshot overlaps) below thresholds.minParticleSamples"},
    {kNoLiquid, "no_liquid", "no liquid volume: no fluid data or no liquid cell centre in the bin"},
    {kLowSolidFraction, "low_solid_fraction", "alpha_s below thresholds.minSolidFraction"},
    {kUnsaturated, "unsaturated",
     "liquid share of the fluid volume below thresholds.minSaturation"},
    {kSmallUs, "small_u_s", "|u_s| below thresholds.minVelocity"},
    {kSmallWs, "small_w_s", "|w_s| below thresholds.minVelocity"},
    {kSmallPs, "small_p_s", "|p_s| below thresholds.minPressure"},
    {kSmallDenominatorU, "small_denominator_u",
     "|alpha_s + lambda_u alpha_f| below thresholds.minDenominator"},
    {kSmallDenominatorW, "small_denominator_w",
     "|alpha_s + lambda_w alpha_f| below thresholds.minDenominator"},
    {kNoGradient, "no_gradient", "mass balance: no mixture neighbour along x or along y"},
    {kLittleLiquid, "little_liquid",
     "liquid share of the fluid volume below thresholds.minLiquidShare (u_f, w_f, p_f masked)"},
    {kNoLiquidSurface, "no_liquid_surface",
     "the liquid surface above the bin is not inside the grid (the column's top bin is more than "
     "half liquid, or the column has no fluid cell)"},
    {kSmallLoad, "small_load", "|p_s + p_f_excess| below thresholds.minPressure"},
};

}  // namespace

const std::vector<MaskBitInfo>& maskBits() { return kBits; }

const FieldDef& fieldDef(FieldId id) { return kFields[id]; }

std::vector<FieldId> outputFields(const ExtractSettings& s) {
  std::vector<FieldId> out;
  for (int k = 0; k < kFieldCount; ++k) {
    const auto f = static_cast<FieldId>(k);
    if (!s.wantRaw() && (f == fLambdaPRaw || f == fPmRaw || f == fLpRaw)) continue;
    if (!s.wantDensity() && (f == fLambdaPDensity || f == fPmDensity || f == fLpDensity)) continue;
    if (!s.haveViscosities && (f == fLetaU || f == fLetaW || f == fLetaM)) continue;
    out.push_back(f);
  }
  return out;
}

MixtureValues mixtureValues(const BinSums& b, double volume, int snapshots, int fluidTimes,
                            const ExtractSettings& s) {
  MixtureValues m;
  for (double& v : m.value) v = std::numeric_limits<double>::quiet_NaN();
  const Thresholds& th = s.thresholds;
  double* v = m.value;
  std::uint16_t& r = m.reasons;

  // Particle phase (snapshots >= 1 for every extracted window).
  const double sampleVolume = volume * snapshots;
  const double as = b.particleVolume / sampleVolume, af = 1.0 - as;
  v[fAlphaS] = as;
  v[fAlphaF] = af;
  double sig[6];
  for (int k = 0; k < 6; ++k) sig[k] = (b.contact[k] + b.kinetic[k]) / sampleVolume;
  v[fSigmaXX] = sig[0];
  v[fSigmaYY] = sig[1];
  v[fSigmaZZ] = sig[2];
  v[fSigmaXY] = sig[3];
  const double ps = -(sig[0] + sig[1] + sig[2]) / 3.0;
  v[fPs] = ps;
  v[fPsContact] = -(b.contact[0] + b.contact[1] + b.contact[2]) / (3.0 * sampleVolume);
  v[fPsKinetic] = -(b.kinetic[0] + b.kinetic[1] + b.kinetic[2]) / (3.0 * sampleVolume);
  double us = 0, ws = 0;
  if (b.particleVolume > 0) {
    us = b.particleVolumeU / b.particleVolume;
    ws = b.particleVolumeW / b.particleVolume;
    v[fUs] = us;
    v[fWs] = ws;
  } else {
    r |= kNoParticles;
  }
  if (b.particleSamples < static_cast<double>(th.minParticleSamples)) r |= kFewParticleSamples;
  if (as < th.minSolidFraction) r |= kLowSolidFraction;

  // Liquid phase.
  double uf = 0, wf = 0, pf = 0;
  if (fluidTimes > 0 && b.liquidVolume > 0) {
    uf = b.liquidVolumeU / b.liquidVolume;
    wf = b.liquidVolumeW / b.liquidVolume;
    pf = b.liquidVolumeP / b.liquidVolume;
    v[fUf] = uf;
    v[fWf] = wf;
    v[fPf] = pf;
    const double sat = b.liquidVolume / b.fluidVolume;  // fluidVolume >= liquidVolume > 0
    v[fSaturation] = sat;
    if (sat < th.minSaturation) r |= kUnsaturated;
    if (sat < th.minLiquidShare) r |= kLittleLiquid;
  } else {
    r |= kNoLiquid;
  }

  if ((r & kOutsideMixture) == 0) {
    v[fUm] = as * us + af * uf;
    v[fWm] = as * ws + af * wf;
    v[fPmRaw] = as * ps + af * pf;
    v[fPmDensity] = as * ps / s.solidDensity + af * pf / s.liquidDensity;
    if (std::fabs(us) < th.minVelocity) r |= kSmallUs;
    if (std::fabs(ws) < th.minVelocity) r |= kSmallWs;
    if (std::fabs(ps) < th.minPressure) r |= kSmallPs;
  }
  double lu = 0, lw = 0, du = 0, dw = 0;
  if ((r & kLu) == 0) {
    lu = uf / us;
    du = as + lu * af;
    v[fLambdaU] = lu;
    v[fLetaUFluidCoeff] = lu * af;
    if (s.haveViscosities) v[fLetaU] = s.nuSolid * as + lu * s.nuFluid * af;
    if (std::fabs(du) < th.minDenominator) r |= kSmallDenominatorU;
  }
  if ((r & kLw) == 0) {
    lw = wf / ws;
    dw = as + lw * af;
    v[fLambdaW] = lw;
    v[fLetaWFluidCoeff] = lw * af;
    if (s.haveViscosities) v[fLetaW] = s.nuSolid * as + lw * s.nuFluid * af;
    if (std::fabs(dw) < th.minDenominator) r |= kSmallDenominatorW;
  }
  if ((r & kLp) == 0) {
    const double lpr = pf / ps;
    const double lpd = (pf / s.liquidDensity) / (ps / s.solidDensity);
    v[fLambdaPRaw] = lpr;
    v[fLambdaPDensity] = lpd;
    v[fLpRaw] = as + lpr * af;
    v[fLpDensity] = as + lpd * af;
    const double psPartial = pf + ps / as;  // as >= minSolidFraction > 0 in the mixture
    if (psPartial != 0)
      v[fLambdaPKinematic] = (pf / s.liquidDensity) / (psPartial / s.solidDensity);
  }
  if ((r & kOutsideMixture) == 0) v[fPTotal] = ps + pf;
  if ((r & kLuD) == 0) {
    v[fLuu] = (as + lu * lu * af) / (du * du);
    v[fLu] = 1.0 / du;
  }
  if ((r & kLwD) == 0) {
    v[fLww] = (as + lw * lw * af) / (dw * dw);
    v[fLw] = 1.0 / dw;
  }
  if ((r & (kLuD | kLwD)) == 0) {
    v[fLuw] = (as + lu * lw * af) / (du * dw);
    const double Lu = 1.0 / du, Lw = 1.0 / dw;
    v[fLetaMSolidCoeff] = 0.5 * as * (Lu + Lw);
    v[fLetaMFluidCoeff] = 0.5 * af * (lu * Lu + lw * Lw);
    if (s.haveViscosities)
      v[fLetaM] = s.nuSolid * v[fLetaMSolidCoeff] + s.nuFluid * v[fLetaMFluidCoeff];
  }
  return m;
}

void massBalance(const AveragingGrid& g, std::vector<MixtureValues>& bins) {
  const int nx = g.nx(), ny = g.ny();
  auto in = [&](int i, int j) {
    return i >= 0 && i < nx && j >= 0 && j < ny &&
           (bins[g.index(i, j)].reasons & kOutsideMixture) == 0;
  };
  // Derivative of field f along one axis at (i, j); false when no mixture neighbour.
  auto deriv = [&](int i, int j, int di, int dj, double h, FieldId f, double& out) {
    const bool lo = in(i - di, j - dj), hi = in(i + di, j + dj);
    const double c = bins[g.index(i, j)].value[f];
    if (lo && hi)
      out = (bins[g.index(i + di, j + dj)].value[f] - bins[g.index(i - di, j - dj)].value[f]) /
            (2 * h);
    else if (hi)
      out = (bins[g.index(i + di, j + dj)].value[f] - c) / h;
    else if (lo)
      out = (c - bins[g.index(i - di, j - dj)].value[f]) / h;
    else
      return false;
    return true;
  };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      MixtureValues& m = bins[g.index(i, j)];
      if (!in(i, j)) continue;
      double ddx = 0, ddy = 0;
      if (!deriv(i, j, 1, 0, g.dx(), fUm, ddx) || !deriv(i, j, 0, 1, g.dy(), fWm, ddy)) {
        m.reasons |= kNoGradient;
        continue;
      }
      m.value[fMassResidual] = ddx + ddy;
      m.value[fMassScale] = std::fabs(ddx) + std::fabs(ddy);
    }
}

}  // namespace mixflow::mx
