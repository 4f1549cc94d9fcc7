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
// Viscosity: mu_f comes from the `dragViscosity` closure (DragViscosity.h): by default the
// fluid's apparent viscosity at the particle at the resolved shear rate (capped at rest); `slip`
// evaluates the liquid's law at a particle-scale shear rate instead.
//
// Re_p -> 0: Cd |U - v| is evaluated as (0.63 sqrt|U - v| + 4.8 sqrt(mu / (rho d eps_f)))^2,
// finite at zero slip, so beta stays finite and the implicit drag is well defined at rest.
#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "DragLaw.h"
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

class DiFeliceDrag final : public DragLaw {
 public:
  DiFeliceDrag(const Dictionary& coeffs, const ForceContext& c) : DragLaw(coeffs, c, {}) {}
  const std::string& name() const override {
    static const std::string n = "DiFeliceDrag";
    return n;
  }
  std::string describe() const override {
    std::ostringstream s;
    s << "DiFeliceDrag: Di Felice (1994), Cd = (0.63 + 4.8/sqrt(Re_p))^2, implicit in the fluid "
         "(Ksl, Us); "
      << (divide_ ? "divided by eps_f (formulation B drag)"
                  : "not divided by eps_f (Eq. 10 as printed, formulation A drag)")
      << "; " << viscosityDescription();
    return s.str();
  }

 private:
  double beta(double d, double rho, double mu, double voidfraction, double slip) const override {
    return diFelice(d, rho, mu, voidfraction, slip, divide_).beta;
  }
};

}  // namespace

std::unique_ptr<ForceModel> makeDiFeliceDrag(const Dictionary& coeffs, const ForceContext& c) {
  return std::make_unique<DiFeliceDrag>(coeffs, c);
}

}  // namespace mixflow::coupling
