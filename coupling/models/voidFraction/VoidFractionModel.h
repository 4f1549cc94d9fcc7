// Void-fraction models: where a particle's volume goes in the fluid mesh. Selected at run time by
// `voidFractionModel <name>;` in constant/couplingProperties, settings in `<name>Coeffs`.
//
//   centre   the whole volume to the cell holding the centre (cheap; eps_f jumps as a particle
//            crosses a face).
//   divided  the sphere is represented by a fixed set of weighted points (SpherePoints) whose
//            weights sum to V_p; each point's weight goes to the cell containing the point. The
//            total is conserved to round-off; the part of the sphere outside the mesh is reported.
//
// Models see the mesh only through CellLocator, so they are plain C++ and testable on a
// synthetic grid.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "Dictionary.h"
#include "ForceModel.h"
#include "SpherePoints.h"
#include "Vec3.h"

namespace mixflow::coupling {

class CellLocator {
 public:
  virtual ~CellLocator() = default;
  // Index of the (local) cell containing p, or -1 if p is in no cell of this mesh. `seed` is a
  // cell at or near p (e.g. the particle's cell at the last exchange) or -1.
  virtual long findCell(const Vec3& p, long seed) const = 0;
  // Optional fast path: true only if the whole sphere lies inside `cell`.
  virtual bool sphereInsideCell(const Vec3& /*centre*/, double /*r*/, long /*cell*/) const {
    return false;
  }
  // Optional fast path for the points of one sphere: the faces of the convex `cell` that the
  // sphere (centre, r) crosses, as half-spaces n . x <= d, in `out` (cleared first). A point of
  // the sphere inside all of them lies in `cell`, so only the others need findCell. False if
  // not provided.
  struct HalfSpace {
    Vec3 n;
    double d;
  };
  virtual bool crossedFaces(const Vec3& /*centre*/, double /*r*/, long /*cell*/,
                            std::vector<HalfSpace>& /*out*/) const {
    return false;
  }
  // Optional, for the divided model's face smoothing: the faces between `cell` (which holds p)
  // and another local cell whose plane lies within `band` of p, in `out` (cleared first).
  // Default: none, so no smoothing.
  struct NearFace {
    long across;      // the cell on the other side
    double distance;  // from p to the face plane (>= 0)
    Vec3 normal;      // outward unit normal of the face
  };
  virtual void facesNear(const Vec3& /*p*/, long /*cell*/, double /*band*/,
                         std::vector<NearFace>& out) const {
    out.clear();
  }
};

// Where one particle's volume went.
struct ParticleCells {
  long centreCell = -1;                          // cell holding the centre (-1: outside)
  std::vector<std::pair<long, double>> volumes;  // (cell, particle volume in it) [m3]
  double outsideVolume = 0;                      // part found in no cell of the mesh [m3]
  void clear() {
    centreCell = -1;
    volumes.clear();
    outsideVolume = 0;
  }
  double insideVolume() const {
    double s = 0;
    for (const auto& cv : volumes) s += cv.second;
    return s;
  }
};

class VoidFractionModel {
 public:
  virtual ~VoidFractionModel() = default;
  virtual const std::string& name() const = 0;
  virtual std::string describe() const = 0;
  // Fills `out` for particle p; `seed` as in CellLocator::findCell.
  virtual void locate(const ParticleState& p, long seed, const CellLocator& mesh,
                      ParticleCells& out) const = 0;

  static std::unique_ptr<VoidFractionModel> New(const std::string& name,
                                                const Dictionary& properties);
  static std::vector<std::string> available();
};

std::unique_ptr<VoidFractionModel> makeCentreVoidFraction(const Dictionary& coeffs);
std::unique_ptr<VoidFractionModel> makeDividedVoidFraction(const Dictionary& coeffs);

}  // namespace mixflow::coupling
