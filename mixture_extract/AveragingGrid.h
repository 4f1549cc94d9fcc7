// The averaging grid of the extractor: nx x ny rectangular bins in the channel's (x, y) plane, each
// spanning the whole sample width W in z. Bin (i, j) is stored at j * nx + i (y slowest), the
// layout of the (ny, nx) datasets in the HDF5 output.
#pragma once

#include <utility>
#include <vector>

namespace mixflow::mx {

class AveragingGrid {
 public:
  AveragingGrid() = default;
  AveragingGrid(double x0, double x1, int nx, double y0, double y1, int ny, double width);

  int nx() const { return nx_; }
  int ny() const { return ny_; }
  int size() const { return nx_ * ny_; }
  double x0() const { return x0_; }
  double x1() const { return x1_; }
  double y0() const { return y0_; }
  double y1() const { return y1_; }
  double width() const { return width_; }
  double dx() const { return (x1_ - x0_) / nx_; }
  double dy() const { return (y1_ - y0_) / ny_; }
  double binVolume() const { return dx() * dy() * width_; }
  // Edges are computed as x0 + (x1 - x0) i / nx everywhere, so shared edges agree bit for bit.
  double xEdge(int i) const { return x0_ + (x1_ - x0_) * i / nx_; }
  double yEdge(int j) const { return y0_ + (y1_ - y0_) * j / ny_; }
  std::vector<double> xEdges() const;
  std::vector<double> yEdges() const;
  std::vector<double> xCentres() const;
  std::vector<double> yCentres() const;
  int index(int i, int j) const { return j * nx_ + i; }

  // Bin holding the point (half-open bins [x_i, x_i+1)); -1 outside the grid.
  int locate(double x, double y) const;

  // Exact split of a sphere's volume over the bins (SphereBinVolume.h): appends (bin, volume) for
  // every bin the sphere overlaps and returns the volume inside the grid. The pieces come from
  // corner values at shared grid lines, so they telescope to the sphere's volume to round-off.
  double splitSphere(double xc, double yc, double r,
                     std::vector<std::pair<int, double>>& out) const;

 private:
  double x0_ = 0, x1_ = 1, y0_ = 0, y1_ = 1, width_ = 1;
  int nx_ = 1, ny_ = 1;
  // Scratch for splitSphere (corner values); the grid is used from one thread at a time.
  mutable std::vector<double> qx_, qy_, corner_;
};

}  // namespace mixflow::mx
