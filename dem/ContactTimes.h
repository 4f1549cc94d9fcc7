// Closed-form contact mechanics used to choose and check the DEM time step and to verify LIGGGHTS.
#pragma once

namespace mixflow::dem {

constexpr double kPi = 3.14159265358979323846;

// Rayleigh wave time of a sphere: T_R = pi R sqrt(rho/G) / (0.1631 nu + 0.8766), G = E / (2(1+nu)).
double rayleighTime(double radius, double density, double youngModulus, double poisson);

// Effective modulus E* = 1 / ((1-nu1^2)/E1 + (1-nu2^2)/E2); pass E2 = inf for a rigid wall.
double effectiveModulus(double e1, double nu1, double e2, double nu2);

// Elastic Hertz impact at relative normal speed v (E*, R*, m* the effective quantities).
double hertzContactTime(double eStar, double rStar, double mStar, double v);
double hertzMaxOverlap(double eStar, double rStar, double mStar, double v);
double hertzPeakForce(double eStar, double rStar, double mStar, double v);

}  // namespace mixflow::dem
