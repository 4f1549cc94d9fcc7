// voidFractionModel divided: the particle is represented by SpherePoints (nShells x nDirections
// points of equal weight, weights summing to V_p); each point's weight goes to the cell containing
// the point, points in no cell are the particle's outside volume. Volume is conserved to
// round-off: sum over cells + outside = V_p.
//
// Cost: one cell search per point, walking from the centre's cell. A sphere that lies entirely
// inside its centre's cell (CellLocator::sphereInsideCell) skips the points: all of them would
// land in that cell anyway, since every point is inside the sphere.
#include <sstream>

#include "VoidFractionModel.h"

namespace mixflow::coupling {

namespace {

class DividedVoidFraction final : public VoidFractionModel {
 public:
  explicit DividedVoidFraction(const Dictionary& coeffs) {
    coeffs.allowOnly({"nShells", "nDirections"});
    nShells_ = static_cast<int>(coeffs.integerOr("nShells", 3, 1, 20));
    nDirections_ = static_cast<int>(coeffs.integerOr("nDirections", 16, 1, 1000));
    points_ = SpherePoints::make(nShells_, nDirections_);
  }
  const std::string& name() const override {
    static const std::string n = "divided";
    return n;
  }
  std::string describe() const override {
    std::ostringstream s;
    s << "divided: " << points_.offsets.size() << " weighted points (" << nShells_
      << " equal-volume shells x " << nDirections_
      << " golden-angle directions), each point's weight to the cell containing it";
    return s.str();
  }
  void locate(const ParticleState& p, long seed, const CellLocator& mesh,
              ParticleCells& out) const override {
    out.clear();
    const double vp = p.volume();
    out.centreCell = mesh.findCell(p.x, seed);
    if (out.centreCell >= 0 && mesh.sphereInsideCell(p.x, p.radius, out.centreCell)) {
      out.volumes.emplace_back(out.centreCell, vp);
      return;
    }
    const long pointSeed = out.centreCell >= 0 ? out.centreCell : seed;
    for (size_t j = 0; j < points_.offsets.size(); ++j) {
      const double w = points_.weights[j] * vp;
      const long c = mesh.findCell(p.x + p.radius * points_.offsets[j], pointSeed);
      if (c < 0) {
        out.outsideVolume += w;
        continue;
      }
      bool added = false;
      for (auto& cv : out.volumes)
        if (cv.first == c) {
          cv.second += w;
          added = true;
          break;
        }
      if (!added) out.volumes.emplace_back(c, w);
    }
  }
  const SpherePoints& points() const { return points_; }

 private:
  int nShells_ = 3, nDirections_ = 16;
  SpherePoints points_;
};

}  // namespace

std::unique_ptr<VoidFractionModel> makeDividedVoidFraction(const Dictionary& coeffs) {
  return std::make_unique<DividedVoidFraction>(coeffs);
}

}  // namespace mixflow::coupling
