#include "ContactTimes.h"

#include <cmath>

namespace mixflow::dem {

double rayleighTime(double radius, double density, double youngModulus, double poisson) {
  const double shear = youngModulus / (2.0 * (1.0 + poisson));
  return kPi * radius * std::sqrt(density / shear) / (0.1631 * poisson + 0.8766);
}

double effectiveModulus(double e1, double nu1, double e2, double nu2) {
  const double inv2 = std::isinf(e2) ? 0.0 : (1.0 - nu2 * nu2) / e2;
  return 1.0 / ((1.0 - nu1 * nu1) / e1 + inv2);
}

double hertzContactTime(double eStar, double rStar, double mStar, double v) {
  return 2.868 * std::pow(mStar * mStar / (rStar * eStar * eStar * v), 0.2);
}

double hertzMaxOverlap(double eStar, double rStar, double mStar, double v) {
  return std::pow(15.0 * mStar * v * v / (16.0 * eStar * std::sqrt(rStar)), 0.4);
}

double hertzPeakForce(double eStar, double rStar, double mStar, double v) {
  const double d = hertzMaxOverlap(eStar, rStar, mStar, v);
  return 4.0 / 3.0 * eStar * std::sqrt(rStar) * std::pow(d, 1.5);
}

}  // namespace mixflow::dem
