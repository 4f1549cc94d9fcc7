// dragViscosity slip: the pore liquid's own law at a particle-scale shear rate,
//   rate = sqrt(rate_resolved^2 + rate_slip^2),
//   rate_slip = |U - v| / d max(shearRateFactor, 12 (1 - eps_f) / eps_f),
// 12 (1 - eps) |U - v| / (eps d) being Christopher & Middleman's (1965) pore-wall shear rate of
// a packed bed (superficial velocity eps |U - v|), and shearRateFactor |U - v| / d the single
// sphere's characteristic rate (the power-law sphere literature's V / d at the default 1).
// mu_f = alpha mu_liquid(rate) + (1 - alpha) mu_air, alpha the liquid fraction at the particle
// (from the mixture density), as the fluid solver mixes the phases. The regularisation is the
// liquid's cap (slipCoeffs viscosityCap, default the fluid solver's).
// powerLawShape (default yes) multiplies the power-law part K rate^(n-1) by the published shape
// factor of the flow around the grains: a lone sphere's X(n) (its drag is 3 pi K V^n d^(2-n) X(n)),
// a packed bed's ((3n + 1) / 4n)^n (Christopher & Middleman's Rabinowitsch factor), weighted
// geometrically by the pore's share of the slip rate, so both limits hold and the drag is smooth.
#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include "DragViscosity.h"
#include "ForceModel.h"

namespace mixflow::coupling {

namespace {
// 12 (1 - eps) / eps: Christopher & Middleman's pore-wall rate over the sphere's |U - v| / d.
double poreRateFactor(double voidfraction) {
  return voidfraction > 0 ? 12.0 * (1.0 - voidfraction) / voidfraction : 0.0;
}
}  // namespace

double slipShearRate(double slip, double diameter, double voidfraction, double shearRateFactor) {
  const double pore = poreRateFactor(voidfraction);
  return slip / diameter * std::max(shearRateFactor, pore);
}

double powerLawSphereFactor(double n) {
  // Gu & Tanner (1985), Tripathi, Chhabra & Sundararajan (1994) via Chhabra & Richardson (2008);
  // n = 1 is Stokes' 1 exactly (the table's 1.002 is the numerical solutions' error).
  static const std::array<std::array<double, 2>, 8> table = {{{0.3, 1.458},
                                                              {0.4, 1.442},
                                                              {0.5, 1.420},
                                                              {0.6, 1.382},
                                                              {0.7, 1.320},
                                                              {0.8, 1.240},
                                                              {0.9, 1.140},
                                                              {1.0, 1.0}}};
  if (n >= 1.0) return 1.0;
  if (n <= table.front()[0]) return table.front()[1];
  for (std::size_t i = 1; i < table.size(); ++i)
    if (n <= table[i][0]) {
      const auto& a = table[i - 1];
      const auto& b = table[i];
      return a[1] + (b[1] - a[1]) * (n - a[0]) / (b[0] - a[0]);
    }
  return 1.0;
}

double powerLawShapeFactor(double n, double voidfraction, double shearRateFactor) {
  if (n >= 1.0) return 1.0;
  const double pore = poreRateFactor(voidfraction);
  const double w = pore / (pore + shearRateFactor);
  const double bed = std::pow((3 * n + 1) / (4 * n), n);
  return std::pow(powerLawSphereFactor(n), 1 - w) * std::pow(bed, w);
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
    c.allowOnly({"shearRateFactor", "viscosityCap", "resolvedRate", "powerLawShape"});
    factor_ = c.scalarOr("shearRateFactor", factor_, Range::positive());
    if (c.has("viscosityCap")) law_.viscosityCap = c.scalar("viscosityCap", Range::positive());
    resolvedRate_ = c.switchOr("resolvedRate", resolvedRate_);
    powerLawShape_ = c.switchOr("powerLawShape", powerLawShape_);
  }
  double viscosity(const ParticleState& p, const FluidAtParticle& f, double slip) const override {
    const double rs = slipShearRate(slip, 2 * p.radius, f.voidfraction, factor_);
    const double rr = resolvedRate_ ? f.shearRate : 0.0;
    const double alpha = law_.liquidFraction(f.rho);
    const double shape =
        powerLawShape_ ? powerLawShapeFactor(law_.flowIndex, f.voidfraction, factor_) : 1.0;
    return alpha * law_.viscosity(std::sqrt(rr * rr + rs * rs), shape) +
           (1 - alpha) * law_.airViscosity;
  }
  unsigned needs() const override { return kNeedsRho | (resolvedRate_ ? kNeedsShearRate : 0u); }
  std::string describe() const override {
    std::ostringstream s;
    s << "mu_f = the liquid's law (tau_y " << law_.yieldStress << " Pa, K " << law_.consistency
      << " Pa s^n, n " << law_.flowIndex << ", cap " << law_.viscosityCap
      << " Pa s) at the slip rate |U - v|/d max(" << factor_ << ", 12 (1 - eps_f)/eps_f)"
      << (resolvedRate_ ? " combined with the resolved rate" : "")
      << (powerLawShape_ && law_.flowIndex < 1 ? ", power-law part times the shape factor "
                                                 "(X(n) lone, ((3n+1)/4n)^n packed)"
                                               : "");
    return s.str();
  }

 private:
  LiquidLaw law_;
  double factor_ = 1.0;        // single-sphere rate |U - v| / d times this
  bool resolvedRate_ = true;   // add the resolved shear rate of the cell
  bool powerLawShape_ = true;  // X(n) / Christopher & Middleman factor on K rate^(n-1)
};

}  // namespace

std::unique_ptr<DragViscosity> makeSlipDragViscosity(const Dictionary& d, const LiquidLaw& l) {
  return std::make_unique<SlipDragViscosity>(d, l);
}

}  // namespace mixflow::coupling
