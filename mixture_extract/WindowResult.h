// Everything the extractor computes for one time window (written by the HDF5 and CSV writers).
#pragma once

#include <string>
#include <vector>

#include "BinAccumulator.h"
#include "DriftCoefficients.h"
#include "ExtractSettings.h"

namespace mixflow::mx {

struct RegionResult {
  MixtureValues values;  // from the region's summed bin sums (mass balance not applicable)
  BinSums sums;
  int bins = 0;                 // bins whose centre lies in the region
  double residualRms = 0;       // RMS of the bins' Eq. 9 residual over the region's valid bins
  double residualScaleRms = 0;  // RMS of mass_balance_scale over the same bins
  int residualBins = 0;
};

struct WindowResult {
  TimeWindow window;
  int snapshots = 0, fluidTimes = 0;
  double tFirst = 0, tLast = 0;            // first and last snapshot time in the window
  double tFirstFluid = 0, tLastFluid = 0;  // first and last fluid time (NaN without fluid)
  double maxPairGap = 0;                   // max |fluid time - its snapshot's time| (NaN: none)
  double particleVolumeMean = 0;           // m3 per snapshot
  double particleVolumeOutsideMean = 0;    // m3 per snapshot outside the grid
  double particlesMean = 0;                // particles per snapshot
  std::vector<BinSums> sums;               // per bin
  std::vector<MixtureValues> bins;         // per bin
  std::vector<RegionResult> regions;       // per settings region
};

// Bins whose centre lies inside the region.
std::vector<int> regionBins(const AveragingGrid& g, const Region& r);

// Finalises a window: per-bin values, Eq. 9 residual, region values.
WindowResult finaliseWindow(const TimeWindow& w, const BinAccumulator& acc, const AveragingGrid& g,
                            const ExtractSettings& s);

}  // namespace mixflow::mx
