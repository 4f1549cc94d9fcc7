// voidFractionModel centre: the whole particle volume goes to the cell holding its centre.
// Cheap, but eps_f jumps by V_p / V_c when a particle crosses a face; a particle whose centre is
// outside the mesh contributes nothing (reported as outside volume).
#include "VoidFractionModel.h"

namespace mixflow::coupling {

namespace {

class CentreVoidFraction final : public VoidFractionModel {
 public:
  explicit CentreVoidFraction(const Dictionary& coeffs) { coeffs.allowOnly({}); }
  const std::string& name() const override {
    static const std::string n = "centre";
    return n;
  }
  std::string describe() const override {
    return "centre: whole particle volume to the cell holding the centre";
  }
  void locate(const ParticleState& p, long seed, const CellLocator& mesh,
              ParticleCells& out) const override {
    out.clear();
    out.centreCell = mesh.findCell(p.x, seed);
    if (out.centreCell >= 0)
      out.volumes.emplace_back(out.centreCell, p.volume());
    else
      out.outsideVolume = p.volume();
  }
};

}  // namespace

std::unique_ptr<VoidFractionModel> makeCentreVoidFraction(const Dictionary& coeffs) {
  return std::make_unique<CentreVoidFraction>(coeffs);
}

}  // namespace mixflow::coupling
