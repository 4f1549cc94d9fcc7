// buoyancy: F_b = -rho_f V_p g (Li & Zhao Eq. 9), rho_f the local fluid density (liquid, air or
// their VOF mixture in the particle's cell). This is formulation B's replacement of the
// pressure-gradient force -V_p grad(p): the fluid keeps the whole -grad(p) and loses the reaction
// +rho_f V_p g through fSource, so a bed at rest in still liquid leaves the liquid hydrostatic
// (cfd/README.md). Formulation A would need -V_p grad(p) instead; using both counts buoyancy twice,
// so this model refuses any formulation but B.
#include <sstream>

#include "ForceModel.h"

namespace mixflow::coupling {

namespace {

class Buoyancy final : public ForceModel {
 public:
  Buoyancy(const Dictionary& coeffs, const ForceContext& c) : g_(c.g) {
    coeffs.allowOnly({});
    if (c.formulation != "B")
      coeffs.fail("buoyancy",
                  "the buoyancy force -rho_f V_p g belongs to formulation B; with "
                  "formulation " +
                      c.formulation + " the particle needs -V_p grad(p) instead");
  }
  const std::string& name() const override {
    static const std::string n = "buoyancy";
    return n;
  }
  unsigned needs() const override { return kNeedsRho; }
  ParticleForce force(const ParticleState& p, const FluidAtParticle& f) const override {
    ParticleForce out;
    out.explicitForce = (-f.rho * p.volume()) * g_;
    return out;
  }
  std::string describe() const override {
    std::ostringstream s;
    s << "buoyancy: -rho_f V_p g, g = (" << g_.x << " " << g_.y << " " << g_.z
      << "), rho_f the VOF mixture density of the cell; explicit (fSource)";
    return s.str();
  }

 private:
  Vec3 g_;
};

}  // namespace

std::unique_ptr<ForceModel> makeBuoyancy(const Dictionary& coeffs, const ForceContext& c) {
  return std::make_unique<Buoyancy>(coeffs, c);
}

}  // namespace mixflow::coupling
