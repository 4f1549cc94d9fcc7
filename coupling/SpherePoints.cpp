#include "SpherePoints.h"

#include <cmath>
#include <stdexcept>

namespace mixflow::coupling {

SpherePoints SpherePoints::make(int nShells, int nDirections) {
  if (nShells < 1 || nDirections < 1)
    throw std::invalid_argument("SpherePoints: nShells and nDirections must be >= 1");
  constexpr double kPi = 3.14159265358979323846;
  const double golden = kPi * (3.0 - std::sqrt(5.0));  // golden angle
  SpherePoints s;
  const int n = nShells * nDirections;
  s.offsets.reserve(n);
  s.weights.assign(n, 1.0 / n);
  for (int k = 0; k < nShells; ++k) {
    const double radius = std::cbrt((k + 0.5) / nShells);
    const double turn = k * 2.0 * kPi / (nShells * 1.61803398874989485);
    for (int j = 0; j < nDirections; ++j) {
      // Lattice point j of nDirections: equal-area bands in z, golden-angle steps in azimuth.
      const double z = 1.0 - (2.0 * j + 1.0) / nDirections;
      const double rho = std::sqrt(std::max(0.0, 1.0 - z * z));
      const double phi = j * golden + turn;
      // Alternate the lattice's axis between shells (z, x, y) for a more isotropic set.
      Vec3 d(rho * std::cos(phi), rho * std::sin(phi), z);
      if (k % 3 == 1) d = Vec3(d.z, d.x, d.y);
      if (k % 3 == 2) d = Vec3(d.y, d.z, d.x);
      s.offsets.push_back(radius * d);
    }
  }
  // Make the weights sum to 1 exactly in the order the coupling adds them.
  double partial = 0;
  for (int i = 0; i + 1 < n; ++i) partial += s.weights[i];
  s.weights[n - 1] = 1.0 - partial;
  return s;
}

double SpherePoints::fractionAbove(int axis, double a) const {
  double f = 0;
  for (size_t i = 0; i < offsets.size(); ++i)
    if (offsets[i][axis] > a) f += weights[i];
  return f;
}

double exactCapFraction(double a) {
  if (a >= 1) return 0;
  if (a <= -1) return 1;
  const double h = 1 - a;        // cap height of the unit ball
  return h * h * (3 - h) / 4.0;  // (pi h^2 (3 - h) / 3) / (4 pi / 3)
}

}  // namespace mixflow::coupling
