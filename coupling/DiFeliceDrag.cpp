// DiFeliceDrag: drag of Di Felice (1994), Li & Zhao Eq. 10,
//   F_d = (1/8) Cd rho_f pi d^2 eps_f^2 |U - v| (U - v) eps_f^(-chi),
//   Cd = (0.63 + 4.8 / sqrt(Re_p))^2,  Re_p = rho_f d eps_f |U - v| / mu_f,
//   chi = 3.7 - 0.65 exp(-(1.5 - log10 Re_p)^2 / 2),
// with U the interstitial fluid velocity at the particle and v the particle velocity.
//
// Formulation: the correlation is the drag of the particle-fluid force split of formulation A
// (drag + pressure-gradient force -Vp grad p). In formulation B (what mixflowFoam solves) the
// particle gets buoyancy instead of -Vp grad p, and the drag must carry the part of the dynamic
// pressure gradient that formulation A gives separately: F_d,B = F_d,A / eps_f (Zhou et al. 2010;
// CFDEMcoupling's "modelType B" does the same). Default: divide when formulation is B
// (`divideByVoidfraction` in DiFeliceDragCoeffs overrides it; `no` reproduces Eq. 10 as printed).
// For a single particle (eps_f -> 1) the two agree.
//
// Viscosity: mu_f is the fluid's apparent dynamic viscosity at the particle, rho nu with nu the
// VOF mixture's kinematic viscosity; for a generalised-Newtonian liquid (Herschel-Bulkley) OpenFOAM
// evaluates nu at the shear rate of the resolved (cell-averaged, interstitial) flow,
// gamma_dot = sqrt(2) |symm(grad U)|, capped by nu0 -- not at a particle-scale shear rate
// |U - v| / d, which an unresolved mesh does not see (documented in coupling/README.md).
//
// Re_p -> 0: Cd |U - v| is evaluated as (0.63 sqrt|U - v| + 4.8 sqrt(mu / (rho d eps_f)))^2,
// finite at zero slip, so beta stays finite and the implicit drag is well defined at rest.
#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "ForceModel.h"

namespace mixflow::coupling {

DiFeliceTerms diFelice(double diameter, double rho, double mu, double voidfraction, double slip,
                       bool divideByVoidfraction) {
  if (!(diameter > 0 && rho > 0 && mu > 0 && voidfraction > 0 && slip >= 0))
    throw std::runtime_error("DiFeliceDrag: needs d, rho_f, mu_f, eps_f > 0 and |U - v| >= 0 (d " +
                             std::to_string(diameter) + ", rho " + std::to_string(rho) + ", mu " +
                             std::to_string(mu) + ", eps_f " + std::to_string(voidfraction) + ")");
  constexpr double kPi = 3.14159265358979323846;
  DiFeliceTerms t{};
  t.reynolds = rho * diameter * voidfraction * slip / mu;
  // chi -> 3.7 as Re_p -> 0 (and as Re_p -> infinity); log10(0) is avoided.
  if (t.reynolds > 0) {
    const double s = 1.5 - std::log10(t.reynolds);
    t.chi = 3.7 - 0.65 * std::exp(-0.5 * s * s);
  } else {
    t.chi = 3.7;
  }
  const double root =
      0.63 * std::sqrt(slip) + 4.8 * std::sqrt(mu / (rho * diameter * voidfraction));
  const double cdSlip = root * root;  // Cd |U - v|
  t.beta = 0.125 * cdSlip * rho * kPi * diameter * diameter * std::pow(voidfraction, 2.0 - t.chi);
  if (divideByVoidfraction) t.beta /= voidfraction;
  return t;
}

namespace {

class DiFeliceDrag final : public ForceModel {
 public:
  DiFeliceDrag(const Dictionary& coeffs, const ForceContext& c) {
    coeffs.allowOnly({"divideByVoidfraction", "viscosityMax"});
    divide_ = coeffs.switchOr("divideByVoidfraction", c.formulation == "B");
    // A drag-only viscosity bound (Pa s; default none): for a yield-stress liquid the same as
    // evaluating its law at a shear rate of at least the one where it reaches this viscosity,
    // i.e. a pore-scale shear rate the unresolved mesh does not see (docs/parameters.md).
    if (coeffs.has("viscosityMax"))
      viscosityMax_ = coeffs.scalar("viscosityMax", Range::positive());
  }
  const std::string& name() const override {
    static const std::string n = "DiFeliceDrag";
    return n;
  }
  unsigned needs() const override { return kNeedsU | kNeedsRho | kNeedsMu | kNeedsVoidfraction; }
  ParticleForce force(const ParticleState& p, const FluidAtParticle& f) const override {
    ParticleForce out;
    const double mu = viscosityMax_ > 0 ? std::min(f.mu, viscosityMax_) : f.mu;
    out.beta = diFelice(2 * p.radius, f.rho, mu, f.voidfraction, mag(f.U - p.v), divide_).beta;
    return out;
  }
  std::string describe() const override {
    std::ostringstream s;
    s << "DiFeliceDrag: Di Felice (1994), Cd = (0.63 + 4.8/sqrt(Re_p))^2, implicit in the fluid "
         "(Ksl, Us); "
      << (divide_ ? "divided by eps_f (formulation B drag)"
                  : "not divided by eps_f (Eq. 10 as printed, formulation A drag)")
      << "; mu_f = rho nu of the mixture at the resolved shear rate";
    if (viscosityMax_ > 0) s << ", bounded by viscosityMax " << viscosityMax_ << " Pa s";
    return s.str();
  }

 private:
  bool divide_ = true;
  double viscosityMax_ = 0;  // 0: the apparent viscosity as it is
};

}  // namespace

std::unique_ptr<ForceModel> makeDiFeliceDrag(const Dictionary& coeffs, const ForceContext& c) {
  return std::make_unique<DiFeliceDrag>(coeffs, c);
}

}  // namespace mixflow::coupling
