#include "DragScheme.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "CouplingProperties.h"

namespace mixflow::coupling {

namespace {

// The drag held over the exchange interval T: a coefficient beta > m / T would push the particle
// past the fluid velocity within one interval (unstable beyond 2 m / T), e.g. in a capped
// yield-stress liquid near rest (mu up to viscosityCap). Limited to dragRelaxationLimit x m / T,
// on both sides (action = reaction), counted in the log. Also c beta T / m <=
// dragCounterflowLimit: in a packed cell the next interval's drag pulls the grain towards the
// pore fluid's counterflow to this interval's compaction, c times the compaction velocity, two
// intervals late; in the slaved model v_k+1 = (1 - s) v_k - c s v_k-1 (s = beta T / m) that
// grows once c s > 1.
class HeldDrag : public DragScheme {
 public:
  HeldDrag(double interval, double relaxationLimit, double counterflowLimit)
      : DragScheme(Kind::held, interval),
        relaxationLimit_(relaxationLimit),
        counterflowLimit_(counterflowLimit) {}
  FluidReaction reaction(const ParticleState& p, const CentreForce& d,
                         const AppliedDrag*) const override {
    return FluidReaction{d.force, d.U, p.v, Vec3()};
  }

 protected:
  double scale(const ParticleState& p, const FluidAtParticle&, double c, ParticleForce& force,
               Counts& counts) const override {
    constexpr double kOff = std::numeric_limits<double>::infinity();
    double sMax = relaxationLimit_ > 0 ? relaxationLimit_ : kOff;
    if (counterflowLimit_ > 0 && c > 0) sMax = std::min(sMax, counterflowLimit_ / c);
    const double betaMax = sMax * p.mass / interval_;
    if (force.beta > betaMax) {  // never with both limits off (betaMax infinite)
      const double s = betaMax / force.beta;
      force.beta = betaMax;
      counts.limited += 1.0;
      return s;
    }
    return 1.0;
  }

 private:
  double relaxationLimit_, counterflowLimit_;
};

// The drag law's beta goes to the particle (DemLink integrates it at every DEM step); the model
// columns of the log show the fluid-side coefficient (fluidSideScale).
class ImplicitDrag : public DragScheme {
 public:
  explicit ImplicitDrag(double interval, Kind kind = Kind::implicit) : DragScheme(kind, interval) {}
  FluidReaction reaction(const ParticleState& p, const CentreForce& d,
                         const AppliedDrag* a) const override {
    FluidReaction r{d.force, d.U, p.v, Vec3()};
    r.force.beta = d.force.beta * fluidSideScale(d.force.beta, p.mass);
    if (a) {
      // The mean drag the particle received, F_d = impulse / T, written as
      // beta_T (U - v_s): at the fluid velocity U the particle saw, the fluid gets exactly -F_d.
      r.force.beta = a->beta * fluidSideScale(a->beta, p.mass);
      r.force.explicitForce = a->explicitForce;
      r.U = a->U;
      if (r.force.beta > 0) r.v = a->U - (1.0 / (r.force.beta * interval_)) * a->impulse;
    }
    return r;
  }

 protected:
  double scale(const ParticleState& p, const FluidAtParticle& f, double c, ParticleForce& force,
               Counts& counts) const override {
    // In a packed bed the fluid step makes the pore fluid counterflow the grains (continuity:
    // eps U = -(1 - eps) v in a column closed below), and the next interval's drag pulls the
    // grain towards that lagged counterflow. With s = beta T / m and c = (1 - eps) / eps one
    // exchange multiplies a compaction velocity by (1 - c s) / (1 + s): it grows, alternating
    // in sign, once s (c - 1) > 2 (coupling/README.md, "Exchange interval").
    // dragFluidResponse continuity has the drag see that counterflow, which removes it;
    // pressureCoupling mixture has the fluid step carry the grains' response (no such lag).
    if (f.voidfraction > 0 && countsCounterflow()) {
      const double bound = force.beta * interval_ / p.mass * (c - 1) / 2;
      counts.counterflowMax = std::max(counts.counterflowMax, bound);
      if (bound > 1) counts.counterflowUnstable += 1.0;
    }
    return fluidSideScale(force.beta, p.mass);
  }
  virtual bool countsCounterflow() const { return true; }
};

class MixtureDrag : public ImplicitDrag {
 public:
  explicit MixtureDrag(double interval) : ImplicitDrag(interval, Kind::implicitMixture) {}
  // The implicit drag relaxes the slip v - U as exp(-s t / T), s = beta T / m, so the mean
  // velocity over the interval is U + g (v0 - U), g = (1 - exp(-s)) / s, and sigma = 1 - g
  // (0 for s -> 0, 1 for s -> inf).
  double responseShare(double beta, double mass) const override {
    const double s = mass > 0 ? beta * interval_ / mass : 0.0;
    if (!(s > 1e-12)) return 0.0;
    return 1.0 + std::expm1(-s) / s;
  }

 protected:
  bool countsCounterflow() const override { return false; }
};

class ShareDrag : public ImplicitDrag {
 public:
  explicit ShareDrag(double interval) : ImplicitDrag(interval, Kind::implicitShare) {}
  FluidReaction reaction(const ParticleState& p, const CentreForce& d,
                         const AppliedDrag* a) const override {
    if (!a) return ImplicitDrag::reaction(p, d, nullptr);
    // The particle's drag already saw its fluid share respond (DemLink): the fluid step gets
    // exactly the mean drag of the interval, explicitly; an implicit term would count the
    // share's response twice.
    FluidReaction r{d.force, a->U, p.v, (1.0 / interval_) * a->impulse};
    r.force = ParticleForce{0.0, a->explicitForce + r.explicitDrag};
    return r;
  }

 protected:
  // The particle's share of its cell's fluid: the cell's fluid mass rho eps V_c split over the
  // particle volume (1 - eps) V_c in it. A cell without particle volume: no response.
  void response(const ParticleState& p, const FluidAtParticle& f, const Vec3& ownAcceleration,
                double, CentreForce& d) const override {
    const double solid = 1.0 - f.voidfraction;
    if (solid > 0 && f.rho > 0) d.invFluidMass = solid / (f.rho * f.voidfraction * p.volume());
    d.fluidAcceleration = ownAcceleration;
  }
};

class ContinuityDrag : public ImplicitDrag {
 public:
  explicit ContinuityDrag(double interval) : ImplicitDrag(interval, Kind::implicitContinuity) {}

 protected:
  void response(const ParticleState&, const FluidAtParticle&, const Vec3&, double c,
                CentreForce& d) const override {
    d.counterflow = c;
  }
  bool countsCounterflow() const override { return false; }
};

}  // namespace

DemLink::DragIntegration DragScheme::integrationOf(const CouplingProperties& props) {
  return props.dragIntegration == "held" ? DemLink::DragIntegration::held
                                         : DemLink::DragIntegration::implicit;
}

std::unique_ptr<DragScheme> DragScheme::New(const CouplingProperties& props, double interval) {
  std::unique_ptr<DragScheme> scheme;
  if (integrationOf(props) == DemLink::DragIntegration::held)
    scheme =
        std::make_unique<HeldDrag>(interval, props.dragRelaxationLimit, props.dragCounterflowLimit);
  else if (props.dragFluidResponse == "share")
    scheme = std::make_unique<ShareDrag>(interval);
  else if (props.dragFluidResponse == "continuity")
    scheme = std::make_unique<ContinuityDrag>(interval);
  else if (props.pressureCoupling == "mixture")
    scheme = std::make_unique<MixtureDrag>(interval);
  else
    scheme = std::make_unique<ImplicitDrag>(interval);
  scheme->followsSlip_ = scheme->kind_ != Kind::held && props.dragCoefficientUpdate == "slip";
  return scheme;
}

// Implicit drag: the fluid's step sees the coefficient beta_T = beta / (1 + beta T / m) (backward
// Euler over the CFD step T). A fluid velocity change dU over the step carries the particle along
// with impulse beta_T T dU <= m dU: in the rigid limit (beta T >> m) the fluid takes on the
// particles' inertia, no more, whereas beta itself (up to 1e4 Pa s Stokes drag) would add an
// inertia beta T that no particle has.
double DragScheme::fluidSideScale(double beta, double mass) const {
  return 1.0 / (1.0 + beta * interval_ / mass);
}

void DragScheme::centreForce(const std::vector<std::unique_ptr<ForceModel>>& models,
                             const ParticleState& p, const FluidAtParticle& f,
                             const Vec3& ownAcceleration, CentreForce& d, ModelForces& modelForces,
                             Counts& counts) const {
  d.U = f.U;
  // c = (1 - eps) / eps: how fast the pore fluid counterflows a compacting grain (continuity in
  // a cell of held mixture flux); the continuity response and the stability bounds.
  const double c = f.voidfraction > 0 ? (1.0 - f.voidfraction) / f.voidfraction : 0.0;
  response(p, f, ownAcceleration, c, d);
  std::array<ParticleForce, kMaxForceModels> fms;
  for (size_t m = 0; m < models.size(); ++m) {
    fms[m] = models[m]->force(p, f);
    d.force.beta += fms[m].beta;
    d.force.explicitForce += fms[m].explicitForce;
  }
  if (followsSlip_) d.sample = DragFluidSample::of(f);
  const double s = scale(p, f, c, d.force, counts);
  for (size_t m = 0; m < models.size(); ++m) {
    fms[m].beta *= s;
    modelForces[m] = fms[m].total(f.U, p.v);
  }
}

void DragScheme::handToDem(DemLink& link, const std::vector<ParticleState>& own,
                           const std::vector<OwnedParticle>& owned) const {
  if (kind_ == Kind::held) {
    std::vector<Vec3> forces(own.size());
    for (size_t i = 0; i < own.size(); ++i)
      if (owned[i].host >= 0) forces[i] = owned[i].drag.force.total(owned[i].drag.U, own[i].v);
    link.push(forces);
    return;
  }
  std::vector<AppliedDrag> next(own.size());
  for (size_t i = 0; i < own.size(); ++i) {
    const CentreForce& d = owned[i].drag;
    if (owned[i].host >= 0)
      next[i] = AppliedDrag{d.force.beta,          d.U,
                            d.force.explicitForce, Vec3(),
                            d.invFluidMass,        d.fluidAcceleration,
                            d.counterflow,         d.sample};
  }
  link.pushImplicit(next);
}

}  // namespace mixflow::coupling
