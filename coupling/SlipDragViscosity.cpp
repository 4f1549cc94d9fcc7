// dragViscosity slip: the pore liquid's own law at a particle-scale shear rate,
//   rate = sqrt(rate_resolved^2 + rate_slip^2),
//   rate_slip = |U - v| / d max(shearRateFactor, 12 (1 - eps_f) / eps_f),
// 12 (1 - eps) |U - v| / (eps d) being Christopher & Middleman's (1965) pore-wall shear rate of
// a packed bed (superficial velocity eps |U - v|), and shearRateFactor |U - v| / d the single
// sphere's characteristic rate (the power-law sphere literature's V / d at the default 1).
// mu_f = alpha mu_liquid(rate) + (1 - alpha) mu_air, alpha the liquid fraction at the particle
// (from the mixture density), as the fluid solver mixes the phases. The regularisation is the
// liquid's cap (slipCoeffs viscosityCap, default the fluid solver's).
#include <cmath>
#include <sstream>

#include "DragViscosity.h"
#include "ForceModel.h"

namespace mixflow::coupling {

double slipShearRate(double slip, double diameter, double voidfraction, double shearRateFactor) {
  const double pore = voidfraction > 0 ? 12.0 * (1.0 - voidfraction) / voidfraction : 0.0;
  return slip / diameter * std::max(shearRateFactor, pore);
}

namespace {

class SlipDragViscosity final : public DragViscosity {
 public:
  SlipDragViscosity(const Dictionary& d, const LiquidLaw& liquid) : law_(liquid) {
    if (d.has("viscosityMax"))
      d.fail("viscosityMax",
             "only read with dragViscosity resolved; the slip closure's "
             "regularisation is slipCoeffs viscosityCap");
    const Dictionary c = d.subDictOrEmpty("slipCoeffs");
    c.allowOnly({"shearRateFactor", "viscosityCap", "resolvedRate"});
    factor_ = c.scalarOr("shearRateFactor", factor_, Range::positive());
    if (c.has("viscosityCap")) law_.viscosityCap = c.scalar("viscosityCap", Range::positive());
    resolvedRate_ = c.switchOr("resolvedRate", resolvedRate_);
  }
  double viscosity(const ParticleState& p, const FluidAtParticle& f, double slip) const override {
    const double rs = slipShearRate(slip, 2 * p.radius, f.voidfraction, factor_);
    const double rr = resolvedRate_ ? f.shearRate : 0.0;
    const double alpha = law_.liquidFraction(f.rho);
    return alpha * law_.viscosity(std::sqrt(rr * rr + rs * rs)) + (1 - alpha) * law_.airViscosity;
  }
  unsigned needs() const override { return kNeedsRho | (resolvedRate_ ? kNeedsShearRate : 0u); }
  std::string describe() const override {
    std::ostringstream s;
    s << "mu_f = the liquid's law (tau_y " << law_.yieldStress << " Pa, K " << law_.consistency
      << " Pa s^n, n " << law_.flowIndex << ", cap " << law_.viscosityCap
      << " Pa s) at the slip rate |U - v|/d max(" << factor_ << ", 12 (1 - eps_f)/eps_f)"
      << (resolvedRate_ ? " combined with the resolved rate" : "");
    return s.str();
  }

 private:
  LiquidLaw law_;
  double factor_ = 1.0;       // single-sphere rate |U - v| / d times this
  bool resolvedRate_ = true;  // add the resolved shear rate of the cell
};

}  // namespace

std::unique_ptr<DragViscosity> makeSlipDragViscosity(const Dictionary& d, const LiquidLaw& l) {
  return std::make_unique<SlipDragViscosity>(d, l);
}

}  // namespace mixflow::coupling
