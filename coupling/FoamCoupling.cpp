// OpenFOAM side of the coupling: one exchange as its list of stages, the fluid checks and the
// resampling after the fluid step. See FoamCoupling.H for the stages.

// OpenFOAM headers (include order matters for OpenFOAM's templates; keep clang-format away).
// clang-format off
#include "FoamCoupling.H"
#include "FluidSampler.H"
#include "ExchangeLog.H"
#include "DemStartup.H"
#include "incompressibleTwoPhaseMixture.H"
#include "incompressibleTurbulenceModel.H"
#include "viscosityModel.H"
// clang-format on

#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "CouplingProperties.h"
#include "DemDict.h"
#include "DemLink.h"
#include "DragLaw.h"
#include "DragScheme.h"
#include "FoamCellLocator.H"
#include "ForceModel.h"
#include "LiggghtsSession.h"
#include "ParticleRouting.h"
#include "SlabBalance.h"
#include "SourceAssembly.h"
#include "Vec3.h"
#include "VoidFractionModel.h"

namespace mixflow::coupling {

namespace {

Vec3 toVec(const Foam::vector& v) { return Vec3(v.x(), v.y(), v.z()); }
Foam::vector toFoam(const Vec3& v) { return Foam::vector(v.x, v.y, v.z); }

[[noreturn]] void fatal(const std::string& msg) {
  FatalErrorInFunction << msg.c_str() << Foam::exit(Foam::FatalError);
  throw std::runtime_error(msg);  // not reached
}

}  // namespace

namespace {
// The liquid's law from transportProperties (phase 1: Newtonian or HerschelBulkley, kinematic
// values) and the air's (phase 2), in SI dynamic units, for the drag viscosity closures.
LiquidLaw liquidLaw(const Foam::incompressibleTwoPhaseMixture& mixture) {
  LiquidLaw law;
  law.density = mixture.rho1().value();
  law.airDensity = mixture.rho2().value();
  const Foam::dictionary& air = mixture.nuModel2().viscosityProperties();
  if (air.found("nu")) law.airViscosity = law.airDensity * air.get<Foam::scalar>("nu");
  const Foam::dictionary& liq = mixture.nuModel1().viscosityProperties();
  const Foam::word model(liq.get<Foam::word>("transportModel"));
  if (model == "HerschelBulkley") {
    const Foam::dictionary& c = liq.optionalSubDict("HerschelBulkleyCoeffs");
    law.yieldStress = law.density * c.get<Foam::scalar>("tau0");
    law.consistency = law.density * c.get<Foam::scalar>("k");
    law.flowIndex = c.get<Foam::scalar>("n");
    law.viscosityCap = law.density * c.get<Foam::scalar>("nu0");
  } else if (liq.found("nu")) {
    law.consistency = law.density * liq.get<Foam::scalar>("nu");
  }
  return law;
}
}  // namespace

// One exchange's particles: those this rank owns in LIGGGHTS and those whose sphere touches its
// mesh (ParticleRouting.h), and its rank-local counts. Kept between exchanges so that the
// particle lists and their cell lists reuse their heap storage; every stage overwrites what it
// fills.
struct FoamCoupling::Exchange {
  std::vector<ParticleState> own;
  std::vector<std::int64_t> tags;
  std::vector<AppliedDrag> applied;  // implicit: what the last interval's drag used and gave
  std::vector<MeshParticle> here;
  std::vector<OwnedParticle> owned;
  DragScheme::Counts counts;
  double remote = 0;                // owned particles whose centre cell is on another rank
  std::vector<double> modelTotals;  // per force model (3 each): forces on the owned particles
};

FoamCoupling::FoamCoupling(const Foam::fvMesh& mesh, Foam::volScalarField& voidfraction,
                           Foam::volScalarField& Ksl, Foam::volVectorField& Us,
                           Foam::volVectorField& fSource, Foam::volScalarField& solidResponse,
                           const Foam::volVectorField& U, const Foam::volScalarField& rho,
                           const Foam::volScalarField& p,
                           const Foam::incompressibleTwoPhaseMixture& mixture,
                           const Foam::incompressibleTurbulenceModel& turbulence,
                           const Foam::uniformDimensionedVectorField& g,
                           Foam::scalar solverVoidfractionMin, const Foam::word& viscousStress,
                           bool resume)
    : mesh_(mesh),
      voidfraction_(voidfraction),
      Ksl_(Ksl),
      Us_(Us),
      fSource_(fSource),
      solidResponse_(solidResponse),
      U_(U),
      rho_(rho),
      p_(p),
      mixture_(mixture),
      turbulence_(turbulence),
      g_(g),
      resume_(resume) {
  readModels(viscousStress, solverVoidfractionMin);
  // The coupling's fields are part of the state: write them with the others.
  Ksl_.writeOpt() = Foam::IOobject::AUTO_WRITE;
  Us_.writeOpt() = Foam::IOobject::AUTO_WRITE;
  fSource_.writeOpt() = Foam::IOobject::AUTO_WRITE;
  startDemHalf();
  makeExchangeStages();
  reportSettings();
  startLogAndBalance();
}

// couplingProperties, its force and void-fraction models, what they need from the fluid, and the
// eps_f floor (the solver's, or couplingProperties' larger one).
void FoamCoupling::readModels(const Foam::word& viscousStress, Foam::scalar solverVoidfractionMin) {
  const std::string propsFile =
      std::string(mesh_.time().globalPath()) + "/constant/couplingProperties";
  ForceContext context;
  context.g = toVec(g_.value());
  context.formulation = "B";  // mixflowFoam's only formulation (it refuses any other)
  context.viscousStress = viscousStress;
  context.liquid = liquidLaw(mixture_);
  try {
    props_ = std::make_unique<CouplingProperties>(CouplingProperties::read(propsFile));
    for (const auto& name : props_->forceModels)
      forceModels_.push_back(ForceModel::New(name, props_->dict, context));
    voidFractionModel_ = VoidFractionModel::New(props_->voidFractionModel, props_->dict);
  } catch (const InputError& e) {
    fatal(e.what());
  }
  if (forceModels_.empty()) fatal(propsFile + ": forceModels is empty");
  needs_ = kNeedsVoidfraction;
  for (const auto& m : forceModels_) needs_ |= m->needs();

  voidfractionMin_ = solverVoidfractionMin;
  if (props_->voidfractionMin) {
    if (*props_->voidfractionMin < solverVoidfractionMin)
      fatal(propsFile + ": voidfractionMin " + std::to_string(*props_->voidfractionMin) +
            " is below mixflowProperties' voidfractionMin " +
            std::to_string(solverVoidfractionMin) + ", which the solver enforces");
    voidfractionMin_ = *props_->voidfractionMin;
  }
}

// LIGGGHTS with the scene (DemStartup.H), the drag scheme, the implicit drag's defect field
// (implicitDragDefect returned) and, when the drag follows the slip at every DEM step, the drag
// laws' beta for the per-step callback.
void FoamCoupling::startDemHalf() {
  DemStart dem = startDem(mesh_, *props_, DragScheme::integrationOf(*props_), g_, resume_);
  dem_ = std::move(dem.session);
  link_ = std::move(dem.link);
  exchangeInterval_ = dem.exchangeInterval;
  drag_ = DragScheme::New(*props_, exchangeInterval_);
  if (drag_->integration() == DemLink::DragIntegration::implicit &&
      props_->implicitDragDefect == "returned")
    dragDefect_ = std::make_unique<Foam::volVectorField>(
        Foam::IOobject("dragDefect", mesh_.time().timeName(), mesh_,
                       Foam::IOobject::READ_IF_PRESENT, Foam::IOobject::AUTO_WRITE),
        mesh_, Foam::dimensionedVector(fSource_.dimensions(), Foam::Zero));
  if (drag_->followsSlip()) {
    // Only the drag laws give beta; the per-step callback skips the explicit forces' models.
    std::vector<const DragLaw*> laws;
    for (const auto& m : forceModels_)
      if (const auto* law = dynamic_cast<const DragLaw*>(m.get())) laws.push_back(law);
    link_->setDragLaw([laws](const ParticleState& p, const FluidAtParticle& f) {
      double beta = 0;
      for (const DragLaw* law : laws) beta += law->force(p, f).beta;
      return beta;
    });
  }
}

// What an exchange's stages keep: the cell locator (with the particle box's periodic z, which
// must be the mesh's), the particle storage, the router to the ranks' (sub)mesh boxes and the
// per-cell source assembly.
void FoamCoupling::makeExchangeStages() {
  auto locator = std::make_unique<FoamCellLocator>(mesh_);
  double zLo = 0, zHi = 0;
  if (link_->periodicZ(zLo, zHi)) {
    const Foam::boundBox all = mesh_.bounds();  // reduced over ranks
    const double tol = 1e-6 * (zHi - zLo);
    if (std::abs(all.min().z() - zLo) > tol || std::abs(all.max().z() - zHi) > tol)
      fatal("the particle box is periodic in z over [" + std::to_string(zLo) + ", " +
            std::to_string(zHi) + "] but the mesh spans [" + std::to_string(all.min().z()) + ", " +
            std::to_string(all.max().z()) + "]: they must match (sample width)");
    locator->setPeriodicZ(zLo, zHi);
    Foam::Info << "Coupling: particle box periodic in z: sphere parts beyond z = " << zLo << " or "
               << zHi << " are wrapped into the mesh" << Foam::endl;
  }
  locator_ = std::move(locator);
  exchange_ = std::make_unique<Exchange>();
  // Every rank's (sub)mesh box, inflated like the locator's: where R1 sends a particle.
  {
    const Foam::boundBox local(mesh_.points(), false);
    const Foam::scalar tol = 1e-9 * Foam::mag(mesh_.bounds().span());
    const double lo[3] = {local.min().x() - tol, local.min().y() - tol, local.min().z() - tol};
    const double hi[3] = {local.max().x() + tol, local.max().y() + tol, local.max().z() + tol};
    router_ = std::make_unique<ParticleRouter>(lo, hi, MPI_COMM_WORLD);
  }
  std::vector<double> volumes(mesh_.V().begin(), mesh_.V().end());
  assembly_ = std::make_unique<SourceAssembly>(
      std::move(volumes), voidfractionMin_,
      props_->sourceDistribution == "centre" ? SourceAssembly::Distribution::centre
                                             : SourceAssembly::Distribution::volume,
      props_->dragReactionVelocity == "cell" ? SourceAssembly::ReactionVelocity::cell
                                             : SourceAssembly::ReactionVelocity::particleMean);
}

// The settings in the log, one line per model.
void FoamCoupling::reportSettings() const {
  Foam::Info << "Coupling (constant/couplingProperties): exchange every " << props_->exchangeEvery
             << " DEM steps (DEM dt " << link_->timeStep() << " s, CFD dt "
             << mesh_.time().deltaTValue() << " s), drag integration "
             << props_->dragIntegration.c_str() << ", interpolation "
             << props_->interpolation.c_str() << ", reaction distribution "
             << props_->sourceDistribution.c_str() << " (drag reaction at the "
             << props_->dragReactionVelocity.c_str() << " velocity), voidfractionMin "
             << voidfractionMin_ << ", pressure coupling " << props_->pressureCoupling.c_str()
             << Foam::nl << "  void fraction: " << voidFractionModel_->describe().c_str()
             << Foam::nl;
  for (const auto& m : forceModels_) Foam::Info << "  force: " << m->describe().c_str() << Foam::nl;
  Foam::Info << Foam::endl;
}

// The exchange log (postProcessing/coupling) and the DEM slabs' re-balancing (demDict).
void FoamCoupling::startLogAndBalance() {
  const Foam::Time& runTime = mesh_.time();
  std::vector<std::string> modelNames;
  for (const auto& m : forceModels_) modelNames.push_back(m->name());
  log_ = std::make_unique<ExchangeLog>(runTime, props_->exchangeEvery, props_->logEvery, modelNames,
                                       resume_);
  readDemBalance(std::string(runTime.globalPath()) + "/system/demDict");
  // Resumed: the stopped run's last re-balance (its last interval ended at the start time).
  if (resume_) lastBalance_ = balanceIndex(runTime.value());
  if (balanceInterval_ > 0)
    Foam::Info << "Coupling: the DEM's x slabs are re-balanced by particles (weight "
               << balanceWeightWord_ << ") every " << balanceInterval_
               << " s (demDict balanceInterval, balanceWeight); the exchange routes each "
                  "particle to the ranks of its cells"
               << Foam::endl;
}

// The index of the last multiple of balanceInterval up to the interval ending at t (half an
// interval of slack for the rounded times of a resumed run).
long FoamCoupling::balanceIndex(double t) const {
  if (balanceInterval_ <= 0) return -1;
  return static_cast<long>(std::floor((t + 0.5 * exchangeInterval_) / balanceInterval_));
}

// demDict's balanceInterval (0 without a demDict: the coupling tests' cases have none) and
// balanceWeight.
void FoamCoupling::readDemBalance(const std::string& file) {
  if (!std::ifstream(file)) return;
  try {
    const DemSpec dem = DemDict::read(Dictionary::readFile(file)).dem;
    balanceInterval_ = dem.balanceInterval;
    balanceWeightWord_ = dem.balanceWeight;
  } catch (const InputError& e) {
    fatal(e.what());
  }
}

FoamCoupling::~FoamCoupling() = default;

Foam::label FoamCoupling::exchangeEvery() const { return props_->exchangeEvery; }

// A resumed run's first interval keeps the drag the stopped run had set for it (read back with
// the particles' restart, DemLink.h), so it runs as it would have without the stop; a restart
// without that state gets the drag computed from the fluid at the write.
void FoamCoupling::handToDem(Exchange& x) {
  if (resume_ && exchanges_ == 0) {
    if (link_->keepRestoredState()) {
      Foam::Info << "Coupling: resumed with the drag state of the particles' restart" << Foam::endl;
      return;
    }
    Foam::Info << "Coupling: the particles' restart holds no drag state; the first interval's "
                  "drag is computed from the fluid at the write"
               << Foam::endl;
  }
  drag_->handToDem(*link_, x.own, x.owned);
}

void FoamCoupling::exchange() {
  const double wall0 = MPI_Wtime();
  Exchange& x = *exchange_;
  x.counts = DragScheme::Counts();
  x.remote = 0;
  clock_.time(StageClock::pull, [&] { pull(x); });
  clock_.time(StageClock::locate, [&] { locate(x); });
  clock_.time(StageClock::voidfraction, [&] { voidFraction(x); });
  clock_.time(StageClock::sample, [&] { sampleFluid(x); });
  clock_.time(StageClock::forces, [&] { forces(x); });
  clock_.time(StageClock::gather, [&] { gather(x); });
  clock_.time(StageClock::toDem, [&] { handToDem(x); });
  clock_.time(StageClock::deposit, [&] { depositSources(x); });
  clock_.time(StageClock::totals,
              [&] { log_->reduce(assembly_->totals(), x.remote, x.counts, x.own, x.modelTotals); });
  // Rows by time index (the uninterrupted run's, resumed or not); the resumed start's exchange
  // repeats the one the stopped run logged at that time.
  log_->write(mesh_.time().timeIndex(), link_->step(), MPI_Wtime() - wall0, clock_,
              !(resume_ && exchanges_ == 0));
  clock_.clear();
  ++exchanges_;
}

void FoamCoupling::evolve() {
  clock_.time(StageClock::dem, [&] {
    // Between intervals the per-particle drag state lives in LIGGGHTS' per-atom arrays, which
    // migrate with the particles, so the slabs can move here as at any re-neighbouring.
    // Re-balances fall on multiples of balanceInterval in simulated time, so a resumed run
    // (which starts from the stopped run's slabs) re-balances when the uninterrupted run did.
    const long k = balanceIndex(mesh_.time().value());
    if (balanceInterval_ > 0 && k > lastBalance_) {
      if (!dem::balanceSlabs(*dem_, MPI_COMM_WORLD, dem::balanceWeight(balanceWeightWord_)) &&
          lastBalance_ < 0 && Foam::Pstream::parRun())
        Foam::Info
            << "Coupling: balanceInterval: the DEM's processor grid is not x slabs (set "
               "demDict processors \"* 1 1\") or there is one rank; the slabs stay as they are"
            << Foam::endl;
      lastBalance_ = k;
    }
    dem_->run(props_->exchangeEvery);
  });
  exchange();
}

void FoamCoupling::pull(Exchange& x) {
  link_->pull(x.own, x.tags);
  // Before this exchange renews eps_f and the sources: the last fluid step's.
  if (drag_->usesFluidOwnAcceleration()) updateFluidOwnAcceleration();
  if (drag_->integration() == DemLink::DragIntegration::implicit) link_->pullApplied(x.applied);
}

void FoamCoupling::locate(Exchange& x) {
  router_->toMeshes(x.own, x.tags, x.here);
  for (MeshParticle& m : x.here) {
    // Seed: the cell this rank found the particle's centre in at the last exchange.
    const bool known = m.tag >= 0 && static_cast<size_t>(m.tag) < lastCell_.size() &&
                       lastCell_[m.tag].exchange == exchanges_ - 1;
    voidFractionModel_->locate(m.p, known ? lastCell_[m.tag].cell : -1, *locator_, m.cells);
  }
}

void FoamCoupling::voidFraction(Exchange& x) {
  assembly_->reset();
  for (const MeshParticle& m : x.here) {
    assembly_->addSolid(m.cells);
    if (m.cells.centreCell < 0 || m.tag < 0) continue;
    if (static_cast<size_t>(m.tag) >= lastCell_.size()) lastCell_.resize(m.tag + 1);
    lastCell_[m.tag] = {exchanges_, m.cells.centreCell};
  }
  assembly_->finishVoidfraction();
  Foam::scalarField& vf = voidfraction_.primitiveFieldRef();
  const std::vector<double>& eps = assembly_->voidfraction();
  forAll(vf, c) { vf[c] = eps[c]; }
}

// The fluid at the particles whose centre is here.
void FoamCoupling::sampleFluid(Exchange& x) {
  const FluidSampler fluid(Foam::word(props_->interpolation), needs_ | kNeedsU | kNeedsRho, U_,
                           rho_, p_, mixture_, turbulence_);
  const Foam::scalarField& vf = voidfraction_.primitiveField();
  samples_.clear();
  for (MeshParticle& m : x.here) {
    const long c = m.cells.centreCell;
    if (c < 0) continue;
    m.fluid = fluid.sample(m.p.x, c, vf[c]);
    if (drag_->resamplesFluid()) samples_.push_back(Sample{m.owner, m.ownerIndex, m.p.x, c});
  }
}

void FoamCoupling::forces(Exchange& x) {
  const bool share = drag_->usesFluidOwnAcceleration();
  for (MeshParticle& m : x.here) {
    const long c = m.cells.centreCell;
    if (c < 0) continue;
    drag_->centreForce(forceModels_, m.p, m.fluid, share ? fluidOwnAcceleration_[c] : Vec3(),
                       m.drag, m.modelForces, x.counts);
  }
}

// Parts and forces to the owners, and what the fluid receives for each owned particle.
void FoamCoupling::gather(Exchange& x) {
  x.modelTotals.assign(3 * forceModels_.size(), 0.0);
  router_->toOwners(x.here, x.own.size(), forceModels_.size(), x.modelTotals, x.owned);
  sampleHost_.assign(x.own.size(), -1);
  const bool interval = !x.applied.empty() && exchanges_ > 0;  // the first has none behind it
  for (size_t i = 0; i < x.own.size(); ++i) {
    OwnedParticle& o = x.owned[i];
    const ParticleState& p = x.own[i];
    assembly_->countParticle(p, std::max(0.0, p.volume() - o.inside), o.host >= 0);
    if (o.host < 0) continue;  // centre in no cell of the mesh: no fluid force
    if (o.host != router_->rank()) x.remote += 1;
    sampleHost_[i] = o.host;
    o.reaction = drag_->reaction(p, o.drag, interval ? &x.applied[i] : nullptr);
    o.sigma = drag_->responseShare(o.drag.force.beta, p.mass);
    ParticleState moved = p;
    moved.v = o.reaction.v;
    assembly_->addParticleForce(moved, o.reaction.force, o.reaction.U, o.reaction.explicitDrag);
  }
}

// The reaction to the ranks holding the particles' parts, and the fluid's fields.
void FoamCoupling::depositSources(Exchange& x) {
  std::vector<Vec3>& Ucell = Udeposit_;
  Ucell.resize(mesh_.nCells());
  forAll(U_, c) { Ucell[c] = toVec(U_[c]); }
  for (const ReactionRecord& r : router_->toParts(x.owned)) {
    const MeshParticle& m = x.here.at(static_cast<size_t>(r.workIndex));
    ParticleState p = m.p;
    p.v = r.reaction.v;
    assembly_->depositReaction(p, m.cells, r.reaction.force, r.reaction.U, r.insideTotal,
                               r.holdsCentre, Ucell, r.reaction.explicitDrag);
    if (r.sigma > 0) assembly_->depositResponse(m.cells, r.sigma);
  }
  assembly_->finishSources(Ucell);

  Foam::scalarField& K = Ksl_.primitiveFieldRef();
  Foam::vectorField& Usf = Us_.primitiveFieldRef();
  Foam::vectorField& fs = fSource_.primitiveFieldRef();
  Foam::scalarField& psi = solidResponse_.primitiveFieldRef();
  const auto& aK = assembly_->Ksl();
  const auto& aUs = assembly_->Us();
  const auto& aF = assembly_->fSource();
  const auto& aPsi = assembly_->solidResponse();
  forAll(K, c) {
    K[c] = aK[c];
    Usf[c] = toFoam(aUs[c]);
    fs[c] = toFoam(aF[c]);
    psi[c] = aPsi[c];
  }
  if (dragDefect_) fs += dragDefect_->primitiveField();
}

// The fluid step just taken saw the drag Ksl (Us - U_new) + fSource, which is the grains'
// impulse over the interval only at U_new = U_held (the cells' U at the deposit): the rest,
// -Ksl (U_new - U_held), is the grains' response to the new fluid velocity, which the next
// interval's impulse brings again. It goes back to the fluid at the next deposit.
void FoamCoupling::recordDragDefect() {
  if (!dragDefect_ || Udeposit_.size() != static_cast<size_t>(mesh_.nCells())) return;
  Foam::vectorField& d = dragDefect_->primitiveFieldRef();
  forAll(d, c) { d[c] = Ksl_[c] * (U_[c] - toFoam(Udeposit_[c])); }
  dragDefect_->correctBoundaryConditions();
}

// The fluid's acceleration over its last step by its own forces (pressure, viscous stress,
// gravity, surface tension, advection), the particles' force removed: dU/dt - S / (eps rho),
// S = Ksl (Us - U) + (explicit drag reaction) the particles' drag per volume in that step (their
// buoyancy and viscous-force reactions are forces the fluid keeps within the interval). The drag's
// fluid share follows it within the next DEM interval (DemLink), one step lagged.
void FoamCoupling::updateFluidOwnAcceleration() {
  const Foam::label n = mesh_.nCells();
  fluidOwnAcceleration_.assign(n, Vec3());
  const bool first = Ulast_.size() != static_cast<size_t>(n);
  if (!first) {
    const std::vector<Vec3>& lastDrag = assembly_->fDragSource();  // not yet reset: last step's
    forAll(U_, c) {
      const double mass = voidfraction_[c] * rho_[c];  // fluid mass per cell volume
      const Vec3 S = Ksl_[c] * toVec(Us_[c] - U_[c]) + lastDrag[c];
      if (mass > 0)
        fluidOwnAcceleration_[c] =
            (1.0 / exchangeInterval_) * (toVec(U_[c]) - Ulast_[c]) - (1.0 / mass) * S;
    }
  }
  Ulast_.resize(n);
  forAll(U_, c) { Ulast_[c] = toVec(U_[c]); }
}

// pressureCoupling mixture: the fluid step just taken counted on each particle's drag pulling it
// towards the new fluid velocity over the next interval; give the drag that velocity. One
// point-to-point round: the rank holding a particle's centre samples U there (same place and
// scheme as the exchange) and sends it to the particle's DEM owner, which keeps the sample of
// the rank the exchange took the force from. No DEM step runs between the exchange and this,
// so the owners' local particle order is the exchange's.
void FoamCoupling::resampleFluidVelocity() {
  if (!drag_->resamplesFluid()) return;
  clock_.time(StageClock::resample, [&] {
    const FluidSampler fluid(Foam::word(props_->interpolation), kNeedsU, U_, rho_, p_, mixture_,
                             turbulence_);
    std::vector<std::vector<VelocityRecord>> send(router_->size());
    for (const Sample& s : samples_)
      send[s.owner].push_back({s.ownerIndex, fluid.velocity(s.x, s.cell)});
    const auto in = router_->route(std::move(send), VelocityRecord::kWidth);
    std::vector<Vec3> Unew(sampleHost_.size());
    std::vector<char> has(sampleHost_.size(), 0);
    for (int q = 0; q < router_->size(); ++q)
      for (const VelocityRecord& r : in[q]) {
        const size_t i = static_cast<size_t>(r.ownerIndex);
        if (i >= sampleHost_.size() || sampleHost_[i] != q) continue;
        Unew[i] = r.U;
        has[i] = 1;
      }
    link_->setFluidVelocity(Unew, has,
                            props_->dragFluidVelocity == "extrapolated" ? exchangeInterval_ : 0.0);
  });
}

void FoamCoupling::checkFluid() const {
  // A diverging step shows as a runaway velocity long before a NaN (OpenFOAM traps floating-point
  // exceptions with a bare stack trace): stop with the field, the place and the time instead.
  const Foam::vectorField& U = U_.primitiveField();
  const Foam::scalarField& p = p_.primitiveField();
  forAll(U, c) {
    const double u = Foam::mag(U[c]);
    const bool badU = !std::isfinite(u) || u > props_->maxVelocity;
    if (badU || !std::isfinite(p[c])) {
      const Foam::point& x = mesh_.C()[c];
      std::ostringstream m;
      m << "the fluid diverged at t = " << mesh_.time().value() << " s: field "
        << (badU ? "U, |U| = " : "p = ") << (badU ? u : p[c]) << " in cell " << c << " at ("
        << x.x() << " " << x.y() << " " << x.z() << ") (maxVelocity " << props_->maxVelocity
        << " m/s, couplingProperties). Outputs up to the last write time are kept "
           "(time directories, postProcessing/, VTK/); dragIntegration "
        << (drag_->integration() == DemLink::DragIntegration::held ? "implicit" : "held")
        << ", a smaller exchangeEvery or a finer DEM step are the usual cures";
      fatal(m.str());
    }
  }
}

}  // namespace mixflow::coupling
