// DragLaw: the body every drag-law force model shares: its Coeffs entries (the drag viscosity's,
// `divideByVoidfraction`, the law's own), the viscosity the law sees at the particle (DragViscosity
// closure at the slip |U - v|), and the implicit coefficient beta of that viscosity and slip. A law
// (DiFeliceDrag, GidaspowDrag) gives only beta(d, rho, mu, eps, slip) and its description.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "ForceModel.h"

namespace mixflow::coupling {

class DragLaw : public ForceModel {
 public:
  unsigned needs() const override {
    return kNeedsU | kNeedsRho | kNeedsVoidfraction | viscosity_->needs();
  }
  ParticleForce force(const ParticleState& p, const FluidAtParticle& f) const override {
    ParticleForce out;
    const double slip = mag(f.U - p.v);
    const double mu = viscosity_->viscosity(p, f, slip);
    out.beta = beta(2 * p.radius, f.rho, mu, f.voidfraction, slip);
    return out;
  }

 protected:
  // ownEntries: the law's entries of its Coeffs block besides the viscosity's and
  // divideByVoidfraction (default: yes in formulation B).
  DragLaw(const Dictionary& coeffs, const ForceContext& c, std::vector<std::string> ownEntries) {
    std::vector<std::string> allowed = DragViscosity::entries();
    allowed.push_back("divideByVoidfraction");
    allowed.insert(allowed.end(), ownEntries.begin(), ownEntries.end());
    coeffs.allowOnly(allowed);
    divide_ = coeffs.switchOr("divideByVoidfraction", c.formulation == "B");
    viscosity_ = DragViscosity::New(coeffs, c.liquid);
  }
  // beta [kg/s] of a particle of diameter d at slip |U - v| in a fluid of rho, mu, eps_f.
  virtual double beta(double d, double rho, double mu, double voidfraction, double slip) const = 0;
  std::string viscosityDescription() const { return viscosity_->describe(); }

  bool divide_ = true;

 private:
  std::unique_ptr<DragViscosity> viscosity_;
};

}  // namespace mixflow::coupling
