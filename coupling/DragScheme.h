// How the drag is integrated over a DEM interval and what the fluid gets back for it, chosen once
// from couplingProperties (dragIntegration, dragFluidResponse, pressureCoupling):
//   held                the exchange's force held over the interval, beta limited
//                       (dragRelaxationLimit, dragCounterflowLimit); the fluid gets that force;
//   implicit            beta, U and F_explicit held, the drag updated at every DEM step
//                       (DemLink.h); the fluid step sees beta / (1 + beta T / m), and from the
//                       second exchange on the mean drag the particle received over the interval;
//   implicit mixture    the same, and the pressure equation carries each grain's drag response
//                       (sigma, SourceAssembly::depositResponse); U is sampled again after the
//                       fluid step;
//   implicit share      the drag sees its share of the cell's fluid respond; the fluid gets the
//                       interval's drag impulse / T explicitly;
//   implicit continuity the drag sees the pore fluid's counterflow at a held mixture flux.
#pragma once

#include <memory>
#include <vector>

#include "DemLink.h"
#include "ForceModel.h"
#include "ParticleRouting.h"

namespace mixflow::coupling {

struct CouplingProperties;

class DragScheme {
 public:
  enum class Kind { held, implicit, implicitMixture, implicitShare, implicitContinuity };
  // interval: the exchange interval T [s].
  static std::unique_ptr<DragScheme> New(const CouplingProperties& props, double interval);
  // How LIGGGHTS integrates the drag for these properties (before the interval is known).
  static DemLink::DragIntegration integrationOf(const CouplingProperties& props);
  virtual ~DragScheme() = default;

  Kind kind() const { return kind_; }
  DemLink::DragIntegration integration() const {
    return kind_ == Kind::held ? DemLink::DragIntegration::held
                               : DemLink::DragIntegration::implicit;
  }
  // implicit share: the drag needs the fluid's own acceleration at the particle's cell.
  bool usesFluidOwnAcceleration() const { return kind_ == Kind::implicitShare; }
  // implicit mixture: after the fluid step the drag's U is sampled again.
  bool resamplesFluid() const { return kind_ == Kind::implicitMixture; }
  // implicit, dragCoefficientUpdate slip: the drag laws are evaluated at every DEM step.
  bool followsSlip() const { return followsSlip_; }

  // Rank-local counts of one exchange, for the log.
  struct Counts {
    double limited = 0;              // held: particles whose beta was limited
    double counterflowUnstable = 0;  // implicit: particles beyond the packed-bed bound
    double counterflowMax = 0;       // implicit: max of beta T / m (c - 1) / 2
  };

  // At the rank holding the particle's centre: the models' forces summed into d (fluid velocity,
  // response terms, limit), and each model's force on the particle for the log (fluid-side
  // coefficient). ownAcceleration: the fluid's own acceleration in the centre cell (share only).
  void centreForce(const std::vector<std::unique_ptr<ForceModel>>& models, const ParticleState& p,
                   const FluidAtParticle& f, const Vec3& ownAcceleration, CentreForce& d,
                   ModelForces& modelForces, Counts& counts) const;
  // At the owner: what the fluid receives for particle p with the centre's force d; applied is
  // what the implicit drag used and gave over the interval just run (null: none behind).
  virtual FluidReaction reaction(const ParticleState& p, const CentreForce& d,
                                 const AppliedDrag* applied) const = 0;
  // The share sigma of the particle's displacement that follows the fluid (mixture only).
  virtual double responseShare(double /*beta*/, double /*mass*/) const { return 0.0; }
  // The next interval's forces to LIGGGHTS (owned[i] for local particle i; no centre: none).
  void handToDem(DemLink& link, const std::vector<ParticleState>& own,
                 const std::vector<OwnedParticle>& owned) const;

 protected:
  DragScheme(Kind kind, double interval) : kind_(kind), interval_(interval) {}
  // The drag's response terms in d (share, continuity); c = (1 - eps) / eps.
  virtual void response(const ParticleState&, const FluidAtParticle&, const Vec3&, double /*c*/,
                        CentreForce&) const {}
  // Limits or scales d.force; returns the factor for the models' beta in the log.
  virtual double scale(const ParticleState& p, const FluidAtParticle& f, double c,
                       ParticleForce& force, Counts& counts) const = 0;
  // beta_T / beta of the implicit drag's fluid side: 1 / (1 + beta T / m).
  double fluidSideScale(double beta, double mass) const;

  Kind kind_;
  double interval_;
  // implicit, dragCoefficientUpdate slip: the fluid sample goes with beta to the DEM (DemLink).
  bool followsSlip_ = false;
};

}  // namespace mixflow::coupling
