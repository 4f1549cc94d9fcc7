// OpenFOAM side of the coupling: mesh search, field sampling, field filling, checks and the log.
// See FoamCoupling.H for the sequence of an exchange.

// OpenFOAM headers (include order matters for OpenFOAM's templates; keep clang-format away).
// clang-format off
#include "FoamCoupling.H"
#include "fvc.H"
#include "interpolation.H"
#include "incompressibleTwoPhaseMixture.H"
#include "incompressibleTurbulenceModel.H"
#include "viscosityModel.H"
// clang-format on

#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "CoupledResume.h"
#include "CouplingProperties.h"
#include "DemLink.h"
#include "FoamCellLocator.H"
#include "ForceModel.h"
#include "LiggghtsSession.h"
#include "SourceAssembly.h"
#include "SparseExchange.h"
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

// Totals vector layout (summed over ranks, except the last entry: min).
enum Total {
  kParticles,
  kParticlesOutside,
  kParticleVolume,
  kOutsideVolume,
  kClippedVolume,
  kFluidSeenVolume,
  kFpX,
  kFpY,
  kFpZ,
  kFfX,
  kFfY,
  kFfZ,
  kForceScale,
  kDragX,
  kDragY,
  kDragZ,
  kVx,
  kVy,
  kVz,  // sum of particle velocities
  kX,
  kY,
  kZ,                    // sum of particle positions
  kRemote,               // particles whose fluid cell is on another rank than their DEM owner
  kDragLimited,          // particles whose drag coefficient was limited (dragRelaxationLimit)
  kCounterflowUnstable,  // implicit drag: particles beyond the packed-bed stability bound
  kNumSums,
  kMinVoidfraction = kNumSums,
  kCounterflowMax,  // implicit drag: max over particles of s (c - 1) / 2 (stable below 1)
  kNumTotals
};

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
  const Foam::Time& runTime = mesh.time();
  const std::string caseDir = runTime.globalPath();
  const std::string propsFile = caseDir + "/constant/couplingProperties";

  ForceContext context;
  context.g = toVec(g.value());
  context.formulation = "B";  // mixflowFoam's only formulation (it refuses any other)
  context.viscousStress = viscousStress;
  context.liquid = liquidLaw(mixture);
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
  if (props_->hasVoidfractionMin) {
    if (props_->voidfractionMin < solverVoidfractionMin)
      fatal(propsFile + ": voidfractionMin " + std::to_string(props_->voidfractionMin) +
            " is below mixflowProperties' voidfractionMin " +
            std::to_string(solverVoidfractionMin) + ", which the solver enforces");
    voidfractionMin_ = props_->voidfractionMin;
  }

  // The coupling's fields are part of the state: write them with the others.
  Ksl_.writeOpt() = Foam::IOobject::AUTO_WRITE;
  Us_.writeOpt() = Foam::IOobject::AUTO_WRITE;
  fSource_.writeOpt() = Foam::IOobject::AUTO_WRITE;

  startDem();

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
  // Every rank's (sub)mesh box, inflated like the locator's: where R1 sends a particle.
  {
    const Foam::boundBox local(mesh_.points(), false);
    const Foam::scalar tol = 1e-9 * Foam::mag(mesh_.bounds().span());
    const double mine[6] = {local.min().x() - tol, local.min().y() - tol, local.min().z() - tol,
                            local.max().x() + tol, local.max().y() + tol, local.max().z() + tol};
    int size = 1;
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    boxes_.resize(6 * size);
    MPI_Allgather(mine, 6, MPI_DOUBLE, boxes_.data(), 6, MPI_DOUBLE, MPI_COMM_WORLD);
  }
  std::vector<double> volumes(mesh_.V().begin(), mesh_.V().end());
  assembly_ = std::make_unique<SourceAssembly>(
      std::move(volumes), voidfractionMin_,
      props_->sourceDistribution == "centre" ? SourceAssembly::Distribution::centre
                                             : SourceAssembly::Distribution::volume,
      props_->dragReactionVelocity == "cell" ? SourceAssembly::ReactionVelocity::cell
                                             : SourceAssembly::ReactionVelocity::particleMean);

  Foam::Info << "Coupling (constant/couplingProperties): exchange every " << props_->exchangeEvery
             << " DEM steps (DEM dt " << link_->timeStep() << " s, CFD dt " << runTime.deltaTValue()
             << " s), drag integration " << props_->dragIntegration.c_str() << ", interpolation "
             << props_->interpolation.c_str() << ", reaction distribution "
             << props_->sourceDistribution.c_str() << " (drag reaction at the "
             << props_->dragReactionVelocity.c_str() << " velocity), voidfractionMin "
             << voidfractionMin_ << ", pressure coupling " << props_->pressureCoupling.c_str()
             << Foam::nl << "  void fraction: " << voidFractionModel_->describe().c_str()
             << Foam::nl;
  for (const auto& m : forceModels_) Foam::Info << "  force: " << m->describe().c_str() << Foam::nl;
  Foam::Info << Foam::endl;

  writeLogHeader();
}

FoamCoupling::~FoamCoupling() = default;

Foam::label FoamCoupling::exchangeEvery() const { return props_->exchangeEvery; }

// Parallel runs: LIGGGHTS' processor grid is made to match OpenFOAM's `simple` decomposition
// (n = (nx ny nz), processor index x-fastest, which is LIGGGHTS' `map xyz`), so that with the
// DEM box = the mesh's bounding box a particle's DEM owner usually also holds its fluid cells and
// R1-R3 of an exchange stay on the rank. Skipped if the DEM script sets `processors` itself or
// the decomposition is not `simple` (the exchange is then still correct, with more traffic; the
// log's "fluid cell on another rank" count shows how much).
void FoamCoupling::demProcessorGrid(const std::string& script) {
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (size == 1) return;
  {
    std::ifstream in(script);
    for (std::string line; std::getline(in, line);) {
      std::istringstream words(line);
      std::string first;
      if (words >> first && first == "processors") {
        Foam::Info << "Coupling: the DEM script sets its own processor grid" << Foam::endl;
        return;
      }
    }
  }
  const std::string file = std::string(mesh_.time().globalPath()) + "/system/decomposeParDict";
  try {
    const Dictionary d = Dictionary::readFile(file);
    const std::string method = d.text("method");
    if (method != "simple") {
      Foam::Info << "Coupling: decomposition method " << method.c_str()
                 << " has no matching LIGGGHTS grid; LIGGGHTS decomposes its box itself"
                 << Foam::endl;
      return;
    }
    const std::vector<double> n = d.subDict("simpleCoeffs").scalars("n", Range::positive());
    if (n.size() != 3 || n[0] * n[1] * n[2] != size)
      fatal(file + ": simpleCoeffs n must have 3 entries whose product is the rank count");
    std::ostringstream cmd;
    cmd << "processors " << n[0] << " " << n[1] << " " << n[2] << " map xyz";
    dem_->command(cmd.str());
    Foam::Info << "Coupling: LIGGGHTS grid " << cmd.str().c_str()
               << " (matches the simple decomposition)" << Foam::endl;
  } catch (const InputError& e) {
    fatal(e.what());
  }
}

void FoamCoupling::startDem() {
  const Foam::Time& runTime = mesh_.time();
  const std::string caseDir = runTime.globalPath();
  const std::string demDir = caseDir + "/dem";
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank == 0) std::filesystem::create_directories(demDir);
  MPI_Barrier(MPI_COMM_WORLD);
  dem_ = std::make_unique<dem::LiggghtsSession>(MPI_COMM_WORLD, demDir);

  // The scene's LIGGGHTS commands, line by line ('&' continues a line, '#' starts a comment),
  // through the session so that dem/in.liggghts replays the whole run.
  const std::string script =
      props_->demScript.front() == '/' ? props_->demScript : caseDir + "/" + props_->demScript;
  std::ifstream in(script);
  if (!in) fatal("cannot open the DEM script " + script + " (demScript in couplingProperties)");
  demProcessorGrid(script);
  // ${mixflowCase} in the script is the case directory (scripts stay valid when a case moves).
  dem_->command("variable mixflowCase string " + caseDir);
  // Resuming: the particles come from the last field write's restart instead of the script's
  // read_restart (the settled sample); every other line (contacts, walls) is the script's.
  std::string resumeRestart;
  if (resume_) {
    try {
      const CoupledResumeState st = CoupledResumeState::read(caseDir);
      const double t = runTime.value();
      // The time directory's name is rounded (OpenFOAM's timePrecision): within a thousandth of
      // a step is the same write.
      if (std::abs(t - st.time) > 1e-3 * std::max(runTime.deltaTValue(), 1e-300))
        fatal(CoupledResumeState::path(caseDir) + ": entry 'time': " + std::to_string(st.time) +
              " s, but the fluid starts at " + runTime.timeName() +
              " s: set startFrom latestTime and remove the time directories after " + st.timeName +
              " (scripts/ResumeFunctions, resumeMixtureCase, does both)");
      resumeRestart = caseDir + "/" + st.restartFile;
      Foam::Info << "Coupling: resuming at t = " << st.timeName.c_str() << " s from "
                 << st.restartFile.c_str() << Foam::endl;
    } catch (const InputError& e) {
      fatal(e.what());
    }
  }
  bool restartReplaced = false;
  std::string line, pending;
  while (std::getline(in, line)) {
    const size_t hash = line.find('#');
    if (hash != std::string::npos) line.erase(hash);
    while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back()))) line.pop_back();
    if (!line.empty() && line.back() == '&') {
      line.pop_back();
      pending += line + " ";
      continue;
    }
    line = pending + line;
    pending.clear();
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    if (resume_ && line.compare(line.find_first_not_of(" \t"), 12, "read_restart") == 0) {
      line = "read_restart " + resumeRestart;
      restartReplaced = true;
    }
    dem_->command(line);
  }
  if (resume_ && !restartReplaced)
    fatal(script +
          ": -resume needs a DEM script that starts from read_restart (a mixture "
          "scene's system/in.liggghts)");

  link_ = std::make_unique<DemLink>(*dem_, props_->dragIntegration == "held"
                                               ? DemLink::DragIntegration::held
                                               : DemLink::DragIntegration::implicit);
  // The external force array is not initialised by LIGGGHTS: zero it before the setup run.
  std::vector<ParticleState> particles;
  std::vector<std::int64_t> tags;
  link_->pull(particles, tags);
  if (link_->mode() == DemLink::DragIntegration::held)
    link_->push(std::vector<Vec3>(particles.size()));
  else
    link_->pushImplicit(std::vector<AppliedDrag>(particles.size()));
  dem_->command("run 0");
  dem_->invalidateSetup();
  demStep0_ = link_->step();
  time0_ = runTime.value();

  // Time steps: one CFD step is exchangeEvery DEM steps, fixed.
  const double dtDem = link_->timeStep();
  exchangeInterval_ = props_->exchangeEvery * dtDem;
  const double dtCfd = runTime.deltaTValue();
  const double expected = props_->exchangeEvery * dtDem;
  if (std::abs(dtCfd - expected) > 1e-9 * expected)
    fatal("CFD deltaT " + std::to_string(dtCfd) + " s must equal exchangeEvery (" +
          std::to_string(props_->exchangeEvery) + ") x DEM timestep (" + std::to_string(dtDem) +
          " s) = " + std::to_string(expected) + " s (system/controlDict deltaT)");
  if (runTime.controlDict().lookupOrDefault<bool>("adjustTimeStep", false))
    fatal("adjustTimeStep must be off in a coupled run (the CFD step is exchangeEvery DEM steps)");

  // Gravity: the particles' weight (LIGGGHTS fix gravity) and the fluid's g must agree, or
  // buoyancy and weight would not balance.
  const Vec3 gDem = link_->gravity();
  const Vec3 gCfd = toVec(g_.value());
  if (mag(gDem - gCfd) > 1e-9 * std::max(mag(gCfd), 1e-300)) {
    std::ostringstream s;
    s << "gravity differs: LIGGGHTS fix gravity gives (" << gDem.x << " " << gDem.y << " " << gDem.z
      << "), constant/g (" << gCfd.x << " " << gCfd.y << " " << gCfd.z << ")";
    fatal(s.str());
  }
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
        << (link_->mode() == DemLink::DragIntegration::held ? "implicit" : "held")
        << ", a smaller exchangeEvery or a finer DEM step are the usual cures";
      fatal(m.str());
    }
  }
}

// Implicit drag: the fluid's step sees the coefficient beta_T = beta / (1 + beta T / m) (backward
// Euler over the CFD step T); this returns beta_T / beta. A fluid velocity change dU over the step
// carries the particle along with impulse beta_T T dU <= m dU: in the rigid limit (beta T >> m) the
// fluid takes on the particles' inertia, no more, whereas beta itself (up to 1e4 Pa s Stokes drag)
// would add an inertia beta T that no particle has.
double FoamCoupling::fluidSideScale(double beta, double mass) const {
  return 1.0 / (1.0 + beta * exchangeInterval_ / mass);
}

namespace {
// pressureCoupling mixture: the share sigma of a particle's displacement over the next interval
// that follows the fluid velocity U it is dragged towards. The implicit drag relaxes the slip
// v - U as exp(-s t / T), s = beta T / m, so the mean velocity over the interval is
// U + g (v0 - U), g = (1 - exp(-s)) / s, and sigma = 1 - g (0 for s -> 0, 1 for s -> inf).
double responseShare(double beta, double mass, double interval) {
  const double s = mass > 0 ? beta * interval / mass : 0.0;
  if (!(s > 1e-12)) return 0.0;
  return 1.0 + std::expm1(-s) / s;
}
}  // namespace

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

void FoamCoupling::evolve() {
  dem_->run(props_->exchangeEvery);
  exchange();
}

namespace {

// Record layouts of the three point-to-point rounds of an exchange (doubles).
constexpr int kR1 = 10;      // owner index, tag, x(3), v(3), radius, mass
constexpr int kR2Head = 16;  // owner index, work index, local inside volume, holds centre,
                             // beta, F_explicit(3), U_i(3), 1 / m_f, fluid's own acceleration(3),
                             // counterflow factor c; then 3 per force model
constexpr int kR3 = 17;      // work index, beta, F_explicit(3), U_i(3), v(3), inside total,
                             // holds centre, drag given explicitly(3) (part of F_explicit),
                             // sigma (pressureCoupling mixture)

// Does the sphere (centre x, radius r) touch the box [lo, hi]?
bool sphereTouchesBox(const Vec3& x, double r, const double* lo, const double* hi) {
  double d2 = 0;
  for (int a = 0; a < 3; ++a) {
    const double c = x[a] < lo[a] ? lo[a] - x[a] : (x[a] > hi[a] ? x[a] - hi[a] : 0.0);
    d2 += c * c;
  }
  return d2 <= r * r;
}

}  // namespace

// One exchange. Serial and parallel share the same three rounds; in serial every buffer goes to
// the rank itself (moved, no MPI):
//   R1  each particle goes from its DEM owner to every rank whose (sub)mesh box its sphere
//       touches (always including the owner); every rank locates the particles it received in
//       its own cells, adds the volume found there to eps_f, and -- if it holds the centre --
//       samples the fluid and evaluates the force models;
//   R2  every rank reports to the owner, per particle: the volume it found and (if it holds the
//       centre) the force; the owner adds the parts (outside volume = V_p - total inside), takes
//       the force from the lowest rank holding the centre, and writes it into LIGGGHTS;
//   R3  the owner sends the force to the ranks holding parts of the particle, which deposit the
//       reaction in their cells (weights V_ic / total inside volume, or all in the centre cell).
void FoamCoupling::exchange() {
  const double wall0 = MPI_Wtime();
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  const size_t nModels = forceModels_.size();

  std::vector<ParticleState> own;
  std::vector<std::int64_t> tags;
  link_->pull(own, tags);
  const size_t nOwn = own.size();
  const bool implicitDrag = link_->mode() == DemLink::DragIntegration::implicit;
  const bool fluidShare = implicitDrag && props_->dragFluidResponse == "share";
  const bool continuity = implicitDrag && props_->dragFluidResponse == "continuity";
  const bool mixturePressure = props_->pressureCoupling == "mixture";
  if (fluidShare) updateFluidOwnAcceleration();
  samples_.clear();
  std::vector<AppliedDrag> applied;  // implicit: what the last interval's drag used and gave
  if (implicitDrag) link_->pullApplied(applied);

  // R1: particles to the ranks whose mesh they touch.
  std::vector<std::vector<double>> buf(size);
  for (size_t i = 0; i < nOwn; ++i) {
    const ParticleState& p = own[i];
    for (int q = 0; q < size; ++q) {
      if (q != rank && !sphereTouchesBox(p.x, p.radius, &boxes_[6 * q], &boxes_[6 * q + 3]))
        continue;
      buf[q].insert(buf[q].end(), {static_cast<double>(i), static_cast<double>(tags[i]), p.x.x,
                                   p.x.y, p.x.z, p.v.x, p.v.y, p.v.z, p.radius, p.mass});
    }
  }
  std::vector<std::vector<double>> in = exchangeBuffers(buf, MPI_COMM_WORLD);

  struct Work {
    int owner = 0;
    long ownerIndex = 0;
    ParticleState p;
    ParticleCells cells;
    ParticleForce force;
    Vec3 Ui;
    double invFluidMass = 0;  // 1 / m_f of the particle's fluid share (dragFluidResponse share)
    Vec3 fluidAcceleration;   // the share's acceleration by the fluid's own forces
    double counterflow = 0;   // c = (1 - eps) / eps (dragFluidResponse continuity)
    std::vector<Vec3> modelForces;
  };
  std::vector<Work> work;
  std::vector<std::int64_t> workTags;
  for (int q = 0; q < size; ++q)
    for (size_t k = 0; k + kR1 <= in[q].size(); k += kR1) {
      const double* r = &in[q][k];
      Work w;
      w.owner = q;
      w.ownerIndex = static_cast<long>(r[0]);
      w.p.x = Vec3(r[2], r[3], r[4]);
      w.p.v = Vec3(r[5], r[6], r[7]);
      w.p.radius = r[8];
      w.p.mass = r[9];
      // Seed: the cell this rank found the particle's centre in at the last exchange.
      const auto tag = static_cast<std::int64_t>(r[1]);
      const auto it = lastCell_.find(tag);
      voidFractionModel_->locate(w.p, it == lastCell_.end() ? -1 : it->second, *locator_, w.cells);
      work.push_back(std::move(w));
      workTags.push_back(tag);
    }

  // Volumes -> eps_f.
  assembly_->reset();
  std::unordered_map<std::int64_t, long> newCell;
  newCell.reserve(work.size());
  for (size_t k = 0; k < work.size(); ++k) {
    assembly_->addSolid(work[k].cells);
    if (work[k].cells.centreCell >= 0) newCell[workTags[k]] = work[k].cells.centreCell;
  }
  lastCell_.swap(newCell);
  assembly_->finishVoidfraction();
  {
    Foam::scalarField& vf = voidfraction_.primitiveFieldRef();
    const std::vector<double>& eps = assembly_->voidfraction();
    forAll(vf, c) { vf[c] = eps[c]; }
  }

  // The fluid at the particles whose centre is here, and their forces.
  const Foam::word scheme(props_->interpolation);
  std::vector<Vec3> Ucell(mesh_.nCells());
  forAll(U_, c) { Ucell[c] = toVec(U_[c]); }
  Foam::autoPtr<Foam::interpolation<Foam::vector>> Uint =
      Foam::interpolation<Foam::vector>::New(scheme, U_);
  Foam::autoPtr<Foam::interpolation<Foam::scalar>> rhoInt =
      Foam::interpolation<Foam::scalar>::New(scheme, rho_);
  Foam::tmp<Foam::volScalarField> tmu;
  Foam::autoPtr<Foam::interpolation<Foam::scalar>> muInt;
  if (needs_ & kNeedsMu) {
    // Apparent dynamic viscosity of the liquid/air mixture: rho nu, nu from the phases' viscosity
    // models at the resolved shear rate (Herschel-Bulkley etc.).
    tmu = Foam::volScalarField::New("muApparent", rho_ * mixture_.nu());
    muInt = Foam::interpolation<Foam::scalar>::New(scheme, tmu());
  }
  Foam::tmp<Foam::volScalarField> trate;
  Foam::autoPtr<Foam::interpolation<Foam::scalar>> rateInt;
  if (needs_ & kNeedsShearRate) {
    // The resolved shear rate as the viscosity models evaluate it: sqrt(2) |symm(grad U)|.
    trate = Foam::volScalarField::New("shearRate",
                                      Foam::sqrt(2.0) * Foam::mag(Foam::symm(Foam::fvc::grad(U_))));
    rateInt = Foam::interpolation<Foam::scalar>::New(scheme, trate());
  }
  Foam::tmp<Foam::volVectorField> tdivTau;
  Foam::autoPtr<Foam::interpolation<Foam::vector>> divTauInt;
  if (needs_ & kNeedsDivTau) {
    // div(tau) exactly as mixflowFoam's viscous term (viscousStress full), evaluated explicitly:
    // div(rho nu_eff dev2(T(grad U))) + laplacian(rho nu_eff, U), with the solver's scheme names.
    const Foam::volScalarField rhoNuEff(rho_ * turbulence_.nuEff());
    tdivTau = Foam::volVectorField::New(
        "divTau", Foam::fvc::div(rhoNuEff * Foam::dev2(Foam::T(Foam::fvc::grad(U_)))) +
                      Foam::fvc::laplacian(rhoNuEff, U_));
    divTauInt = Foam::interpolation<Foam::vector>::New(scheme, tdivTau());
  }
  Foam::tmp<Foam::volVectorField> tgradP;
  Foam::autoPtr<Foam::interpolation<Foam::vector>> gradPInt;
  if (needs_ & kNeedsGradP) {
    tgradP = Foam::fvc::grad(p_);
    gradPInt = Foam::interpolation<Foam::vector>::New(scheme, tgradP());
  }
  const Foam::scalarField& vf = voidfraction_.primitiveField();
  double limited = 0, counterflowUnstable = 0, counterflowMax = 0;
  std::vector<ParticleForce> fms(nModels);  // per-model forces of the particle at hand
  for (Work& w : work) {
    const long c = w.cells.centreCell;
    if (c < 0) continue;
    const Foam::point x(w.p.x.x, w.p.x.y, w.p.x.z);
    FluidAtParticle f;
    f.U = toVec(Uint->interpolate(x, c));
    f.rho = rhoInt->interpolate(x, c);
    f.voidfraction = vf[c];
    if (muInt.valid()) f.mu = muInt->interpolate(x, c);
    if (rateInt.valid()) f.shearRate = rateInt->interpolate(x, c);
    if (divTauInt.valid()) f.divTau = toVec(divTauInt->interpolate(x, c));
    if (gradPInt.valid()) f.gradP = toVec(gradPInt->interpolate(x, c));
    w.Ui = f.U;
    if (mixturePressure) samples_.push_back(Sample{w.owner, w.ownerIndex, w.p.x, c});
    if (fluidShare) {
      // The particle's share of its cell's fluid: the cell's fluid mass rho eps V_c split over
      // the particle volume (1 - eps) V_c in it. A cell without particle volume: no response.
      const double solid = 1.0 - f.voidfraction;
      if (solid > 0 && f.rho > 0) w.invFluidMass = solid / (f.rho * f.voidfraction * w.p.volume());
      w.fluidAcceleration = fluidOwnAcceleration_[c];
    }
    // c = (1 - eps) / eps: how fast the pore fluid counterflows a compacting grain (continuity
    // in a cell of held mixture flux); the continuity response and the stability bound below.
    const double counterflow = f.voidfraction > 0 ? (1.0 - f.voidfraction) / f.voidfraction : 0.0;
    if (continuity) w.counterflow = counterflow;
    w.modelForces.resize(nModels);
    for (size_t m = 0; m < nModels; ++m) {
      fms[m] = forceModels_[m]->force(w.p, f);
      w.force.beta += fms[m].beta;
      w.force.explicitForce += fms[m].explicitForce;
    }
    double scale = 1.0;
    if (implicitDrag) {
      // The drag law's beta goes to the particle (DemLink integrates it at every DEM step); the
      // model columns of the log show the fluid-side coefficient (see fluidSideScale).
      scale = fluidSideScale(w.force.beta, w.p.mass);
      // In a packed bed the fluid step makes the pore fluid counterflow the grains (continuity:
      // eps U = -(1 - eps) v in a column closed below), and the next interval's drag pulls the
      // grain towards that lagged counterflow. With s = beta T / m and c = (1 - eps) / eps one
      // exchange multiplies a compaction velocity by (1 - c s) / (1 + s): it grows, alternating
      // in sign, once s (c - 1) > 2 (coupling/README.md, "Exchange interval").
      // dragFluidResponse continuity has the drag see that counterflow, which removes it;
      // pressureCoupling mixture has the fluid step carry the grains' response (no such lag).
      if (f.voidfraction > 0 && !continuity && !mixturePressure) {
        const double bound = w.force.beta * exchangeInterval_ / w.p.mass * (counterflow - 1) / 2;
        counterflowMax = std::max(counterflowMax, bound);
        if (bound > 1) counterflowUnstable += 1.0;
      }
    } else {
      // The drag is held over the exchange interval T: a coefficient beta > m / T would push the
      // particle past the fluid velocity within one interval (unstable beyond 2 m / T), e.g. in a
      // capped yield-stress liquid near rest (mu up to viscosityCap). Limited to
      // dragRelaxationLimit x m / T, on both sides (action = reaction), counted in the log.
      // Also c beta T / m <= dragCounterflowLimit: in a packed cell the next interval's drag
      // pulls the grain towards the pore fluid's counterflow to this interval's compaction,
      // c times the compaction velocity, two intervals late; in the slaved model
      // v_k+1 = (1 - s) v_k - c s v_k-1 (s = beta T / m) that grows once c s > 1.
      constexpr double kOff = std::numeric_limits<double>::infinity();
      double sMax = props_->dragRelaxationLimit > 0 ? props_->dragRelaxationLimit : kOff;
      if (props_->dragCounterflowLimit > 0 && counterflow > 0)
        sMax = std::min(sMax, props_->dragCounterflowLimit / counterflow);
      const double betaMax = sMax * w.p.mass / exchangeInterval_;
      if (w.force.beta > betaMax) {  // never with both limits off (betaMax infinite)
        scale = betaMax / w.force.beta;
        w.force.beta = betaMax;
        limited += 1.0;
      }
    }
    for (size_t m = 0; m < nModels; ++m) {
      fms[m].beta *= scale;
      w.modelForces[m] = fms[m].total(f.U, w.p.v);
    }
  }

  // R2: parts and forces back to the owners.
  buf.assign(size, {});
  for (size_t k = 0; k < work.size(); ++k) {
    const Work& w = work[k];
    const double inside = w.cells.insideVolume();
    const bool centre = w.cells.centreCell >= 0;
    if (inside <= 0 && !centre) continue;
    std::vector<double>& b = buf[w.owner];
    b.insert(b.end(),
             {static_cast<double>(w.ownerIndex), static_cast<double>(k), inside, centre ? 1.0 : 0.0,
              w.force.beta, w.force.explicitForce.x, w.force.explicitForce.y,
              w.force.explicitForce.z, w.Ui.x, w.Ui.y, w.Ui.z, w.invFluidMass,
              w.fluidAcceleration.x, w.fluidAcceleration.y, w.fluidAcceleration.z, w.counterflow});
    for (size_t m = 0; m < nModels; ++m) {
      const Vec3 F = centre ? w.modelForces[m] : Vec3();
      b.insert(b.end(), {F.x, F.y, F.z});
    }
  }
  in = exchangeBuffers(buf, MPI_COMM_WORLD);

  struct Part {
    int rank;
    long workIndex;
    double inside;
    bool centre;
  };
  struct Owned {
    std::vector<Part> parts;
    double inside = 0;
    int host = -1;  // lowest rank holding the centre
    ParticleForce force;
    Vec3 Ui;
    double invFluidMass = 0;
    Vec3 fluidAcceleration;
    double counterflow = 0;
    // What the fluid receives for this CFD step: the force at this exchange (held), or the mean
    // force the particle actually received over the DEM interval just run (implicit), written as
    // beta (U - v) + F_explicit with the velocity v that reproduces the drag impulse.
    ParticleForce reaction;
    Vec3 reactionU, reactionV;
    Vec3 explicitDrag;  // the part of reaction.explicitForce that is drag
  };
  std::vector<Owned> owned(nOwn);
  modelTotals_.assign(3 * nModels, 0.0);
  const size_t r2 = kR2Head + 3 * nModels;
  for (int q = 0; q < size; ++q)  // rank order: the first centre holder is the lowest rank
    for (size_t k = 0; k + r2 <= in[q].size(); k += r2) {
      const double* r = &in[q][k];
      Owned& o = owned.at(static_cast<size_t>(r[0]));
      const bool centre = r[3] > 0.5;
      o.parts.push_back({q, static_cast<long>(r[1]), r[2], centre});
      o.inside += r[2];
      if (centre && o.host < 0) {
        o.host = q;
        o.force.beta = r[4];
        o.force.explicitForce = Vec3(r[5], r[6], r[7]);
        o.Ui = Vec3(r[8], r[9], r[10]);
        o.invFluidMass = r[11];
        o.fluidAcceleration = Vec3(r[12], r[13], r[14]);
        o.counterflow = r[15];
        for (size_t m = 0; m < 3 * nModels; ++m) modelTotals_[m] += r[kR2Head + m];
      }
    }
  std::vector<Vec3> forces(implicitDrag ? 0 : nOwn);
  std::vector<AppliedDrag> next(implicitDrag ? nOwn : 0);
  sampleHost_.assign(nOwn, -1);
  double remote = 0;
  for (size_t i = 0; i < nOwn; ++i) {
    Owned& o = owned[i];
    assembly_->countParticle(own[i], std::max(0.0, own[i].volume() - o.inside), o.host >= 0);
    if (o.host < 0) continue;  // centre in no cell of the mesh: no fluid force
    if (o.host != rank) remote += 1;
    sampleHost_[i] = o.host;
    o.reaction = o.force;
    o.reactionU = o.Ui;
    o.reactionV = own[i].v;
    if (implicitDrag) {
      next[i] = AppliedDrag{o.force.beta, o.Ui,           o.force.explicitForce,
                            Vec3(),       o.invFluidMass, o.fluidAcceleration,
                            o.counterflow};
      o.reaction.beta = o.force.beta * fluidSideScale(o.force.beta, own[i].mass);
      if (exchanges_ > 0 && fluidShare) {
        // The particle's drag already saw its fluid share respond (DemLink): the fluid step gets
        // exactly the mean drag of the interval, explicitly; an implicit term would count the
        // share's response twice.
        const AppliedDrag& a = applied[i];
        o.explicitDrag = (1.0 / exchangeInterval_) * a.impulse;
        o.reaction = ParticleForce{0.0, a.explicitForce + o.explicitDrag};
        o.reactionU = a.U;
      } else if (exchanges_ > 0) {  // the first exchange has no interval behind it
        // The mean drag the particle received, F_d = impulse / T, written as
        // beta_T (U - v_s): at the fluid velocity U the particle saw, the fluid gets exactly -F_d.
        const AppliedDrag& a = applied[i];
        o.reaction.beta = a.beta * fluidSideScale(a.beta, own[i].mass);
        o.reaction.explicitForce = a.explicitForce;
        o.reactionU = a.U;
        if (o.reaction.beta > 0)
          o.reactionV = a.U - (1.0 / (o.reaction.beta * exchangeInterval_)) * a.impulse;
      }
    } else {
      forces[i] = o.force.total(o.Ui, own[i].v);
    }
    ParticleState p = own[i];
    p.v = o.reactionV;
    assembly_->addParticleForce(p, o.reaction, o.reactionU, o.explicitDrag);
  }
  if (implicitDrag)
    link_->pushImplicit(next);
  else
    link_->push(forces);

  // R3: the reaction to the ranks holding the particle's parts.
  buf.assign(size, {});
  for (size_t i = 0; i < nOwn; ++i) {
    const Owned& o = owned[i];
    if (o.host < 0) continue;
    const double sigma =
        mixturePressure ? responseShare(o.force.beta, own[i].mass, exchangeInterval_) : 0.0;
    bool hostDone = false;
    for (const Part& part : o.parts) {
      const bool isHost = part.centre && part.rank == o.host && !hostDone;
      hostDone = hostDone || isHost;
      if (!isHost && part.inside <= 0) continue;
      const ParticleForce& f = o.reaction;
      const Vec3& U = o.reactionU;
      const Vec3& v = o.reactionV;
      buf[part.rank].insert(
          buf[part.rank].end(),
          {static_cast<double>(part.workIndex), f.beta, f.explicitForce.x, f.explicitForce.y,
           f.explicitForce.z, U.x, U.y, U.z, v.x, v.y, v.z, o.inside, isHost ? 1.0 : 0.0,
           o.explicitDrag.x, o.explicitDrag.y, o.explicitDrag.z, sigma});
    }
  }
  in = exchangeBuffers(buf, MPI_COMM_WORLD);
  for (int q = 0; q < size; ++q)
    for (size_t k = 0; k + kR3 <= in[q].size(); k += kR3) {
      const double* r = &in[q][k];
      Work& w = work.at(static_cast<size_t>(r[0]));
      ParticleForce f;
      f.beta = r[1];
      f.explicitForce = Vec3(r[2], r[3], r[4]);
      ParticleState p = w.p;
      p.v = Vec3(r[8], r[9], r[10]);
      assembly_->depositReaction(p, w.cells, f, Vec3(r[5], r[6], r[7]), r[11], r[12] > 0.5, Ucell,
                                 Vec3(r[13], r[14], r[15]));
      if (r[16] > 0) assembly_->depositResponse(w.cells, r[16]);
    }
  assembly_->finishSources(Ucell);

  // The fluid's fields.
  {
    Foam::scalarField& K = Ksl_.primitiveFieldRef();
    Foam::vectorField& Usf = Us_.primitiveFieldRef();
    Foam::vectorField& fs = fSource_.primitiveFieldRef();
    const auto& aK = assembly_->Ksl();
    const auto& aUs = assembly_->Us();
    const auto& aF = assembly_->fSource();
    Foam::scalarField& psi = solidResponse_.primitiveFieldRef();
    const auto& aPsi = assembly_->solidResponse();
    forAll(K, c) {
      K[c] = aK[c];
      Usf[c] = toFoam(aUs[c]);
      fs[c] = toFoam(aF[c]);
      psi[c] = aPsi[c];
    }
  }

  // Totals over ranks, log.
  const ExchangeTotals& t = assembly_->totals();
  totals_.assign(kNumTotals, 0.0);
  totals_[kParticles] = t.particles;
  totals_[kParticlesOutside] = t.particlesOutside;
  totals_[kParticleVolume] = t.particleVolume;
  totals_[kOutsideVolume] = t.outsideVolume;
  totals_[kClippedVolume] = t.clippedVolume;
  totals_[kFluidSeenVolume] = t.fluidSeenVolume;
  for (int k = 0; k < 3; ++k) {
    totals_[kFpX + k] = t.forceOnParticles[k];
    totals_[kFfX + k] = t.forceOnFluid[k];
    totals_[kDragX + k] = t.dragOnParticles[k];
  }
  totals_[kForceScale] = t.forceScale;
  totals_[kRemote] = remote;
  totals_[kDragLimited] = limited;
  totals_[kCounterflowUnstable] = counterflowUnstable;
  for (const auto& p : own)
    for (int k = 0; k < 3; ++k) {
      totals_[kVx + k] += p.v[k];
      totals_[kX + k] += p.x[k];
    }
  MPI_Allreduce(MPI_IN_PLACE, totals_.data(), kNumSums, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  double minVf = t.minVoidfraction;
  MPI_Allreduce(MPI_IN_PLACE, &minVf, 1, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
  totals_[kMinVoidfraction] = minVf;
  MPI_Allreduce(&counterflowMax, &totals_[kCounterflowMax], 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  if (!modelTotals_.empty())
    MPI_Allreduce(MPI_IN_PLACE, modelTotals_.data(), static_cast<int>(modelTotals_.size()),
                  MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  log(MPI_Wtime() - wall0);
  ++exchanges_;
}

// pressureCoupling mixture: the fluid step just taken counted on each particle's drag pulling it
// towards the new fluid velocity over the next interval; give the drag that velocity. One
// point-to-point round: the rank holding a particle's centre samples U there (same place and
// scheme as the exchange) and sends it to the particle's DEM owner, which keeps the sample of
// the rank the exchange took the force from. No DEM step runs between the exchange and this,
// so the owners' local particle order is the exchange's.
void FoamCoupling::resampleFluidVelocity() {
  if (props_->pressureCoupling != "mixture") return;
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  Foam::autoPtr<Foam::interpolation<Foam::vector>> Uint =
      Foam::interpolation<Foam::vector>::New(Foam::word(props_->interpolation), U_);
  std::vector<std::vector<double>> buf(size);
  for (const Sample& s : samples_) {
    const Foam::vector u = Uint->interpolate(Foam::point(s.x.x, s.x.y, s.x.z), s.cell);
    buf[s.owner].insert(buf[s.owner].end(),
                        {static_cast<double>(s.ownerIndex), u.x(), u.y(), u.z()});
  }
  const std::vector<std::vector<double>> in = exchangeBuffers(buf, MPI_COMM_WORLD);
  std::vector<Vec3> Unew(sampleHost_.size());
  std::vector<char> has(sampleHost_.size(), 0);
  for (int q = 0; q < size; ++q)
    for (size_t k = 0; k + 4 <= in[q].size(); k += 4) {
      const size_t i = static_cast<size_t>(in[q][k]);
      if (i >= sampleHost_.size() || sampleHost_[i] != q) continue;
      Unew[i] = Vec3(in[q][k + 1], in[q][k + 2], in[q][k + 3]);
      has[i] = 1;
    }
  link_->setFluidVelocity(Unew, has);
}

void FoamCoupling::writeLogHeader() {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank != 0) return;
  const std::string dir = std::string(mesh_.time().globalPath()) + "/postProcessing/coupling";
  std::filesystem::create_directories(dir);
  if (resume_) {  // resumeMixtureCase cut the rows from the resumed time on: append
    csv_.open(dir + "/exchange.csv", std::ios::app);
    return;
  }
  csv_.open(dir + "/exchange.csv");
  csv_ << "# mixflowCoupled exchange log: one line per exchange (every logEvery). Volumes in m3,"
          " forces in N.\n"
          "# volumeError = (fluidSeenVolume - (particleVolume - outsideVolume - clippedVolume))"
          " / particleVolume; actionReaction = |Fp + Ff| / forceScale, Fp = sum of fluid forces"
          " on particles, Ff = sum_c V_c [Ksl (Us - U) + fSource] at the exchange,"
          " forceScale = sum |F_i|.\n";
  csv_ << "time,demStep,particles,particlesOutside,particleVolume,outsideVolume,clippedVolume,"
          "fluidSeenVolume,volumeError,Fp_x,Fp_y,Fp_z,Ff_x,Ff_y,Ff_z,forceScale,actionReaction,"
          "minVoidfraction,meanVx,meanVy,meanVz,meanX,meanY,meanZ,remote,dragLimited,"
          "counterflowUnstable,counterflowMax";
  for (const auto& m : forceModels_)
    csv_ << "," << m->name() << "_x," << m->name() << "_y," << m->name() << "_z";
  csv_ << ",seconds\n";
}

void FoamCoupling::log(double seconds) {
  const std::vector<double>& T = totals_;
  const double vp = T[kParticleVolume];
  const double volumeError =
      vp > 0 ? (T[kFluidSeenVolume] - (vp - T[kOutsideVolume] - T[kClippedVolume])) / vp : 0.0;
  const Vec3 Fp(T[kFpX], T[kFpY], T[kFpZ]), Ff(T[kFfX], T[kFfY], T[kFfZ]);
  const double actionReaction = T[kForceScale] > 0 ? mag(Fp + Ff) / T[kForceScale] : 0.0;
  const double np = std::max(T[kParticles], 1.0);

  Foam::Info << "Coupling: " << static_cast<long>(T[kParticles]) << " particles ("
             << static_cast<long>(T[kParticlesOutside]) << " outside), volume error " << volumeError
             << ", outside " << T[kOutsideVolume] << " m3, clipped " << T[kClippedVolume]
             << " m3, action-reaction " << actionReaction << ", min voidfraction "
             << T[kMinVoidfraction] << ", fluid cell on another rank "
             << static_cast<long>(T[kRemote]) << ", drag limited "
             << static_cast<long>(T[kDragLimited]) << ", counterflow unstable "
             << static_cast<long>(T[kCounterflowUnstable]) << ", " << seconds << " s" << Foam::endl;
  if (T[kCounterflowUnstable] > 0 && !warnedCounterflow_) {
    warnedCounterflow_ = true;
    const long n = props_->exchangeEvery;
    const long stable = static_cast<long>(n / T[kCounterflowMax]);
    // std::string goes out quoted on a Foam stream: the advice is handed over as const char*.
    const std::string advice =
        stable >= 1
            ? " -> at most " + std::to_string(stable) + " brings them within the bound"
            : ": even exchangeEvery 1 exceeds the bound; dragIntegration held, or a smaller "
              "DEM step";
    Foam::Warning << "mixflowCoupled: at t = " << mesh_.time().value() << " s, "
                  << static_cast<long>(T[kCounterflowUnstable])
                  << " particles exceed the packed-bed stability bound of the implicit drag "
                     "(beta T / m ((1 - eps) / eps - 1) / 2 up to "
                  << T[kCounterflowMax] << " > 1): the exchange can oscillate and grow. "
                  << "constant/couplingProperties exchangeEvery " << n << advice.c_str()
                  << " (the bound is necessary, not sufficient, in a deep bed; coupling/README.md, "
                     "\"Exchange interval\")"
                  << Foam::endl;
  }

  if (!csv_.is_open() || exchanges_ % props_->logEvery != 0) return;
  csv_ << std::setprecision(17) << mesh_.time().value() << "," << link_->step() << ","
       << static_cast<long>(T[kParticles]) << "," << static_cast<long>(T[kParticlesOutside]);
  for (Total k : {kParticleVolume, kOutsideVolume, kClippedVolume, kFluidSeenVolume})
    csv_ << "," << T[k];
  csv_ << "," << volumeError;
  for (Total k : {kFpX, kFpY, kFpZ, kFfX, kFfY, kFfZ, kForceScale}) csv_ << "," << T[k];
  csv_ << "," << actionReaction << "," << T[kMinVoidfraction];
  for (Total k : {kVx, kVy, kVz, kX, kY, kZ}) csv_ << "," << T[k] / np;
  csv_ << "," << static_cast<long>(T[kRemote]) << "," << static_cast<long>(T[kDragLimited]) << ","
       << static_cast<long>(T[kCounterflowUnstable]) << "," << T[kCounterflowMax];
  for (double v : modelTotals_) csv_ << "," << v;
  csv_ << "," << seconds << "\n" << std::flush;
}

}  // namespace mixflow::coupling
