// dragViscosity resolved: the mixture's apparent viscosity rho nu at the particle, as the fluid
// solver evaluates it (for a yield-stress liquid at the resolved, cell-averaged shear rate,
// capped at rest), optionally bounded by viscosityMax [Pa s] (a drag-only bound). Where the
// solver's value is 0 (OpenFOAM's HerschelBulkley evaluates (tau_y + K rate^n) / rate as 0 at
// zero shear when tau_y = 0 and n >= 1) the liquid's own limit at zero shear is taken: K for
// n = 1, so a Herschel-Bulkley liquid with tau_y 0 and n 1 is the Newtonian one at rest too.
#include <algorithm>
#include <sstream>

#include "DragViscosity.h"
#include "ForceModel.h"

namespace mixflow::coupling {

namespace {

class ResolvedDragViscosity final : public DragViscosity {
 public:
  ResolvedDragViscosity(const Dictionary& d, const LiquidLaw& liquid)
      : atRest_(liquid.viscosity(0)) {
    if (d.has("slipCoeffs")) d.fail("slipCoeffs", "only read with dragViscosity slip");
    if (d.has("viscosityMax")) viscosityMax_ = d.scalar("viscosityMax", Range::positive());
  }
  double viscosity(const ParticleState&, const FluidAtParticle& f, double) const override {
    const double mu = f.mu > 0 ? f.mu : atRest_;
    return viscosityMax_ > 0 ? std::min(mu, viscosityMax_) : mu;
  }
  unsigned needs() const override { return kNeedsMu; }
  std::string describe() const override {
    std::ostringstream s;
    s << "mu_f = rho nu of the mixture at the resolved shear rate";
    if (viscosityMax_ > 0) s << ", bounded by viscosityMax " << viscosityMax_ << " Pa s";
    return s.str();
  }

 private:
  double atRest_;            // the liquid's viscosity at zero shear [Pa s]
  double viscosityMax_ = 0;  // 0: the apparent viscosity as it is
};

}  // namespace

std::unique_ptr<DragViscosity> makeResolvedDragViscosity(const Dictionary& d, const LiquidLaw& l) {
  return std::make_unique<ResolvedDragViscosity>(d, l);
}

}  // namespace mixflow::coupling
