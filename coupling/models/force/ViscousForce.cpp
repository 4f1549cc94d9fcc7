// viscousForce: the force of the fluid's viscous stress field on the particle volume,
//   F_v = V_p div(tau),   tau = rho nu_eff (grad U + grad U^T) (mixflowFoam's deviatoric stress,
//                         positive in tension), div(tau) the viscous force per unit volume the
//                         fluid's momentum equation carries on its right-hand side.
// Sign: Li & Zhao print F_v = -(div tau) V_p. That is the same force written with
// CFDEMcoupling's field "divTau", which holds minus the divergence of the viscous stress (the
// momentum-flux sign convention, tau counted positive in compression). In mixflowFoam's
// convention the force is +V_p div(tau), the analogue of -V_p grad(p) for the pressure: a
// particle in a fluid whose viscous stresses push a fluid parcel towards +x is pushed towards +x.
// It vanishes for fluid at rest and for uniform shear.
//
// Consistency: with mixflowFoam's `viscousStress full` the fluid carries the whole div(tau) and
// loses the reaction -F_v/V_c through fSource (formulation B). With `voidfractionWeighted` the
// fluid already carries only div(eps_f tau); returning F_v as well would count the particles'
// share twice, so that combination is refused.
#include <sstream>

#include "ForceModel.h"

namespace mixflow::coupling {

namespace {

class ViscousForce final : public ForceModel {
 public:
  ViscousForce(const Dictionary& coeffs, const ForceContext& c) {
    coeffs.allowOnly({});
    if (c.viscousStress != "full")
      coeffs.fail("viscousForce",
                  "the particle viscous force V_p div(tau) needs the fluid's full viscous term "
                  "(mixflowProperties viscousStress full); with div(eps_f tau) the fluid "
                  "already lacks the particles' share and the force would be counted twice");
  }
  const std::string& name() const override {
    static const std::string n = "viscousForce";
    return n;
  }
  unsigned needs() const override { return kNeedsDivTau; }
  ParticleForce force(const ParticleState& p, const FluidAtParticle& f) const override {
    ParticleForce out;
    out.explicitForce = p.volume() * f.divTau;
    return out;
  }
  std::string describe() const override {
    return "viscousForce: +V_p div(tau) (tau = rho nu_eff (grad U + grad U^T), the fluid's own "
           "viscous term; the paper's -(div tau) V_p in CFDEM's sign, docs/model.md); explicit "
           "(fSource)";
  }
};

}  // namespace

std::unique_ptr<ForceModel> makeViscousForce(const Dictionary& coeffs, const ForceContext& c) {
  return std::make_unique<ViscousForce>(coeffs, c);
}

}  // namespace mixflow::coupling
