#include "PorePressure.h"

#include <cmath>

namespace mixflow::mx {

namespace {
// The scenes' gravity (dem/LiggghtsCommands.cpp, the coupled solver's g): 9.81 m/s2 along -y.
constexpr double kGravity = 9.81;

// p_f_excess and chi from the hydrostatic part; p_f, p_s and the reasons already set.
void setExcess(MixtureValues& m, double hydrostatic, const ExtractSettings& s) {
  double* v = m.value;
  if (std::isnan(hydrostatic)) {
    m.reasons |= kNoLiquidSurface;
    return;
  }
  if (!m.valid(fPf)) return;
  v[fPfHydrostatic] = hydrostatic;
  v[fPfExcess] = v[fPf] - hydrostatic;
  if ((m.reasons & kOutsideMixture) != 0) return;
  const double load = v[fPs] + v[fPfExcess];  // total less hydrostatic
  if (std::fabs(load) < s.thresholds.minPressure) {
    m.reasons |= kSmallLoad;
    return;
  }
  v[fPoreRatio] = v[fPfExcess] / load;
}
}  // namespace

std::vector<LiquidSurface> liquidSurfaces(const AveragingGrid& g,
                                          const std::vector<BinSums>& sums) {
  std::vector<LiquidSurface> h(g.nx(), {std::nan(""), std::nan("")});
  for (int i = 0; i < g.nx(); ++i) {
    std::vector<double> sat(g.ny(), std::nan(""));
    // The bins' saturation, 0 where the fluid cells hold no liquid (the field is NaN there).
    for (int j = 0; j < g.ny(); ++j) {
      const BinSums& b = sums[g.index(i, j)];
      if (b.fluidVolume > 0) sat[j] = b.liquidVolume / b.fluidVolume;
    }
    double sum = 0;
    bool any = false;
    for (int j = 0; j < g.ny(); ++j) {
      double sj = sat[j];
      if (std::isnan(sj)) {
        int lo = j - 1, hi = j + 1;
        while (lo >= 0 && std::isnan(sat[lo])) --lo;
        while (hi < g.ny() && std::isnan(sat[hi])) ++hi;
        const bool l = lo >= 0, u = hi < g.ny();
        if (!l && !u) break;  // no fluid cell in the column
        // Linear in the row between the nearest rows with fluid, held beyond the last.
        sj = l && u ? sat[lo] + (sat[hi] - sat[lo]) * (j - lo) / double(hi - lo)
                    : (l ? sat[lo] : sat[hi]);
      }
      any = true;
      sum += sj;
    }
    // A top bin more than half liquid: the surface may lie above the grid.
    const double top = sat[g.ny() - 1];
    if (!any || top > 0.5) continue;
    const double hl = g.y0() + sum * g.dy();
    for (int j = 0; j < g.ny(); ++j) {
      const BinSums& b = sums[g.index(i, j)];
      const double gas = b.fluidVolume - b.liquidVolume;
      if (g.yEdge(j) >= hl && gas > 0) {
        h[i] = {hl, b.gasVolumeP / gas};
        break;
      }
    }
  }
  return h;
}

void porePressure(const AveragingGrid& g, const std::vector<BinSums>& sums,
                  std::vector<MixtureValues>& bins, const ExtractSettings& s) {
  const std::vector<LiquidSurface> h = liquidSurfaces(g, sums);
  const std::vector<double> yc = g.yCentres();
  for (int j = 0; j < g.ny(); ++j)
    for (int i = 0; i < g.nx(); ++i)
      setExcess(bins[g.index(i, j)],
                h[i].pressure + s.liquidDensity * kGravity * (h[i].height - yc[j]), s);
}

void regionPorePressure(const std::vector<int>& members, const std::vector<BinSums>& sums,
                        const std::vector<MixtureValues>& bins, MixtureValues& region,
                        const ExtractSettings& s) {
  double weighted = 0, liquid = 0;
  for (int b : members) {
    if (!(sums[b].liquidVolume > 0)) continue;
    const double hb = bins[b].value[fPfHydrostatic];
    if (std::isnan(hb) && (bins[b].reasons & kNoLiquidSurface) != 0) {
      weighted = std::nan("");
      break;
    }
    if (std::isnan(hb)) continue;  // a bin whose p_f is masked (a smeared interface tail)
    weighted += sums[b].liquidVolume * hb;
    liquid += sums[b].liquidVolume;
  }
  setExcess(region, liquid > 0 ? weighted / liquid : std::nan(""), s);
}

}  // namespace mixflow::mx
