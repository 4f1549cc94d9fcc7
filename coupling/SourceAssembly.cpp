#include "SourceAssembly.h"

#include <algorithm>
#include <stdexcept>

namespace mixflow::coupling {

SourceAssembly::SourceAssembly(std::vector<double> cellVolumes, double voidfractionMin,
                               Distribution d, ReactionVelocity r)
    : volumes_(std::move(cellVolumes)),
      voidfractionMin_(voidfractionMin),
      distribution_(d),
      reactionVelocity_(r) {
  if (!(voidfractionMin_ >= 0 && voidfractionMin_ < 1))
    throw std::invalid_argument("SourceAssembly: voidfractionMin must be in [0, 1)");
  reset();
}

void SourceAssembly::reset() {
  const size_t n = volumes_.size();
  solid_.assign(n, 0.0);
  voidfraction_.assign(n, 1.0);
  ksl_.assign(n, 0.0);
  response_.assign(n, 0.0);
  kslUs_.assign(n, Vec3());
  us_.assign(n, Vec3());
  fSource_.assign(n, Vec3());
  fDrag_.assign(n, Vec3());
  totals_ = ExchangeTotals();
}

void SourceAssembly::addVolume(const ParticleState& p, const ParticleCells& cells) {
  countParticle(p, cells.outsideVolume, cells.centreCell >= 0);
  addSolid(cells);
}

void SourceAssembly::countParticle(const ParticleState& p, double outsideVolume,
                                   bool centreInMesh) {
  totals_.particles += 1;
  totals_.particleVolume += p.volume();
  totals_.outsideVolume += outsideVolume;
  if (!centreInMesh) totals_.particlesOutside += 1;
}

void SourceAssembly::addSolid(const ParticleCells& cells) {
  for (const auto& cv : cells.volumes) solid_.at(cv.first) += cv.second;
}

void SourceAssembly::finishVoidfraction() {
  for (size_t c = 0; c < volumes_.size(); ++c) {
    const double vc = volumes_[c];
    double solid = solid_[c];
    const double maxSolid = (1.0 - voidfractionMin_) * vc;
    if (solid > maxSolid) {
      totals_.clippedVolume += solid - maxSolid;
      solid = maxSolid;
    }
    // max(): 1 - maxSolid / V_c may round to just below the floor, which the solver rejects.
    voidfraction_[c] = std::max(voidfractionMin_, 1.0 - solid / vc);
    totals_.fluidSeenVolume += (1.0 - voidfraction_[c]) * vc;
    totals_.minVoidfraction = std::min(totals_.minVoidfraction, voidfraction_[c]);
  }
}

void SourceAssembly::addSource(const ParticleState& p, const ParticleCells& cells,
                               const ParticleForce& force, const Vec3& Ui,
                               const std::vector<Vec3>& Ucell) {
  if (cells.centreCell < 0) return;  // no fluid force on a particle outside the mesh
  addParticleForce(p, force, Ui);
  depositReaction(p, cells, force, Ui, cells.insideVolume(), true, Ucell);
}

void SourceAssembly::addParticleForce(const ParticleState& p, const ParticleForce& force,
                                      const Vec3& Ui, const Vec3& explicitDrag) {
  const Vec3 F = force.total(Ui, p.v);
  totals_.forceOnParticles += F;
  totals_.forceScale += mag(F);
  totals_.dragOnParticles += force.beta * (Ui - p.v) + explicitDrag;
  totals_.explicitOnParticles += force.explicitForce - explicitDrag;
}

void SourceAssembly::depositReaction(const ParticleState& p, const ParticleCells& localCells,
                                     const ParticleForce& force, const Vec3& Ui, double insideTotal,
                                     bool holdsCentre, const std::vector<Vec3>& Ucell,
                                     const Vec3& explicitDrag) {
  const bool centreOnly = distribution_ == Distribution::centre || insideTotal <= 0;
  // particleMean: U_ref is the deposit-weighted mean of U_c over the cells deposited into here
  // (one cell for the centre distribution, where it equals U_c).
  Vec3 Umean;
  double wsum = 0;
  if (reactionVelocity_ == ReactionVelocity::particleMean && !centreOnly) {
    for (const auto& cv : localCells.volumes) {
      Umean += cv.second * Ucell[cv.first];
      wsum += cv.second;
    }
    if (wsum > 0) Umean = (1.0 / wsum) * Umean;
  }
  auto deposit = [&](long c, double w) {
    const double s = w / volumes_[c];
    const Vec3& Uref = wsum > 0 ? Umean : Ucell[c];
    ksl_[c] += s * force.beta;
    kslUs_[c] += (s * force.beta) * p.v;
    fSource_[c] += s * (force.beta * (Uref - Ui) - force.explicitForce);
    fDrag_[c] -= s * explicitDrag;
  };
  if (centreOnly) {
    if (holdsCentre && localCells.centreCell >= 0) deposit(localCells.centreCell, 1.0);
  } else {
    for (const auto& cv : localCells.volumes) deposit(cv.first, cv.second / insideTotal);
  }
}

void SourceAssembly::depositResponse(const ParticleCells& localCells, double sigma) {
  for (const auto& cv : localCells.volumes)
    response_.at(cv.first) += sigma * cv.second / volumes_[cv.first];
}

void SourceAssembly::finishSources(const std::vector<Vec3>& Ucell) {
  for (size_t c = 0; c < volumes_.size(); ++c) {
    response_[c] = std::min(response_[c], 1.0 - voidfraction_[c]);
    us_[c] = ksl_[c] > 0 ? (1.0 / ksl_[c]) * kslUs_[c] : Vec3();
    totals_.forceOnFluid += volumes_[c] * (ksl_[c] * (us_[c] - Ucell[c]) + fSource_[c]);
  }
}

}  // namespace mixflow::coupling
