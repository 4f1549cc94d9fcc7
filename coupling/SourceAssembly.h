// Per-cell assembly of what the fluid receives from the particles (plain C++, local cells):
//   voidfraction  eps_f = 1 - V_solid / V_c, floored at voidfractionMin (the volume the floor
//                 removes is counted as clipped, never dropped silently);
//   Ksl, Us       implicit drag: Ksl = sum_i w_ic beta_i / V_c, Ksl Us = sum_i w_ic beta_i v_i /
//   V_c; fSource       explicit rest: sum_i w_ic [-F_expl,i + beta_i (U_ref - U_i)] / V_c,
// where w_ic is particle i's share in cell c (its volume share over the cells it covers inside
// the mesh, or 1 for the centre cell only) and U_i the fluid velocity the particle's drag used.
// The term beta_i (U_ref - U_i) makes the fluid's force exactly -sum F_i at the exchange whatever
// the interpolation: sum_c V_c [Ksl (Us - U_c) + fSource] = sum_i [beta_i (v_i - U_i) - F_expl,i].
// U_ref (couplingProperties dragReactionVelocity):
//   particleMean  the mean fluid velocity over the particle's part in this rank's cells, weighted
//                 like the deposit (sum_c w_ic U_c / sum_c w_ic). The explicit term is then the
//                 same in every cell of the particle, so the implicit -Ksl U_c damps each cell's
//                 own velocity, including cells that hold only slivers of particles centred
//                 elsewhere (a bed's edge and top row). Exact for any partition: each rank's parts
//                 give w_q beta (v - U_i).
//   cell          U_c: the explicit term cancels the implicit drag of a cell
//                 wherever its velocity differs from the velocity at the particles' centres, so
//                 sliver cells carry no drag on their own velocity. That let air flow at 10-20
//                 m/s through the edge cells of a saturated column (coupling/README.md, "Air
//                 jets").
#pragma once

#include <string>
#include <vector>

#include "ForceModel.h"
#include "Vec3.h"
#include "VoidFractionModel.h"

namespace mixflow::coupling {

// Rank-local sums of one exchange (the caller reduces them over ranks).
struct ExchangeTotals {
  double particles = 0;         // particles on this rank
  double particlesOutside = 0;  // ... whose centre is in no cell (no fluid force)
  double particleVolume = 0;    // sum V_p [m3]
  double outsideVolume = 0;     // volume found in no cell [m3]
  double clippedVolume = 0;     // volume removed by the eps_f floor [m3]
  double fluidSeenVolume = 0;   // sum_c (1 - eps_f) V_c [m3]
  Vec3 forceOnParticles;        // sum_i F_i [N]
  Vec3 forceOnFluid;            // sum_c V_c [Ksl (Us - U_c) + fSource] at the exchange [N]
  double forceScale = 0;        // sum_i |F_i| [N] (scale of the action-reaction check)
  Vec3 dragOnParticles;         // sum_i beta_i (U_i - v_i) [N]
  Vec3 explicitOnParticles;     // sum_i F_expl,i [N]
  double minVoidfraction = 1;   // over this rank's cells (reduce with min)
};

class SourceAssembly {
 public:
  enum class Distribution { centre, volume };
  enum class ReactionVelocity { particleMean, cell };

  SourceAssembly(std::vector<double> cellVolumes, double voidfractionMin, Distribution d,
                 ReactionVelocity r = ReactionVelocity::particleMean);

  // Pass 1: particle volumes -> eps_f. In serial addVolume() does both parts; in parallel the
  // rank owning the particle (in LIGGGHTS) counts it, every rank holding part of it adds its cells.
  void reset();
  void addVolume(const ParticleState& p, const ParticleCells& cells);  // count + solid
  void countParticle(const ParticleState& p, double outsideVolume, bool centreInMesh);
  void addSolid(const ParticleCells& cells);
  void finishVoidfraction();
  const std::vector<double>& voidfraction() const { return voidfraction_; }

  // Pass 2: forces -> Ksl, Us, fSource. `force` is the particle's total (all models), `Ui` the
  // fluid velocity its drag used, `Ucell` the fluid velocity of every local cell.
  // Serial form: the particle's whole volume is in `cells`.
  void addSource(const ParticleState& p, const ParticleCells& cells, const ParticleForce& force,
                 const Vec3& Ui, const std::vector<Vec3>& Ucell);
  // Parallel parts: the owner adds the force to the totals; every rank holding part of the
  // particle deposits the reaction in its cells, with weights V_ic / insideTotal (volume
  // distribution; insideTotal = the particle's volume inside the whole mesh) or, for the
  // centre distribution (or insideTotal = 0), all in the centre cell on the rank holding it.
  // explicitDrag: the part of force.explicitForce that is drag (for the totals' split).
  void addParticleForce(const ParticleState& p, const ParticleForce& force, const Vec3& Ui,
                        const Vec3& explicitDrag = Vec3());
  void depositReaction(const ParticleState& p, const ParticleCells& localCells,
                       const ParticleForce& force, const Vec3& Ui, double insideTotal,
                       bool holdsCentre, const std::vector<Vec3>& Ucell,
                       const Vec3& explicitDrag = Vec3());
  void finishSources(const std::vector<Vec3>& Ucell);
  // Pressure coupling `mixture`: the drag-slaved solid fraction psi_c = sum_i sigma_i V_ic / V_c
  // of the parts of particle i in this rank's cells (sigma_i in [0, 1]); capped at 1 - eps_f by
  // finishSources (a clipped cell carries no more solid than eps_f leaves).
  void depositResponse(const ParticleCells& localCells, double sigma);
  const std::vector<double>& solidResponse() const { return response_; }

  const std::vector<double>& Ksl() const { return ksl_; }
  const std::vector<Vec3>& Us() const { return us_; }
  const std::vector<Vec3>& fSource() const { return fSource_; }
  // The part of fSource that is the reaction to drag given explicitly (explicitDrag above).
  const std::vector<Vec3>& fDragSource() const { return fDrag_; }
  const ExchangeTotals& totals() const { return totals_; }
  Distribution distribution() const { return distribution_; }

 private:
  std::vector<double> volumes_;
  double voidfractionMin_;
  Distribution distribution_;
  ReactionVelocity reactionVelocity_;
  std::vector<double> solid_, voidfraction_, ksl_, response_;
  std::vector<Vec3> kslUs_, us_, fSource_, fDrag_;
  ExchangeTotals totals_;
};

}  // namespace mixflow::coupling
