#include "CoarseGrainKernel.h"

#include <algorithm>
#include <cmath>

namespace mixflow::mx {

namespace {
// 6-point Gauss-Legendre on [0, 1]: a contact line is at most a grain long and the kernel at least
// half a grain wide, so the line integral is smooth on the segment.
constexpr int kGauss = 6;
constexpr double kNode[kGauss] = {0.033765242898423975, 0.16939530676686776, 0.38069040695840156,
                                  0.61930959304159844,  0.83060469323313224, 0.96623475710157603};
constexpr double kWeight[kGauss] = {0.085662246189585, 0.180380786524069, 0.233956967286345,
                                    0.233956967286345, 0.180380786524069, 0.085662246189585};
}  // namespace

CoarseGrainKernel::CoarseGrainKernel(const AveragingGrid& grid, const std::string& shape,
                                     double width)
    : grid_(grid), width_(width) {
  if (shape == "lucy") {
    shape_ = Shape::Lucy;
    cutoff_ = 2 * width;
    norm_ = 5 / (M_PI * cutoff_ * cutoff_);
  } else if (shape == "gaussian") {
    shape_ = Shape::Gaussian;
    cutoff_ = 3 * width;
    norm_ = 1 / (2 * M_PI * width * width * (1 - std::exp(-4.5)));
  } else {
    shape_ = Shape::Bins;
    cutoff_ = 0;
    norm_ = 0;
  }
}

double CoarseGrainKernel::psi(double r) const {
  if (r >= cutoff_) return 0;
  if (shape_ == Shape::Lucy) {
    const double q = r / cutoff_, u = 1 - q;
    return norm_ * (1 + 3 * q) * u * u * u;
  }
  return norm_ * std::exp(-0.5 * r * r / (width_ * width_));
}

double CoarseGrainKernel::pointWeights(double x, double y,
                                       std::vector<std::pair<int, double>>& out) const {
  if (exactBins()) {
    const int b = grid_.locate(x, y);
    if (b < 0) return 0;
    out.emplace_back(b, 1.0);
    return 1;
  }
  const double dx = grid_.dx(), dy = grid_.dy(), area = dx * dy;
  const int i0 = std::max(0, static_cast<int>(std::floor((x - cutoff_ - grid_.x0()) / dx)));
  const int i1 =
      std::min(grid_.nx() - 1, static_cast<int>(std::floor((x + cutoff_ - grid_.x0()) / dx)));
  const int j0 = std::max(0, static_cast<int>(std::floor((y - cutoff_ - grid_.y0()) / dy)));
  const int j1 =
      std::min(grid_.ny() - 1, static_cast<int>(std::floor((y + cutoff_ - grid_.y0()) / dy)));
  double sum = 0;
  for (int j = j0; j <= j1; ++j) {
    const double ry = grid_.y0() + (j + 0.5) * dy - y;
    for (int i = i0; i <= i1; ++i) {
      const double rx = grid_.x0() + (i + 0.5) * dx - x;
      const double w = psi(std::sqrt(rx * rx + ry * ry)) * area;
      if (w > 0) {
        out.emplace_back(grid_.index(i, j), w);
        sum += w;
      }
    }
  }
  return sum;
}

void CoarseGrainKernel::segmentWeights(double x1, double y1, double x2, double y2,
                                       std::vector<std::pair<int, double>>& out) const {
  const double ex = x2 - x1, ey = y2 - y1;
  if (!exactBins()) {
    // Weights of the Gauss points, merged per bin in a dense scratch (a line reaches tens of
    // bins, six points each).
    if (sum_.size() != static_cast<size_t>(grid_.size())) sum_.assign(grid_.size(), 0.0);
    touched_.clear();
    for (int g = 0; g < kGauss; ++g) {
      points_.clear();
      pointWeights(x1 + kNode[g] * ex, y1 + kNode[g] * ey, points_);
      for (const auto& [b, w] : points_) {
        if (sum_[b] == 0) touched_.push_back(b);
        sum_[b] += kWeight[g] * w;
      }
    }
    for (int b : touched_) {
      out.emplace_back(b, sum_[b]);
      sum_[b] = 0;
    }
    return;
  }
  // Parameters where the segment crosses a grid line; each piece lies in one bin.
  cuts_.assign({0.0, 1.0});
  auto crossings = [&](double a, double e, double lo, double h, int n) {
    if (e == 0) return;
    const double s0 = (std::min(a, a + e) - lo) / h, s1 = (std::max(a, a + e) - lo) / h;
    for (int k = std::max(0, static_cast<int>(std::ceil(s0)));
         k <= std::min(n, static_cast<int>(std::floor(s1))); ++k) {
      const double s = (lo + k * h - a) / e;
      if (s > 0 && s < 1) cuts_.push_back(s);
    }
  };
  crossings(x1, ex, grid_.x0(), grid_.dx(), grid_.nx());
  crossings(y1, ey, grid_.y0(), grid_.dy(), grid_.ny());
  std::sort(cuts_.begin(), cuts_.end());
  for (size_t k = 0; k + 1 < cuts_.size(); ++k) {
    const double ds = cuts_[k + 1] - cuts_[k];
    if (ds <= 0) continue;
    const double sm = 0.5 * (cuts_[k] + cuts_[k + 1]);
    const int b = grid_.locate(x1 + sm * ex, y1 + sm * ey);
    if (b >= 0) out.emplace_back(b, ds);
  }
}

}  // namespace mixflow::mx
