// The three point-to-point rounds of an exchange, as typed records (plain C++ and MPI). In serial
// every buffer goes to the rank itself (moved, no MPI):
//   R1  a particle goes from its DEM owner to every rank whose (sub)mesh box its sphere touches
//       (always including the owner), which locates it in its cells and, if it holds the centre,
//       samples the fluid and evaluates the forces;
//   R2  every rank reports to the owner, per particle, the volume it found and (if it holds the
//       centre) the force; the owner takes the force from the lowest rank holding the centre;
//   R3  the owner sends the reaction to the ranks holding parts of the particle, which deposit it.
// On the wire each record is a fixed run of doubles (integers converted exactly).
#pragma once

#include <mpi.h>

#include <cstdint>
#include <utility>
#include <vector>

#include "ForceModel.h"
#include "SparseExchange.h"
#include "Vec3.h"
#include "VoidFractionModel.h"

namespace mixflow::coupling {

// What the rank holding a particle's centre gives its drag for the next interval.
struct CentreForce {
  ParticleForce force;      // sum of the force models (held: limited)
  Vec3 U;                   // fluid velocity at the particle
  double invFluidMass = 0;  // 1 / m_f of the particle's fluid share (dragFluidResponse share)
  Vec3 fluidAcceleration;   // the share's acceleration by the fluid's own forces
  double counterflow = 0;   // c = (1 - eps) / eps (dragFluidResponse continuity)
  DragFluidSample sample;   // dragCoefficientUpdate slip: the laws' fluid values
};

// What the fluid receives for one particle in this CFD step, written as beta (U - v) + F_explicit.
struct FluidReaction {
  ParticleForce force;
  Vec3 U, v;
  Vec3 explicitDrag;  // the part of force.explicitForce that is drag
};

// R1: a particle from its owner.
struct ParticleRecord {
  static constexpr size_t kWidth = 10;  // owner index, tag, x(3), v(3), radius, mass
  long ownerIndex = 0;
  std::int64_t tag = 0;
  ParticleState p;
  void pack(std::vector<double>& b) const;
  static ParticleRecord unpack(const double* r, size_t width);
};

// R2: a rank's part of a particle, to its owner.
struct PartRecord {
  // owner index, work index, inside, centre, CentreForce(12 + the fluid sample(4))
  static constexpr size_t kHead = 20;
  static size_t width(size_t nModels) { return kHead + 3 * nModels; }
  long ownerIndex = 0;
  long workIndex = 0;   // the particle's index at the reporting rank (R3 addresses it)
  double inside = 0;    // volume found in the reporting rank's cells [m3]
  bool centre = false;  // the reporting rank holds the centre
  CentreForce drag;
  size_t nModels = 0;       // force models in modelForces (on the wire: width - kHead over 3)
  ModelForces modelForces;  // per force model (zero without the centre)
  void pack(std::vector<double>& b) const;
  static PartRecord unpack(const double* r, size_t width);
};

// R3: the reaction, from the owner to a rank holding part of the particle.
struct ReactionRecord {
  static constexpr size_t kWidth = 17;  // work index, reaction(12), inside total, holds centre,
                                        // sigma (pressureCoupling mixture)
  long workIndex = 0;
  FluidReaction reaction;
  double insideTotal = 0;    // the particle's volume inside the whole mesh [m3]
  bool holdsCentre = false;  // this rank takes the centre's share
  double sigma = 0;          // share of the displacement that follows the fluid (0: none)
  void pack(std::vector<double>& b) const;
  static ReactionRecord unpack(const double* r, size_t width);
};

// pressureCoupling mixture: the fluid velocity sampled again at a particle's centre, to its owner.
struct VelocityRecord {
  static constexpr size_t kWidth = 4;  // owner index, U(3)
  long ownerIndex = 0;
  Vec3 U;
  void pack(std::vector<double>& b) const {
    b.insert(b.end(), {static_cast<double>(ownerIndex), U.x, U.y, U.z});
  }
  static VelocityRecord unpack(const double* r, size_t) {
    return {static_cast<long>(r[0]), Vec3(r[1], r[2], r[3])};
  }
};

// A particle at a rank whose mesh it touches (received in R1).
struct MeshParticle {
  int owner = 0;
  long ownerIndex = 0;
  std::int64_t tag = 0;
  ParticleState p;
  ParticleCells cells;
  FluidAtParticle fluid;  // at the centre (centre holder only)
  CentreForce drag;       // centre holder only
  ModelForces modelForces;
  // Every field back to its default, the cell list's heap storage kept (lists reused between
  // exchanges).
  void reset() {
    auto volumes = std::move(cells.volumes);
    volumes.clear();
    *this = MeshParticle();
    cells.volumes = std::move(volumes);
  }
};

// A particle this rank owns in LIGGGHTS, assembled from the R2 reports.
struct OwnedParticle {
  struct Part {
    int rank;
    long workIndex;
    double inside;
    bool centre;
  };
  std::vector<Part> parts;
  double inside = 0;
  int host = -1;  // lowest rank holding the centre; -1: centre in no cell, no fluid force
  CentreForce drag;
  FluidReaction reaction;
  double sigma = 0;
  // Every field back to its default, the part list's heap storage kept.
  void reset() {
    auto kept = std::move(parts);
    kept.clear();
    *this = OwnedParticle();
    parts = std::move(kept);
  }
};

class ParticleRouter {
 public:
  // Every rank's (sub)mesh box [lo, hi] (inflated by the caller) is gathered.
  ParticleRouter(const double lo[3], const double hi[3], MPI_Comm comm);
  int rank() const { return rank_; }
  int size() const { return size_; }

  // The two output lists below are the caller's, kept between exchanges: their elements are
  // reset, not rebuilt, so their cell and part lists keep their heap storage.
  // R1: the owned particles to the ranks whose mesh they touch; `here` becomes those received
  // here, in rank order, with no cells, fluid or forces yet.
  void toMeshes(const std::vector<ParticleState>& own, const std::vector<std::int64_t>& tags,
                std::vector<MeshParticle>& here) const;
  // R2: the parts found here to their owners; `owned` becomes the owner's particles with their
  // parts, force from the lowest rank holding the centre. modelTotals (3 per model) adds that
  // force's per-model parts.
  void toOwners(const std::vector<MeshParticle>& here, size_t nOwn, size_t nModels,
                std::vector<double>& modelTotals, std::vector<OwnedParticle>& owned) const;
  // R3: each owned particle's reaction to the ranks holding its parts; returns the records
  // received here, in rank order.
  std::vector<ReactionRecord> toParts(const std::vector<OwnedParticle>& owned) const;

  // Records R (pack, unpack, `width` doubles each) to the ranks: send[q] to rank q; returns
  // what each rank sent here. This rank's own records are moved, not packed (pack and unpack
  // are lossless, so the result is the same).
  template <class R>
  std::vector<std::vector<R>> route(std::vector<std::vector<R>> send, size_t width) const {
    std::vector<std::vector<double>> buf(size_);
    for (int q = 0; q < size_; ++q) {
      if (q == rank_) continue;
      buf[q].reserve(send[q].size() * width);
      for (const R& r : send[q]) r.pack(buf[q]);
    }
    const std::vector<std::vector<double>> in = exchangeBuffers(buf, comm_);
    std::vector<std::vector<R>> out(size_);
    for (int q = 0; q < size_; ++q) {
      if (q == rank_) {
        out[q] = std::move(send[q]);
        continue;
      }
      out[q].reserve(in[q].size() / width);
      for (size_t k = 0; k + width <= in[q].size(); k += width)
        out[q].push_back(R::unpack(&in[q][k], width));
    }
    return out;
  }

 private:
  MPI_Comm comm_;
  int rank_ = 0, size_ = 1;
  std::vector<double> boxes_;  // lo(3), hi(3) per rank
};

}  // namespace mixflow::coupling
