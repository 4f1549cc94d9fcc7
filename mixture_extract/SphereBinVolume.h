// Exact volume of a sphere inside an averaging bin that spans the whole channel width (z), i.e. the
// sphere's volume inside the infinite prism x0 < x < x1, y0 < y < y1 (docs/model.md §9: particle
// volume split exactly between bins, not centre-counted).
//
// Method (closed form, no quadrature): the corner function
//   Q(X, Y) = volume of the sphere (centre 0, radius r) with x < X and y < Y
// is the integral over x of S(x), the area of the circular cross-section (radius rho(x) =
// sqrt(r^2 - x^2)) below the chord y = Y:
//   S = rho^2 (pi/2 + asin(Y/rho)) + Y sqrt(rho^2 - Y^2)  for |Y| < rho,   0 or pi rho^2 otherwise.
// Its antiderivative over x is elementary (integration by parts of the asin term, then the
// standard integrals of u^2/sqrt(c^2-u^2) and 1/((r^2-u^2) sqrt(c^2-u^2)), c^2 = r^2 - Y^2):
//   P(u) = (r^2 u - u^3/3) atan2(Y, s) + (2/3) Y u s + (Y/3)(c^2 + 2 r^2) asin(u/c)
//          - (2/3) r^3 sgn(Y) atan2(u |Y|, r s),            s = sqrt(c^2 - u^2),
// valid on |u| < c; outside it the section is entirely above or below the chord. The bin volume is
// Q(x1,y1) - Q(x0,y1) - Q(x1,y0) + Q(x0,y0), and splitting a sphere over a row of bins uses the
// corner values at the shared grid lines, so the pieces telescope to the full 4/3 pi r^3 (to
// round-off) when the sphere lies inside the grid.
#pragma once

namespace mixflow::mx {

constexpr double kPi = 3.14159265358979323846;

// Q(X, Y): volume of the sphere of radius r centred at the origin with x < X and y < Y.
double sphereCornerVolume(double X, double Y, double r);

// Volume of the sphere (centre xc, yc, radius r) inside x0 < x < x1, y0 < y < y1 (all z).
double sphereRectVolume(double xc, double yc, double r, double x0, double x1, double y0, double y1);

inline double sphereVolume(double r) { return 4.0 / 3.0 * kPi * r * r * r; }

}  // namespace mixflow::mx
