// clang-format off
#include "FluidSampler.H"
#include "fvc.H"
#include "incompressibleTwoPhaseMixture.H"
#include "incompressibleTurbulenceModel.H"
// clang-format on

namespace mixflow::coupling {

namespace {
Vec3 toVec(const Foam::vector& v) { return Vec3(v.x(), v.y(), v.z()); }
}  // namespace

FluidSampler::FluidSampler(const Foam::word& scheme, unsigned needs, const Foam::volVectorField& U,
                           const Foam::volScalarField& rho, const Foam::volScalarField& p,
                           const Foam::incompressibleTwoPhaseMixture& mixture,
                           const Foam::incompressibleTurbulenceModel& turbulence) {
  if (needs & kNeedsU) U_ = Foam::interpolation<Foam::vector>::New(scheme, U);
  if (needs & kNeedsRho) rho_ = Foam::interpolation<Foam::scalar>::New(scheme, rho);
  if (needs & kNeedsMu) {
    // Apparent dynamic viscosity of the liquid/air mixture: rho nu, nu from the phases' viscosity
    // models at the resolved shear rate (Herschel-Bulkley etc.).
    tmu_ = Foam::volScalarField::New("muApparent", rho * mixture.nu());
    mu_ = Foam::interpolation<Foam::scalar>::New(scheme, tmu_());
  }
  if (needs & kNeedsShearRate) {
    // The resolved shear rate as the viscosity models evaluate it: sqrt(2) |symm(grad U)|.
    trate_ = Foam::volScalarField::New("shearRate",
                                       Foam::sqrt(2.0) * Foam::mag(Foam::symm(Foam::fvc::grad(U))));
    rate_ = Foam::interpolation<Foam::scalar>::New(scheme, trate_());
  }
  if (needs & kNeedsDivTau) {
    // div(tau) exactly as mixflowFoam's viscous term (viscousStress full), evaluated explicitly:
    // div(rho nu_eff dev2(T(grad U))) + laplacian(rho nu_eff, U), with the solver's scheme names.
    const Foam::volScalarField rhoNuEff(rho * turbulence.nuEff());
    tdivTau_ = Foam::volVectorField::New(
        "divTau", Foam::fvc::div(rhoNuEff * Foam::dev2(Foam::T(Foam::fvc::grad(U)))) +
                      Foam::fvc::laplacian(rhoNuEff, U));
    divTau_ = Foam::interpolation<Foam::vector>::New(scheme, tdivTau_());
  }
  if (needs & kNeedsGradP) {
    tgradP_ = Foam::fvc::grad(p);
    gradP_ = Foam::interpolation<Foam::vector>::New(scheme, tgradP_());
  }
}

FluidAtParticle FluidSampler::sample(const Vec3& at, long c, double voidfraction) const {
  const Foam::point x(at.x, at.y, at.z);
  FluidAtParticle f;
  if (U_.valid()) f.U = toVec(U_->interpolate(x, c));
  if (rho_.valid()) f.rho = rho_->interpolate(x, c);
  f.voidfraction = voidfraction;
  if (mu_.valid()) f.mu = mu_->interpolate(x, c);
  if (rate_.valid()) f.shearRate = rate_->interpolate(x, c);
  if (divTau_.valid()) f.divTau = toVec(divTau_->interpolate(x, c));
  if (gradP_.valid()) f.gradP = toVec(gradP_->interpolate(x, c));
  return f;
}

Vec3 FluidSampler::velocity(const Vec3& x, long c) const {
  return toVec(U_->interpolate(Foam::point(x.x, x.y, x.z), c));
}

}  // namespace mixflow::coupling
