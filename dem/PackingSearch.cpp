#include "PackingSearch.h"

#include <algorithm>
#include <cmath>

#include "Dictionary.h"

namespace mixflow::dem {

namespace {
// A bracket narrower than this (in friction) is below what the packing's noise resolves.
constexpr double kMinBracket = 1e-4;
// A bracketed secant step keeps this share of the bracket from either end, so one end that the
// secant keeps returning to still moves.
constexpr double kBracketMargin = 0.1;

std::string num(double v) { return formatNumber(v, 4); }
}  // namespace

PackingSearch::PackingSearch(double target, double tolerance, double minFriction,
                             double maxFriction, double firstFriction)
    : target_(target),
      tolerance_(tolerance),
      minFriction_(minFriction),
      maxFriction_(maxFriction),
      first_(std::clamp(firstFriction, minFriction, maxFriction)) {}

double PackingSearch::u(double friction) const { return std::log(friction + kShift); }

double PackingSearch::friction(double uu) const {
  return std::clamp(std::exp(uu) - kShift, minFriction_, maxFriction_);
}

void PackingSearch::add(double friction, double fraction) {
  trials_.push_back({friction, fraction});
}

bool PackingSearch::landed() const {
  return !trials_.empty() && std::abs(trials_.back().fraction - target_) <= tolerance_;
}

double PackingSearch::extrapolate(const Trial& a, const Trial* b) const {
  double slope = kSlope;
  if (b && std::abs(u(a.friction) - u(b->friction)) > 1e-9) {
    const double s = (a.fraction - b->fraction) / (u(a.friction) - u(b->friction));
    // A flat or rising pair is packing noise, not the trend: keep the reference slope.
    if (s <= 0.25 * kSlope) slope = s;
  }
  return friction(u(a.friction) + (target_ - a.fraction) / slope);
}

std::optional<double> PackingSearch::next() const {
  if (trials_.empty()) return first_;
  if (!whyNot().empty()) return std::nullopt;
  const Trial *dense = nullptr, *loose = nullptr;  // the trials nearest the target's each side
  const Trial *dense2 = nullptr, *loose2 = nullptr;
  for (const Trial& t : trials_) {
    if (t.fraction > target_ && (!dense || t.friction > dense->friction))
      dense2 = dense, dense = &t;
    else if (t.fraction > target_ && (!dense2 || t.friction > dense2->friction))
      dense2 = &t;
    if (t.fraction < target_ && (!loose || t.friction < loose->friction))
      loose2 = loose, loose = &t;
    else if (t.fraction < target_ && (!loose2 || t.friction < loose2->friction))
      loose2 = &t;
  }
  if (dense && loose) {
    const double ud = u(dense->friction), ul = u(loose->friction);
    double uu = ud + (target_ - dense->fraction) * (ul - ud) / (loose->fraction - dense->fraction);
    const double margin = kBracketMargin * (ul - ud);
    uu = std::clamp(uu, ud + margin, ul - margin);
    return friction(uu);
  }
  // All on one side: more friction loosens a dense sample, less compacts a loose one.
  return dense ? extrapolate(*dense, dense2) : extrapolate(*loose, loose2);
}

std::string PackingSearch::whyNot() const {
  if (trials_.empty() || landed()) return "";
  double denseMax = -1, looseMin = 1e300;
  bool anyDense = false, anyLoose = false;
  for (const Trial& t : trials_) {
    if (t.fraction > target_) anyDense = true, denseMax = std::max(denseMax, t.friction);
    if (t.fraction < target_) anyLoose = true, looseMin = std::min(looseMin, t.friction);
  }
  if (anyDense && anyLoose) {
    if (looseMin <= denseMax)
      return "a settle at friction " + num(looseMin) + " came out looser than one at " +
             num(denseMax) + ": the packing's trial-to-trial noise exceeds the tolerance";
    if (looseMin - denseMax < kMinBracket)
      return "the frictions on either side of the target are within " + num(kMinBracket) +
             " of each other: the packing's noise exceeds the tolerance";
    return "";
  }
  if (anyDense && denseMax >= maxFriction_)
    return "even at maxFriction " + num(maxFriction_) + " the sample is denser than the target";
  if (anyLoose && looseMin <= minFriction_)
    return "even at minFriction " + num(minFriction_) + " the sample is looser than the target";
  return "";
}

}  // namespace mixflow::dem
