#include "DemLink.h"

// LIGGGHTS headers (kept out of every OpenFOAM translation unit).
#include <atom.h>
#include <domain.h>
#include <fix.h>
#include <fix_external.h>
#include <fix_gravity.h>
#include <lammps.h>
#include <lmptype.h>
#include <modify.h>
#include <mpi.h>
#include <update.h>

#include <cstring>
#include <stdexcept>

namespace mixflow::coupling {

namespace {
const char* kFixId = "mixflowFluidForce";
const char* kStateId = "mixflowDragState";
// Per-atom held force(3) and 1 once a push set it: the held drag's state in restarts.
const char* kHeldId = "mixflowHeldForce";
constexpr int kHeldPushed = 3;
// Per-atom implicit-drag state: beta, U(3), F_explicit(3), impulse(3), last drag(3), 1 / m_f,
// the fluid share's own acceleration(3), counterflow factor c, the sum of the particle's
// half-step velocities over this interval(3), its mean velocity over the last interval(3) and
// over the one before(3) (v_ref: what the fluid step behind U saw), and 1 once a pushImplicit set
// it (0 in a restart without the state), then the fluid sample of the drag laws (rho, mu, shear
// rate, eps_f; eps_f 0: beta held).
enum State {
  kBeta = 0,
  kU = 1,
  kFexp = 4,
  kImpulse = 7,
  kLastDrag = 10,
  kInvFluidMass = 13,
  kAccel = 14,
  kCounterflow = 17,
  kVelocitySum = 18,
  kMeanVelocityLast = 21,
  kMeanVelocityRef = 24,
  kPushed = 27,
  kSample = 28,
  kStateSize = 32
};

void implicitDragCallback(void* link, LAMMPS_NS::bigint step, int nlocal, LAMMPS_NS::tagint*,
                          double**, double** fexternal) {
  static_cast<DemLink*>(link)->implicitDrag(static_cast<std::int64_t>(step), nlocal, fexternal);
}
}  // namespace

DemLink::DemLink(dem::LiggghtsSession& session, DragIntegration mode)
    : session_(session), mode_(mode) {
  if (!session_.lammps()->atom->tag_enable)
    throw std::runtime_error("coupling: LIGGGHTS atoms need IDs (atom_modify id yes)");
  if (mode_ == DragIntegration::held) {
    // The held forces also in a per-atom array that restarts keep (fix external's array is not).
    session_.command(std::string("fix ") + kHeldId + " all property/atom " + kHeldId +
                     " vector yes no no 0 0 0 0");
    // pf/array 1: the array is added to the atoms' forces at every step; no callback.
    session_.command(std::string("fix ") + kFixId + " all external pf/array 1");
    return;
  }
  // The state migrates with the atoms (exchange), is written to restarts (read back when this fix
  // is defined after read_restart), and is not needed on ghosts.
  std::string cmd =
      std::string("fix ") + kStateId + " all property/atom " + kStateId + " vector yes no no";
  for (int k = 0; k < kStateSize; ++k) cmd += " 0";
  session_.command(cmd);
  // pf/callback 1 1: the callback fills fexternal at every step, which is then added to f.
  session_.command(std::string("fix ") + kFixId + " all external pf/callback 1 1");
  fix()->set_callback(&implicitDragCallback, this);
}

double** DemLink::state() const {
  LAMMPS_NS::Modify* modify = session_.lammps()->modify;
  const char* id = mode_ == DragIntegration::held ? kHeldId : kStateId;
  const int i = modify->find_fix(id);
  if (i < 0) throw std::runtime_error(std::string("coupling: LIGGGHTS fix ") + id + " not found");
  return modify->fix[i]->array_atom;
}

// Backward Euler for the drag in the half-step velocity update of velocity Verlet: the velocity
// after this step's force is v' = v + dt (f_other + F_explicit + F_d) / m with F_d = beta (Uf -
// (1 + c) v'), Uf = U + a tau - J / m_f + c v_ref the parts of the seen fluid velocity that do
// not depend on v' (DemLink.h), hence F_d = beta_eff (Uf - (1 + c) (v + dt (f_other +
// F_explicit) / m)), beta_eff = beta / (1 + beta dt ((1 + c) / m + 1 / m_f)). LIGGGHTS applies
// each step's force over dt (half in final_integrate, half in the next initial_integrate); a
// setup (a run after atoms were deleted) recomputes the force of the same step, which then
// replaces the old one for the second half: the impulse is corrected by dt/2 (new - old).
// The velocity here is the half-step one (post_force follows initial_integrate), whose sum times
// dt is exactly the interval's displacement.
void DemLink::implicitDrag(std::int64_t step, int nlocal, double** fexternal) {
  LAMMPS_NS::LAMMPS* lmp = session_.lammps();
  const LAMMPS_NS::Atom* a = lmp->atom;
  double** s = state();
  const double dt = lmp->update->dt;
  const bool repeat = step == lastCallStep_;
  lastCallStep_ = step;
  const double tau = static_cast<double>(step - intervalStart_) * dt;  // end of this step
  if (holdState_) {
    // The start-up setups of a resumed run: the restart's state stays as written (the first
    // interval's setup computes this step's force, as the uninterrupted run's setup after its
    // write did).
    for (int i = 0; i < nlocal; ++i)
      for (int k = 0; k < 3; ++k) fexternal[i][k] = 0.0;
    return;
  }
  for (int i = 0; i < nlocal; ++i) {
    double* si = s[i];
    const double dtm = dt / a->rmass[i];
    const double invMf = si[kInvFluidMass];
    const double c = si[kCounterflow];
    // The fluid share's velocity before this step's drag (a repeated step's old drag undone).
    double Uf[3];
    for (int k = 0; k < 3; ++k) {
      const double impulse = si[kImpulse + k] - (repeat ? dt * si[kLastDrag + k] : 0.0);
      Uf[k] = si[kU + k] + tau * si[kAccel + k] - invMf * impulse + c * si[kMeanVelocityRef + k];
    }
    // dragCoefficientUpdate slip: the laws' beta at this step's slip, the velocity before the
    // step's update (beta lags by one DEM step; backward Euler keeps it stable, and its fixed
    // points are the law's).
    double beta = si[kBeta];
    if (law_ && si[kSample + 3] > 0) {
      const DragFluidSample sample{si[kSample], si[kSample + 1], si[kSample + 2], si[kSample + 3]};
      ParticleState p;
      p.radius = a->radius[i];
      p.mass = a->rmass[i];
      p.v = (1.0 + c) * Vec3(a->v[i][0], a->v[i][1], a->v[i][2]);
      beta = law_(p, sample.at(Vec3(Uf[0], Uf[1], Uf[2])));
    }
    const double betaEff = beta / (1.0 + beta * dt * ((1.0 + c) / a->rmass[i] + invMf));
    for (int k = 0; k < 3; ++k) {
      const double fexp = si[kFexp + k];
      const double drag = betaEff * (Uf[k] - (1.0 + c) * (a->v[i][k] + dtm * (a->f[i][k] + fexp)));
      si[kImpulse + k] += repeat ? 0.5 * dt * (drag - si[kLastDrag + k]) : dt * drag;
      si[kLastDrag + k] = drag;
      if (!repeat && tau > 0) si[kVelocitySum + k] += a->v[i][k];  // not a run's setup
      fexternal[i][k] = drag + fexp;
    }
  }
}

void DemLink::pullApplied(std::vector<AppliedDrag>& applied) const {
  if (mode_ != DragIntegration::implicit)
    throw std::logic_error("coupling: pullApplied needs dragIntegration implicit");
  double** s = state();
  const int n = session_.lammps()->atom->nlocal;
  applied.resize(n);
  for (int i = 0; i < n; ++i) {
    const double* si = s[i];
    applied[i].beta = si[kBeta];
    applied[i].U = Vec3(si[kU], si[kU + 1], si[kU + 2]);
    applied[i].explicitForce = Vec3(si[kFexp], si[kFexp + 1], si[kFexp + 2]);
    applied[i].impulse = Vec3(si[kImpulse], si[kImpulse + 1], si[kImpulse + 2]);
    applied[i].invFluidMass = si[kInvFluidMass];
    applied[i].fluidAcceleration = Vec3(si[kAccel], si[kAccel + 1], si[kAccel + 2]);
    applied[i].counterflow = si[kCounterflow];
  }
}

void DemLink::pushImplicit(const std::vector<AppliedDrag>& next) {
  if (mode_ != DragIntegration::implicit)
    throw std::logic_error("coupling: pushImplicit needs dragIntegration implicit");
  double** s = state();
  const int n = session_.lammps()->atom->nlocal;
  if (static_cast<int>(next.size()) != n)
    throw std::runtime_error("coupling: force count differs from the local particle count");
  const long steps = session_.step() - intervalStart_;  // of the interval just run (0: none)
  intervalStart_ = session_.step();
  for (int i = 0; i < n; ++i) {
    double* si = s[i];
    si[kBeta] = next[i].beta;
    si[kInvFluidMass] = next[i].invFluidMass;
    si[kCounterflow] = next[i].counterflow;
    for (int k = 0; k < 3; ++k) {
      // The mean velocities shift by one interval: the next interval's v_ref is the mean over
      // the interval before the one just run (see DemLink.h).
      si[kMeanVelocityRef + k] = si[kMeanVelocityLast + k];
      si[kMeanVelocityLast + k] = steps > 0 ? si[kVelocitySum + k] / steps : 0.0;
      si[kVelocitySum + k] = 0.0;
      si[kU + k] = next[i].U[k];
      si[kFexp + k] = next[i].explicitForce[k];
      si[kImpulse + k] = 0.0;
      si[kAccel + k] = next[i].fluidAcceleration[k];
    }
    si[kSample] = next[i].sample.rho;
    si[kSample + 1] = next[i].sample.mu;
    si[kSample + 2] = next[i].sample.shearRate;
    si[kSample + 3] = next[i].sample.voidfraction;
    si[kPushed] = 1.0;
  }
}

bool DemLink::adoptRestoredState() {
  const bool held = mode_ == DragIntegration::held;
  double** s = state();
  const int n = session_.lammps()->atom->nlocal;
  int missing = 0;
  for (int i = 0; i < n; ++i)
    if (s[i][held ? kHeldPushed : kPushed] != 1.0) ++missing;
  int anyMissing = 0;
  MPI_Allreduce(&missing, &anyMissing, 1, MPI_INT, MPI_MAX, session_.lammps()->world);
  adopted_ = anyMissing == 0;
  if (held && adopted_) {
    double** f = fix()->fexternal;
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < 3; ++k) f[i][k] = s[i][k];
  }
  holdState_ = adopted_ && !held;
  intervalStart_ = session_.step();
  return adopted_;
}

bool DemLink::keepRestoredState() {
  if (!adopted_) return false;
  adopted_ = false;
  if (mode_ == DragIntegration::held) return true;  // fix external holds the adopted forces
  holdState_ = false;
  // The interval starts here, and its setup repeats the step the restart was written at, as the
  // uninterrupted run's setup after the write did (its drag replaces the restart's last one for
  // the second half step).
  lastCallStep_ = session_.step();
  double** s = state();
  const int n = session_.lammps()->atom->nlocal;
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) {
      s[i][kImpulse + k] = 0.0;
      s[i][kVelocitySum + k] = 0.0;
    }
  intervalStart_ = session_.step();
  return true;
}

void DemLink::setFluidVelocity(const std::vector<Vec3>& U, const std::vector<char>& has,
                               double step) {
  if (mode_ != DragIntegration::implicit)
    throw std::logic_error("coupling: setFluidVelocity needs dragIntegration implicit");
  if (session_.step() != intervalStart_)
    throw std::logic_error("coupling: setFluidVelocity after the interval started");
  double** s = state();
  const int n = session_.lammps()->atom->nlocal;
  if (static_cast<int>(U.size()) != n || static_cast<int>(has.size()) != n)
    throw std::runtime_error("coupling: velocity count differs from the local particle count");
  for (int i = 0; i < n; ++i)
    if (has[i])
      for (int k = 0; k < 3; ++k) {
        if (step > 0) s[i][kAccel + k] = (U[i][k] - s[i][kU + k]) / step;
        s[i][kU + k] = U[i][k];
      }
}

bool DemLink::periodicZ(double& lo, double& hi) const {
  const LAMMPS_NS::Domain* d = session_.lammps()->domain;
  lo = d->boxlo[2];
  hi = d->boxhi[2];
  return d->zperiodic != 0;
}

LAMMPS_NS::FixExternal* DemLink::fix() const {
  LAMMPS_NS::Modify* modify = session_.lammps()->modify;
  const int i = modify->find_fix(kFixId);
  auto* f = i < 0 ? nullptr : dynamic_cast<LAMMPS_NS::FixExternal*>(modify->fix[i]);
  if (!f) throw std::runtime_error(std::string("coupling: LIGGGHTS fix ") + kFixId + " not found");
  return f;
}

void DemLink::pull(std::vector<ParticleState>& particles, std::vector<std::int64_t>& tags) {
  LAMMPS_NS::Atom* a = session_.lammps()->atom;
  const long global = static_cast<long>(a->natoms);
  if (lastGlobalCount_ >= 0 && global > lastGlobalCount_)
    throw std::runtime_error(
        "coupling: the particle count grew from " + std::to_string(lastGlobalCount_) + " to " +
        std::to_string(global) +
        " during a coupled DEM interval; inserting particles while coupled is not supported "
        "(their held fluid force would be undefined)");
  lastGlobalCount_ = global;
  const int n = a->nlocal;
  particles.resize(n);
  tags.resize(n);
  for (int i = 0; i < n; ++i) {
    particles[i].x = Vec3(a->x[i][0], a->x[i][1], a->x[i][2]);
    particles[i].v = Vec3(a->v[i][0], a->v[i][1], a->v[i][2]);
    particles[i].radius = a->radius[i];
    particles[i].mass = a->rmass[i];
    tags[i] = a->tag[i];
  }
}

void DemLink::push(const std::vector<Vec3>& forces) {
  if (mode_ != DragIntegration::held)
    throw std::logic_error("coupling: push needs dragIntegration held");
  LAMMPS_NS::FixExternal* f = fix();
  double** s = state();
  const int n = session_.lammps()->atom->nlocal;
  if (static_cast<int>(forces.size()) != n)
    throw std::runtime_error("coupling: force count differs from the local particle count");
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) f->fexternal[i][k] = s[i][k] = forces[i][k];
    s[i][kHeldPushed] = 1.0;
  }
}

double DemLink::timeStep() const { return session_.timeStep(); }

Vec3 DemLink::gravity() const {
  LAMMPS_NS::Modify* modify = session_.lammps()->modify;
  Vec3 g;
  for (int i = 0; i < modify->nfix; ++i) {
    if (std::strcmp(modify->fix[i]->style, "gravity") != 0) continue;
    auto* fg = dynamic_cast<LAMMPS_NS::FixGravity*>(modify->fix[i]);
    if (!fg) continue;
    double a[3];
    fg->get_gravity(a);
    g += Vec3(a[0], a[1], a[2]);
  }
  return g;
}

}  // namespace mixflow::coupling
