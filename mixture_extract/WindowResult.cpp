#include "WindowResult.h"

#include <cmath>

#include "PorePressure.h"

namespace mixflow::mx {

std::vector<int> regionBins(const AveragingGrid& g, const Region& r) {
  std::vector<int> out;
  const std::vector<double> xc = g.xCentres(), yc = g.yCentres();
  for (int j = 0; j < g.ny(); ++j)
    for (int i = 0; i < g.nx(); ++i)
      if (xc[i] >= r.x0 && xc[i] < r.x1 && yc[j] >= r.y0 && yc[j] < r.y1)
        out.push_back(g.index(i, j));
  return out;
}

WindowResult finaliseWindow(const TimeWindow& w, const BinAccumulator& acc, const AveragingGrid& g,
                            const ExtractSettings& s) {
  WindowResult res;
  res.window = w;
  res.snapshots = acc.snapshots();
  res.fluidTimes = acc.fluidTimes();
  res.tFirst = acc.snapshotTimes.front();
  res.tLast = acc.snapshotTimes.back();
  res.tFirstFluid = res.tLastFluid = res.maxPairGap = std::nan("");  // set by the caller
  res.particleVolumeMean = acc.particleVolumeTotal() / res.snapshots;
  res.particleVolumeOutsideMean = acc.volumeOutsideGrid() / res.snapshots;
  res.particlesMean = acc.particleCount() / res.snapshots;
  res.sums = acc.bins();
  res.bins.reserve(g.size());
  for (int b = 0; b < g.size(); ++b)
    res.bins.push_back(mixtureValues(res.sums[b], g.binVolume(), res.snapshots, res.fluidTimes, s));
  massBalance(g, res.bins);
  porePressure(g, res.sums, res.bins, s);
  for (const Region& r : s.regions) {
    RegionResult rr;
    const std::vector<int> members = regionBins(g, r);
    rr.bins = static_cast<int>(members.size());
    double sq = 0, sqs = 0;
    for (int b : members) {
      rr.sums.add(res.sums[b]);
      const MixtureValues& m = res.bins[b];
      if (m.valid(fMassResidual)) {
        sq += m.value[fMassResidual] * m.value[fMassResidual];
        sqs += m.value[fMassScale] * m.value[fMassScale];
        ++rr.residualBins;
      }
    }
    if (rr.residualBins > 0) {
      rr.residualRms = std::sqrt(sq / rr.residualBins);
      rr.residualScaleRms = std::sqrt(sqs / rr.residualBins);
    }
    // A region always has bins (checked against the grid when the settings were read).
    rr.values = mixtureValues(rr.sums, g.binVolume() * std::max(rr.bins, 1), res.snapshots,
                              res.fluidTimes, s);
    regionPorePressure(members, res.sums, res.bins, rr.values, s);
    res.regions.push_back(rr);
  }
  return res;
}

}  // namespace mixflow::mx
