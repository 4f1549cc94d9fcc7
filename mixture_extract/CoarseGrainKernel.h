// The coarse-graining function of the extractor (Goldhirsch 2010; Weinhart et al. 2012): how a
// particle, a contact line or a fluid cell is shared among the bins of the averaging grid. The
// fields are averaged across the width, so kernels are 2-D in (x, y) and evaluated at the bin
// centres. A weight is the share of a unit quantity given to the bin, ψ(r_b − r) Δx Δy for a
// point, Δx Δy ∫₀¹ ψ(r_b − r(s)) ds along a segment; the bin's field is the weighted sum over the
// bin's volume Δx Δy W, so every additive sum of BinAccumulator keeps its meaning.
//   bins      ψ = the bin's indicator / (Δx Δy): the exact fraction of a segment inside each
//             bin (particles are split by their exact sphere volume, AveragingGrid::splitSphere)
//   lucy      ψ = 5 / (π c²) (1 + 3 r/c)(1 − r/c)³, r < c, cutoff c = 2 w (w = c/2 as Weinhart et
//             al. take it; its standard deviation per direction is √(5/56) c = 0.60 w)
//   gaussian  ψ = exp(−r² / 2w²) / (2π w²), cut at 3 w and scaled to integrate to 1
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "AveragingGrid.h"

namespace mixflow::mx {

class CoarseGrainKernel {
 public:
  enum class Shape { Bins, Lucy, Gaussian };
  // shape: bins | lucy | gaussian; width w in metres (unused for bins).
  CoarseGrainKernel(const AveragingGrid& grid, const std::string& shape, double width);

  Shape shape() const { return shape_; }
  bool exactBins() const { return shape_ == Shape::Bins; }
  double cutoff() const { return cutoff_; }
  // 2-D kernel value at distance r (1/m2).
  double psi(double r) const;

  // Appends (bin, weight) for a point; returns the sum of the weights appended (< 1 when part
  // of the kernel lies outside the grid). Exact bins: the bin holding the point, weight 1.
  double pointWeights(double x, double y, std::vector<std::pair<int, double>>& out) const;
  // Appends (bin, weight) for the segment from (x1, y1) to (x2, y2): exact bins give the
  // fraction of the segment inside each bin, kernels Δx Δy ∫₀¹ ψ ds (Gauss-Legendre).
  void segmentWeights(double x1, double y1, double x2, double y2,
                      std::vector<std::pair<int, double>>& out) const;

 private:
  const AveragingGrid& grid_;
  Shape shape_;
  double width_, cutoff_, norm_;
  // Scratch of segmentWeights; the kernel is used from one thread at a time.
  mutable std::vector<double> cuts_, sum_;
  mutable std::vector<int> touched_;
  mutable std::vector<std::pair<int, double>> points_;
};

}  // namespace mixflow::mx
