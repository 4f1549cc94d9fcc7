#include "FluidSource.h"

#include <sstream>

namespace mixflow::mx {

void FluidCells::resize(size_t n) {
  for (auto* v : {&x, &y, &volume, &alphaL, &epsF, &ux, &uy, &p}) v->resize(n);
}

SyntheticFluidSource::SyntheticFluidSource(double x0, double x1, int nx, double y0, double y1,
                                           int ny, double width, std::vector<double> times,
                                           Field field)
    : x0_(x0),
      x1_(x1),
      y0_(y0),
      y1_(y1),
      width_(width),
      nx_(nx),
      ny_(ny),
      times_(std::move(times)),
      field_(std::move(field)) {}

FluidCells SyntheticFluidSource::cells(double time) const {
  FluidCells c;
  c.resize(static_cast<size_t>(nx_) * ny_);
  const double dx = (x1_ - x0_) / nx_, dy = (y1_ - y0_) / ny_;
  for (int j = 0; j < ny_; ++j)
    for (int i = 0; i < nx_; ++i) {
      const size_t k = static_cast<size_t>(j) * nx_ + i;
      c.x[k] = x0_ + (i + 0.5) * dx;
      c.y[k] = y0_ + (j + 0.5) * dy;
      c.volume[k] = dx * dy * width_;
      const FluidState s = field_(c.x[k], c.y[k], time);
      c.alphaL[k] = s.alphaL;
      c.epsF[k] = s.epsF;
      c.ux[k] = s.ux;
      c.uy[k] = s.uy;
      c.p[k] = s.p;
    }
  return c;
}

std::string SyntheticFluidSource::describe() const {
  std::ostringstream s;
  s << "synthetic lattice " << nx_ << " x " << ny_ << " cells over [" << x0_ << ", " << x1_
    << "] x [" << y0_ << ", " << y1_ << "]";
  return s.str();
}

}  // namespace mixflow::mx
