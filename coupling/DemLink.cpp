#include "DemLink.h"

// LIGGGHTS headers (kept out of every OpenFOAM translation unit).
#include <atom.h>
#include <domain.h>
#include <fix.h>
#include <fix_external.h>
#include <fix_gravity.h>
#include <lammps.h>
#include <modify.h>
#include <update.h>

#include <cstring>
#include <stdexcept>

namespace mixflow::coupling {

namespace {
const char* kFixId = "mixflowFluidForce";
}

DemLink::DemLink(dem::LiggghtsSession& session) : session_(session) {
  // pf/array 1: the array is added to the atoms' forces at every step; no callback.
  session_.command(std::string("fix ") + kFixId + " all external pf/array 1");
  if (!session_.lammps()->atom->tag_enable)
    throw std::runtime_error("coupling: LIGGGHTS atoms need IDs (atom_modify id yes)");
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
  LAMMPS_NS::FixExternal* f = fix();
  const int n = session_.lammps()->atom->nlocal;
  if (static_cast<int>(forces.size()) != n)
    throw std::runtime_error("coupling: force count differs from the local particle count");
  for (int i = 0; i < n; ++i) {
    f->fexternal[i][0] = forces[i].x;
    f->fexternal[i][1] = forces[i].y;
    f->fexternal[i][2] = forces[i].z;
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
