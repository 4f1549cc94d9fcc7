// voidFractionModel divided: the particle is represented by SpherePoints (nShells x nDirections
// points of equal weight, weights summing to V_p); each point's weight goes to the cell containing
// the point, points in no cell are the particle's outside volume. Volume is conserved to
// round-off: sum over cells + outside = V_p.
//
// Cost: a sphere that lies entirely inside its centre's cell (CellLocator::sphereInsideCell)
// skips the points: all of them would land in that cell anyway, since every point is inside the
// sphere. Otherwise a point is tested against the centre cell's faces the sphere crosses
// (CellLocator::crossedFaces, one or two on a hex mesh); only a point beyond one of them is
// searched for (findCell, walking from the centre's cell).
//
// Face smoothing (dividedCoeffs smoothing s, a fraction of the particle radius; default 0 = off).
// Without it eps_f jumps by a whole point's weight (1/48 of the particle) when a point crosses a
// face, however slowly the particle moves: over an exchange interval T that is a rate d(eps)/dt of
// (V_p / 48 / V_c) / T, a kick to the pore liquid that grows as 1/T, so the mixtures' answers
// move with T (docs/parameters.md, "Void fraction face smoothing"). With smoothing, a
// point within the band b = s r of a face to another local cell shares its weight with that cell,
// linearly in its distance d: f = (b - d) / (2 b), half each on the face. eps_f is then continuous
// in the particle positions, so d(eps)/dt is bounded by the particles' speed over b, whatever T.
// Near several faces the shares multiply (cloud-in-cell), the corner's share going to the cell
// across both faces, so eps_f is continuous on hex meshes. Boundary and processor faces share
// nothing (a jump remains where a point crosses a processor face).
#include <algorithm>
#include <sstream>

#include "VoidFractionModel.h"

namespace mixflow::coupling {

namespace {

class DividedVoidFraction final : public VoidFractionModel {
 public:
  explicit DividedVoidFraction(const Dictionary& coeffs) {
    coeffs.allowOnly({"nShells", "nDirections", "smoothing"});
    nShells_ = static_cast<int>(coeffs.integerOr("nShells", 3, 1, 20));
    nDirections_ = static_cast<int>(coeffs.integerOr("nDirections", 16, 1, 1000));
    smoothing_ = coeffs.scalarOr("smoothing", 0.0, Range::closed(0.0, 1.0));
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
    if (smoothing_ > 0)
      s << ", shared linearly with the cell across a face within " << smoothing_
        << " x the particle radius (face smoothing)";
    return s.str();
  }
  void locate(const ParticleState& p, long seed, const CellLocator& mesh,
              ParticleCells& out) const override {
    out.clear();
    const double vp = p.volume();
    out.centreCell = mesh.findCell(p.x, seed);
    const double band = smoothing_ * p.radius;
    // Inside by the band too: no point is then within the band of a face.
    if (out.centreCell >= 0 && mesh.sphereInsideCell(p.x, p.radius + band, out.centreCell)) {
      out.volumes.emplace_back(out.centreCell, vp);
      return;
    }
    const long pointSeed = out.centreCell >= 0 ? out.centreCell : seed;
    // The centre cell's faces the sphere crosses: a point behind all of them is in that cell
    // without a search (most points; the search would return the same cell).
    thread_local std::vector<CellLocator::HalfSpace> crossed;
    const bool shortcut =
        out.centreCell >= 0 && mesh.crossedFaces(p.x, p.radius, out.centreCell, crossed);
    thread_local std::vector<CellLocator::NearFace> near;
    for (size_t j = 0; j < points_.offsets.size(); ++j) {
      const double w = points_.weights[j] * vp;
      const Vec3 x = p.x + p.radius * points_.offsets[j];
      const long c =
          shortcut && behindAll(crossed, x) ? out.centreCell : mesh.findCell(x, pointSeed);
      if (c < 0) {
        out.outsideVolume += w;
        continue;
      }
      if (band > 0) mesh.facesNear(x, c, band, near);
      if (band <= 0 || near.empty()) {
        add(out, c, w);
        continue;
      }
      // Cloud-in-cell: every non-empty subset S of the near faces gets prod_{k in S} f_k
      // prod_{k not in S} (1 - f_k), in the cell across all of them (the point pushed just past
      // each face of S; the face's own `across` for one face); what finds no cell stays in c.
      const size_t n = std::min<size_t>(near.size(), 3);  // a hex corner has 3
      double f[3];                                        // each near face's share, (b - d) / (2 b)
      for (size_t k = 0; k < n; ++k) f[k] = (band - near[k].distance) / (2 * band);
      double kept = w;
      for (unsigned mask = 1; mask < (1u << n); ++mask) {
        double share = 1;
        Vec3 q = x;
        int count = 0;
        long target = -1;
        for (size_t k = 0; k < n; ++k) {
          if (mask & (1u << k)) {
            share *= f[k];
            q += (near[k].distance + 1e-6 * band) * near[k].normal;
            target = near[k].across;
            ++count;
          } else {
            share *= 1 - f[k];
          }
        }
        if (count > 1) target = mesh.findCell(q, target);
        if (target < 0 || share <= 0) continue;
        add(out, target, w * share);
        kept -= w * share;
      }
      add(out, c, kept);
    }
  }
  const SpherePoints& points() const { return points_; }

 private:
  static bool behindAll(const std::vector<CellLocator::HalfSpace>& planes, const Vec3& x) {
    for (const auto& h : planes)
      if (dot(h.n, x) - h.d > 0) return false;
    return true;
  }
  static void add(ParticleCells& out, long c, double w) {
    for (auto& cv : out.volumes)
      if (cv.first == c) {
        cv.second += w;
        return;
      }
    out.volumes.emplace_back(c, w);
  }
  int nShells_ = 3, nDirections_ = 16;
  double smoothing_ = 0;  // face band as a fraction of the particle radius (0: off)
  SpherePoints points_;
};

}  // namespace

std::unique_ptr<VoidFractionModel> makeDividedVoidFraction(const Dictionary& coeffs) {
  return std::make_unique<DividedVoidFraction>(coeffs);
}

}  // namespace mixflow::coupling
