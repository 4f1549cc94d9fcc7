#include "SphereBinVolume.h"

#include <algorithm>
#include <cmath>

namespace mixflow::mx {

namespace {

// Integral of (pi/2) rho^2 = (pi/2)(r^2 - u^2) from -r to U (half of every full section).
double halfSections(double U, double r) {
  return 0.5 * kPi * (r * r * (U + r) - (U * U * U + r * r * r) / 3.0);
}

// Antiderivative of T(u) = S(u) - (pi/2) rho^2 on |u| <= c (see the header).
double chordPart(double u, double Y, double r, double c) {
  const double s = std::sqrt(std::max(c * c - u * u, 0.0));
  const double sgn = Y > 0 ? 1.0 : (Y < 0 ? -1.0 : 0.0);
  const double ratio = std::clamp(u / c, -1.0, 1.0);
  return (r * r * u - u * u * u / 3.0) * std::atan2(Y, s) + 2.0 / 3.0 * Y * u * s +
         Y / 3.0 * (c * c + 2.0 * r * r) * std::asin(ratio) -
         2.0 / 3.0 * r * r * r * sgn * std::atan2(u * std::fabs(Y), r * s);
}

}  // namespace

double sphereCornerVolume(double X, double Y, double r) {
  const double Xh = std::clamp(X, -r, r);
  const double half = halfSections(Xh, r);
  if (Y >= r) return 2.0 * half;
  if (Y <= -r) return 0.0;
  const double c = std::sqrt(r * r - Y * Y);
  if (c == 0.0) return Y > 0 ? 2.0 * half : 0.0;
  const double sgn = Y > 0 ? 1.0 : (Y < 0 ? -1.0 : 0.0);
  // |u| >= c: the whole section lies on one side of the chord (T = sgn(Y) (pi/2) rho^2).
  double t = sgn * halfSections(std::min(Xh, -c), r);
  t += chordPart(std::clamp(Xh, -c, c), Y, r, c) - chordPart(-c, Y, r, c);
  if (Xh > c) t += sgn * (halfSections(Xh, r) - halfSections(c, r));
  return half + t;
}

double sphereRectVolume(double xc, double yc, double r, double x0, double x1, double y0,
                        double y1) {
  if (x1 <= x0 || y1 <= y0) return 0.0;
  const double a0 = x0 - xc, a1 = x1 - xc, b0 = y0 - yc, b1 = y1 - yc;
  return sphereCornerVolume(a1, b1, r) - sphereCornerVolume(a0, b1, r) -
         sphereCornerVolume(a1, b0, r) + sphereCornerVolume(a0, b0, r);
}

}  // namespace mixflow::mx
