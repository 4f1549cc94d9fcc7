// The pore pressure split into its hydrostatic and excess parts, and the pore-pressure ratio chi
// of the bulk model's closure (docs/bulk_model.md "Pore pressure"): column by column, since the
// hydrostatic part is the weight of the liquid column above a bin.
#pragma once

#include <vector>

#include "AveragingGrid.h"
#include "DriftCoefficients.h"

namespace mixflow::mx {

// The liquid surface of an x column: its height h_l, y0 + sum_j saturation_j dy (saturation the
// liquid share of the bin's fluid volume, 0 in gas; a row without a fluid cell centre takes the
// saturation interpolated linearly between the nearest rows with one, held beyond them: the binning
// by centre leaves some rows empty), and the gas pressure above it, that of the lowest bin wholly
// above h_l (its gas-volume weighted p). NaN where the surface is not inside the grid (the top bin
// more than half liquid, no fluid cell, no gas above).
struct LiquidSurface {
  double height;
  double pressure;
};
std::vector<LiquidSurface> liquidSurfaces(const AveragingGrid& g, const std::vector<BinSums>& sums);

// Sets p_f_hydrostatic = p_surface + rho_f g (h_l - y), p_f_excess and pore_pressure_ratio of
// every bin (and kNoLiquidSurface, kSmallLoad) from the column surfaces.
void porePressure(const AveragingGrid& g, const std::vector<BinSums>& sums,
                  std::vector<MixtureValues>& bins, const ExtractSettings& s);

// The same fields of a region from its member bins: the hydrostatic part weighted as the region's
// p_f is (by liquid volume), masked when a member with liquid has no surface.
void regionPorePressure(const std::vector<int>& members, const std::vector<BinSums>& sums,
                        const std::vector<MixtureValues>& bins, MixtureValues& region,
                        const ExtractSettings& s);

}  // namespace mixflow::mx
