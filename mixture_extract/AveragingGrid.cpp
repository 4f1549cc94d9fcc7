#include "AveragingGrid.h"

#include <algorithm>
#include <cmath>

#include "SphereBinVolume.h"

namespace mixflow::mx {

AveragingGrid::AveragingGrid(double x0, double x1, int nx, double y0, double y1, int ny,
                             double width)
    : x0_(x0), x1_(x1), y0_(y0), y1_(y1), width_(width), nx_(nx), ny_(ny) {}

std::vector<double> AveragingGrid::xEdges() const {
  std::vector<double> e(nx_ + 1);
  for (int i = 0; i <= nx_; ++i) e[i] = xEdge(i);
  return e;
}

std::vector<double> AveragingGrid::yEdges() const {
  std::vector<double> e(ny_ + 1);
  for (int j = 0; j <= ny_; ++j) e[j] = yEdge(j);
  return e;
}

std::vector<double> AveragingGrid::xCentres() const {
  std::vector<double> c(nx_);
  for (int i = 0; i < nx_; ++i) c[i] = 0.5 * (xEdge(i) + xEdge(i + 1));
  return c;
}

std::vector<double> AveragingGrid::yCentres() const {
  std::vector<double> c(ny_);
  for (int j = 0; j < ny_; ++j) c[j] = 0.5 * (yEdge(j) + yEdge(j + 1));
  return c;
}

int AveragingGrid::locate(double x, double y) const {
  if (!(x >= x0_ && x < x1_ && y >= y0_ && y < y1_)) return -1;
  int i = static_cast<int>((x - x0_) / dx());
  int j = static_cast<int>((y - y0_) / dy());
  // Round-off near an edge: settle against the edges actually used.
  i = std::clamp(i, 0, nx_ - 1);
  j = std::clamp(j, 0, ny_ - 1);
  if (x < xEdge(i))
    --i;
  else if (i + 1 < nx_ && x >= xEdge(i + 1))
    ++i;
  if (y < yEdge(j))
    --j;
  else if (j + 1 < ny_ && y >= yEdge(j + 1))
    ++j;
  return index(i, j);
}

double AveragingGrid::splitSphere(double xc, double yc, double r,
                                  std::vector<std::pair<int, double>>& out) const {
  if (xc + r <= x0_ || xc - r >= x1_ || yc + r <= y0_ || yc - r >= y1_) return 0.0;
  const int ia = std::clamp(static_cast<int>(std::floor((xc - r - x0_) / dx())), 0, nx_ - 1);
  const int ib = std::clamp(static_cast<int>(std::floor((xc + r - x0_) / dx())), 0, nx_ - 1);
  const int ja = std::clamp(static_cast<int>(std::floor((yc - r - y0_) / dy())), 0, ny_ - 1);
  const int jb = std::clamp(static_cast<int>(std::floor((yc + r - y0_) / dy())), 0, ny_ - 1);
  const int ni = ib - ia + 1, nj = jb - ja + 1;
  // Corner values Q(X_i, Y_j) at the grid lines the sphere spans (plus the bounding lines).
  qx_.resize(ni + 1);
  qy_.resize(nj + 1);
  for (int a = 0; a <= ni; ++a) qx_[a] = xEdge(ia + a) - xc;
  for (int b = 0; b <= nj; ++b) qy_[b] = yEdge(ja + b) - yc;
  corner_.resize((ni + 1) * (nj + 1));
  for (int b = 0; b <= nj; ++b)
    for (int a = 0; a <= ni; ++a) corner_[b * (ni + 1) + a] = sphereCornerVolume(qx_[a], qy_[b], r);
  double inside = 0.0;
  for (int b = 0; b < nj; ++b) {
    for (int a = 0; a < ni; ++a) {
      const double v = corner_[(b + 1) * (ni + 1) + a + 1] - corner_[b * (ni + 1) + a + 1] -
                       corner_[(b + 1) * (ni + 1) + a] + corner_[b * (ni + 1) + a];
      if (v != 0.0) {
        out.emplace_back(index(ia + a, ja + b), v);
        inside += v;
      }
    }
  }
  return inside;
}

}  // namespace mixflow::mx
