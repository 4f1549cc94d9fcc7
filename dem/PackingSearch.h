// The packing control's search (demDict settle.packingControl friction): the settling friction μ
// whose settle of the loose fill gives a sample solid fraction φ within a tolerance of the target.
// φ falls monotonically with μ and nearly linearly in u = ln(μ + 0.05): 0.63, 0.61 and 0.569 at
// μ = 0, 0.1 and 0.7 on the reference tier, about −0.022 per unit of u. The search is a secant on
// u, extrapolated from the trials nearest the target's side until trials lie on both sides of it,
// then kept inside that bracket. Pure arithmetic: DemDriver::settle runs the trials.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace mixflow::dem {

class PackingSearch {
 public:
  struct Trial {
    double friction = 0;
    double fraction = 0;
  };
  // The slope dφ/du used until two trials give their own (reference tier, see above).
  static constexpr double kSlope = -0.022;
  static constexpr double kShift = 0.05;  // u = ln(μ + kShift): finite at μ = 0
  // In the settling inputs (SettledSample.h): bump when the sequence of trials changes.
  static constexpr int kVersion = 1;

  PackingSearch(double target, double tolerance, double minFriction, double maxFriction,
                double firstFriction);
  // The next trial's friction; nullopt when no friction in range can help (whyNot() says why).
  std::optional<double> next() const;
  void add(double friction, double fraction);
  // The last trial lies within the tolerance of the target.
  bool landed() const;
  const std::vector<Trial>& trials() const { return trials_; }
  // Why next() has no friction to offer (empty while it has).
  std::string whyNot() const;

 private:
  double u(double friction) const;
  double friction(double u) const;
  // Secant step from trial a towards the target, with the slope of (a, b) or kSlope.
  double extrapolate(const Trial& a, const Trial* b) const;

  double target_, tolerance_, minFriction_, maxFriction_, first_;
  std::vector<Trial> trials_;
};

}  // namespace mixflow::dem
