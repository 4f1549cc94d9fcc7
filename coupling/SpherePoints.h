// A fixed set of points with weights representing a sphere's volume, for splitting a particle's
// volume between mesh cells (voidFractionModel divided).
//
// Construction: the unit ball is cut into nShells concentric shells of equal volume; shell k
// (k = 1..nShells) carries nDirections points at radius ((k - 1/2) / nShells)^(1/3) (the radius
// that halves the shell's volume) along the directions of a Fibonacci (golden-angle) lattice,
// turned by a different angle in every shell so that points of different shells do not line up.
// Every point gets the same weight; the weights are then scaled so that their sum is exactly 1
// in floating point (the last weight takes the remainder), so a particle's volume split over
// cells adds up to V_p to round-off.
#pragma once

#include <vector>

#include "Vec3.h"

namespace mixflow::coupling {

struct SpherePoints {
  std::vector<Vec3> offsets;    // on or inside the unit ball (multiply by the radius)
  std::vector<double> weights;  // fractions of the particle volume, summing to 1

  static SpherePoints make(int nShells, int nDirections);
  // Volume fraction of the ball on the side x > a (a in units of the radius), as the points see
  // it (for tests of the split's accuracy against the exact cap volume).
  double fractionAbove(int axis, double a) const;
};

// Exact volume fraction of the unit ball with coordinate > a (a in [-1, 1]).
double exactCapFraction(double a);

}  // namespace mixflow::coupling
