#include "ParticleRouting.h"

#include <stdexcept>

namespace mixflow::coupling {

namespace {

void put(std::vector<double>& b, const Vec3& v) { b.insert(b.end(), {v.x, v.y, v.z}); }
Vec3 vec(const double* r) { return Vec3(r[0], r[1], r[2]); }

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

void ParticleRecord::pack(std::vector<double>& b) const {
  b.insert(b.end(), {static_cast<double>(ownerIndex), static_cast<double>(tag)});
  put(b, p.x);
  put(b, p.v);
  b.insert(b.end(), {p.radius, p.mass});
}

ParticleRecord ParticleRecord::unpack(const double* r, size_t) {
  ParticleRecord m;
  m.ownerIndex = static_cast<long>(r[0]);
  m.tag = static_cast<std::int64_t>(r[1]);
  m.p.x = vec(r + 2);
  m.p.v = vec(r + 5);
  m.p.radius = r[8];
  m.p.mass = r[9];
  return m;
}

void PartRecord::pack(std::vector<double>& b) const {
  b.insert(b.end(), {static_cast<double>(ownerIndex), static_cast<double>(workIndex), inside,
                     centre ? 1.0 : 0.0, drag.force.beta});
  put(b, drag.force.explicitForce);
  put(b, drag.U);
  b.push_back(drag.invFluidMass);
  put(b, drag.fluidAcceleration);
  b.push_back(drag.counterflow);
  b.insert(b.end(),
           {drag.sample.rho, drag.sample.mu, drag.sample.shearRate, drag.sample.voidfraction});
  for (size_t m = 0; m < nModels; ++m) put(b, modelForces[m]);
}

PartRecord PartRecord::unpack(const double* r, size_t width) {
  PartRecord m;
  m.ownerIndex = static_cast<long>(r[0]);
  m.workIndex = static_cast<long>(r[1]);
  m.inside = r[2];
  m.centre = r[3] > 0.5;
  m.drag.force.beta = r[4];
  m.drag.force.explicitForce = vec(r + 5);
  m.drag.U = vec(r + 8);
  m.drag.invFluidMass = r[11];
  m.drag.fluidAcceleration = vec(r + 12);
  m.drag.counterflow = r[15];
  m.drag.sample = DragFluidSample{r[16], r[17], r[18], r[19]};
  for (size_t k = kHead; k + 3 <= width && m.nModels < kMaxForceModels; k += 3)
    m.modelForces[m.nModels++] = vec(r + k);
  return m;
}

void ReactionRecord::pack(std::vector<double>& b) const {
  const FluidReaction& f = reaction;
  b.insert(b.end(), {static_cast<double>(workIndex), f.force.beta});
  put(b, f.force.explicitForce);
  put(b, f.U);
  put(b, f.v);
  b.insert(b.end(), {insideTotal, holdsCentre ? 1.0 : 0.0});
  put(b, f.explicitDrag);
  b.push_back(sigma);
}

ReactionRecord ReactionRecord::unpack(const double* r, size_t) {
  ReactionRecord m;
  m.workIndex = static_cast<long>(r[0]);
  m.reaction.force.beta = r[1];
  m.reaction.force.explicitForce = vec(r + 2);
  m.reaction.U = vec(r + 5);
  m.reaction.v = vec(r + 8);
  m.insideTotal = r[11];
  m.holdsCentre = r[12] > 0.5;
  m.reaction.explicitDrag = vec(r + 13);
  m.sigma = r[16];
  return m;
}

ParticleRouter::ParticleRouter(const double lo[3], const double hi[3], MPI_Comm comm)
    : comm_(comm) {
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
  const double mine[6] = {lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]};
  boxes_.resize(6 * size_);
  MPI_Allgather(mine, 6, MPI_DOUBLE, boxes_.data(), 6, MPI_DOUBLE, comm_);
}

void ParticleRouter::toMeshes(const std::vector<ParticleState>& own,
                              const std::vector<std::int64_t>& tags,
                              std::vector<MeshParticle>& here) const {
  std::vector<std::vector<ParticleRecord>> send(size_);
  send[rank_].reserve(own.size());  // every owned particle goes to its owner's mesh too
  for (size_t i = 0; i < own.size(); ++i)
    for (int q = 0; q < size_; ++q) {
      if (q != rank_ &&
          !sphereTouchesBox(own[i].x, own[i].radius, &boxes_[6 * q], &boxes_[6 * q + 3]))
        continue;
      send[q].push_back({static_cast<long>(i), tags[i], own[i]});
    }
  const auto in = route(std::move(send), ParticleRecord::kWidth);
  size_t total = 0;
  for (const auto& records : in) total += records.size();
  here.resize(total);
  size_t k = 0;
  for (int q = 0; q < size_; ++q)
    for (const ParticleRecord& r : in[q]) {
      MeshParticle& m = here[k++];
      m.reset();
      m.owner = q;
      m.ownerIndex = r.ownerIndex;
      m.tag = r.tag;
      m.p = r.p;
    }
}

void ParticleRouter::toOwners(const std::vector<MeshParticle>& here, size_t nOwn, size_t nModels,
                              std::vector<double>& modelTotals,
                              std::vector<OwnedParticle>& owned) const {
  // Reserved: a part record is large (ModelForces), and growing the lists copies them.
  std::vector<std::vector<PartRecord>> send(size_);
  {
    std::vector<size_t> count(size_, 0);
    for (const MeshParticle& m : here) ++count[m.owner];
    for (int q = 0; q < size_; ++q) send[q].reserve(count[q]);
  }
  for (size_t k = 0; k < here.size(); ++k) {
    const MeshParticle& m = here[k];
    PartRecord r;
    r.inside = m.cells.insideVolume();
    r.centre = m.cells.centreCell >= 0;
    if (r.inside <= 0 && !r.centre) continue;
    r.ownerIndex = m.ownerIndex;
    r.workIndex = static_cast<long>(k);
    r.drag = m.drag;
    r.nModels = nModels;
    if (r.centre) r.modelForces = m.modelForces;
    send[m.owner].push_back(r);
  }
  owned.resize(nOwn);
  for (OwnedParticle& o : owned) o.reset();
  const auto in = route(std::move(send), PartRecord::width(nModels));
  for (int q = 0; q < size_; ++q)  // rank order: the first centre holder is the lowest rank
    for (const PartRecord& r : in[q]) {
      OwnedParticle& o = owned.at(static_cast<size_t>(r.ownerIndex));
      o.parts.push_back({q, r.workIndex, r.inside, r.centre});
      o.inside += r.inside;
      if (r.centre && o.host < 0) {
        o.host = q;
        o.drag = r.drag;
        for (size_t m = 0; m < nModels; ++m)
          for (int a = 0; a < 3; ++a) modelTotals[3 * m + a] += r.modelForces[m][a];
      }
    }
}

std::vector<ReactionRecord> ParticleRouter::toParts(const std::vector<OwnedParticle>& owned) const {
  std::vector<std::vector<ReactionRecord>> send(size_);
  send[rank_].reserve(owned.size());
  for (const OwnedParticle& o : owned) {
    if (o.host < 0) continue;
    bool hostDone = false;
    for (const OwnedParticle::Part& part : o.parts) {
      const bool isHost = part.centre && part.rank == o.host && !hostDone;
      hostDone = hostDone || isHost;
      if (!isHost && part.inside <= 0) continue;
      send[part.rank].push_back({part.workIndex, o.reaction, o.inside, isHost, o.sigma});
    }
  }
  auto in = route(std::move(send), ReactionRecord::kWidth);
  std::vector<ReactionRecord> here;
  size_t total = 0;
  for (const auto& records : in) total += records.size();
  here.reserve(total);
  for (auto& records : in)
    for (ReactionRecord& r : records) here.push_back(std::move(r));
  return here;
}

}  // namespace mixflow::coupling
