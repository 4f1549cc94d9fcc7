// dragViscosity resolved: the mixture's apparent viscosity rho nu at the particle, as the fluid
// solver evaluates it (for a yield-stress liquid at the resolved, cell-averaged shear rate,
// capped at rest), optionally bounded by viscosityMax [Pa s] (a drag-only bound).
#include <algorithm>
#include <sstream>

#include "DragViscosity.h"
#include "ForceModel.h"

namespace mixflow::coupling {

namespace {

class ResolvedDragViscosity final : public DragViscosity {
 public:
  explicit ResolvedDragViscosity(const Dictionary& d) {
    if (d.has("slipCoeffs")) d.fail("slipCoeffs", "only read with dragViscosity slip");
    if (d.has("viscosityMax")) viscosityMax_ = d.scalar("viscosityMax", Range::positive());
  }
  double viscosity(const ParticleState&, const FluidAtParticle& f, double) const override {
    return viscosityMax_ > 0 ? std::min(f.mu, viscosityMax_) : f.mu;
  }
  unsigned needs() const override { return kNeedsMu; }
  std::string describe() const override {
    std::ostringstream s;
    s << "mu_f = rho nu of the mixture at the resolved shear rate";
    if (viscosityMax_ > 0) s << ", bounded by viscosityMax " << viscosityMax_ << " Pa s";
    return s.str();
  }

 private:
  double viscosityMax_ = 0;  // 0: the apparent viscosity as it is
};

}  // namespace

std::unique_ptr<DragViscosity> makeResolvedDragViscosity(const Dictionary& d, const LiquidLaw&) {
  return std::make_unique<ResolvedDragViscosity>(d);
}

}  // namespace mixflow::coupling
