#include "WindowPlan.h"

#include <algorithm>
#include <cmath>
#include <ostream>

#include "Dictionary.h"
#include "Scene.h"

namespace mixflow::mx {

namespace {

std::string num(double v) { return formatNumber(v, 8); }

bool sameTime(double a, double b) {
  return std::fabs(a - b) <= 1e-12 * std::max(1.0, std::fabs(a));
}

// "a, b, c" of at most `most` times, then "... (n in all)".
std::string timeList(const std::vector<double>& t, size_t most = 8) {
  std::string s;
  for (size_t k = 0; k < std::min(t.size(), most); ++k) s += (k ? ", " : "") + num(t[k]);
  if (t.size() > most) s += ", ... (" + std::to_string(t.size()) + " in all)";
  return s;
}

// Index of the time in the ascending list nearest to t (the list must not be empty).
template <class Get>
size_t nearestIndex(size_t n, Get time, double t) {
  size_t lo = 0, hi = n;
  while (lo < hi) {
    const size_t mid = (lo + hi) / 2;
    if (time(mid) < t)
      lo = mid + 1;
    else
      hi = mid;
  }
  if (lo == n) return n - 1;
  if (lo > 0 && t - time(lo - 1) <= time(lo) - t) return lo - 1;
  return lo;
}

std::string pairRule(const ExtractSettings& s) {
  return "pairTolerance " + num(s.pairTolerance) + " s";
}

// A window with no snapshot: after the last snapshot of a finished case (Skipped when generated),
// else a listed or generated window narrower than the snapshot interval (an input error).
WindowState emptyWindow(const TimeWindow& w, const PlanInputs& in) {
  const std::vector<SnapshotEntry>& series = in.series;
  const double tol = in.settings.timeTolerance, lastT = series.back().time;
  if (w.t0 - tol > lastT) {
    if (!in.settings.windowsGenerated)
      throw InputError(w.origin + ": window (" + num(w.t0) + " " + num(w.t1) +
                       ") starts after the last snapshot (t = " + num(lastT) +
                       " s) of a finished case; available snapshots span [" +
                       num(series.front().time) + ", " + num(lastT) + "] s");
    return WindowState::Skipped;
  }
  double before = series.front().time, after = lastT;
  for (const auto& e : series) {
    if (e.time < w.t0) before = e.time;
    if (e.time >= w.t1) {
      after = e.time;
      break;
    }
  }
  throw InputError(w.origin + ": window [" + num(w.t0) + ", " + num(w.t1) +
                   ") holds no particle snapshot (nearest snapshots at t = " + num(before) +
                   " and " + num(after) + " s; snapshots span [" + num(series.front().time) + ", " +
                   num(lastT) +
                   "] s); widen the window to at least the snapshot interval (controlDict "
                   "writeInterval " +
                   num(in.scene.writeInterval) + " s)");
}

// A window whose snapshots all lack a solved fluid partner: Unpaired when generated, else an
// input error.
WindowState unpairedWindow(const PlannedWindow& p, const PlanInputs& in) {
  const TimeWindow& w = p.window;
  const ExtractSettings& s = in.settings;
  std::vector<double> t;
  for (size_t k : p.unpairedSnapshots) t.push_back(in.series[k].time);
  const std::string why = "window [" + num(w.t0) + ", " + num(w.t1) +
                          ") holds the snapshots t = " + timeList(t) +
                          " s, none paired with a solved fluid time within " + pairRule(s) + " (" +
                          in.fluid.nearestTo(t.front()) + " for t = " + num(t.front()) +
                          " s; the t = 0 fluid write is the unsolved initial state)";
  if (!s.windowsGenerated)
    throw InputError(w.origin + ": " + why + "; move the window, or raise " + s.pairToleranceWhere +
                     " (allowed range [0, " + num(0.5 * in.scene.writeInterval) +
                     "] s, half controlDict writeInterval)");
  return WindowState::Unpaired;
}

PlannedWindow planWindow(const TimeWindow& w, const PlanInputs& in,
                         const std::vector<std::pair<double, double>>& stored) {
  const std::vector<SnapshotEntry>& series = in.series;
  const FluidPairing& fluid = in.fluid;
  const double tol = in.settings.timeTolerance, pairTol = in.settings.pairTolerance;
  PlannedWindow p;
  p.window = w;
  for (const auto& [a, b] : stored)
    if (sameTime(a, w.t0) && sameTime(b, w.t1)) p.state = WindowState::Present;
  if (p.state == WindowState::Present) return p;
  std::vector<size_t> inWindow;
  for (size_t k = 0; k < series.size(); ++k)
    if (series[k].time >= w.t0 - tol && series[k].time < w.t1 - tol) inWindow.push_back(k);
  for (size_t k : inWindow) {
    if (!fluid.present) {
      p.snapshots.push_back(k);
    } else if (fluid.partner[k] >= 0) {
      p.snapshots.push_back(k);
      p.fluidTimes.push_back(fluid.solved[fluid.partner[k]]);
    } else {
      p.unpairedSnapshots.push_back(k);
    }
  }
  for (size_t f = 0; f < fluid.solved.size(); ++f)
    if (!fluid.paired[f] && fluid.solved[f] >= w.t0 - tol && fluid.solved[f] < w.t1 - tol)
      p.unpairedFluid.push_back(fluid.solved[f]);
  const bool particlesDone = in.finished || series.back().time >= w.t1 - tol;
  // A snapshot's pairing is final once the fluid has passed it by its partner's gap (a later
  // fluid time would be farther) or, unpaired, by pairTolerance.
  bool fluidDone = !fluid.present || in.finished;
  if (!fluidDone && !fluid.solved.empty()) {
    fluidDone = true;
    for (size_t k : inWindow) {
      const double reach = fluid.partner[k] >= 0
                               ? std::fabs(fluid.solved[fluid.partner[k]] - series[k].time)
                               : pairTol;
      fluidDone = fluidDone && fluid.solved.back() >= series[k].time + reach - 1e-12;
    }
  }
  if (!particlesDone || !fluidDone)
    p.state = WindowState::Deferred;
  else if (inWindow.empty())
    p.state = emptyWindow(w, in);
  else if (p.snapshots.empty())
    p.state = unpairedWindow(p, in);
  return p;
}

// Throws InputError when every window is after the end of the case or without a pair.
void checkSomeWindowUsable(const std::vector<PlannedWindow>& plans, const PlanInputs& in) {
  const ExtractSettings& s = in.settings;
  const std::vector<SnapshotEntry>& series = in.series;
  const double lastT = series.back().time;
  const int skipped = countWindows(plans, WindowState::Skipped);
  const int unpaired = countWindows(plans, WindowState::Unpaired);
  const int usable = static_cast<int>(plans.size()) - skipped - unpaired;
  if (usable == 0 && skipped > 0)
    throw InputError(s.windowStartWhere + ": every window (" + num(s.windows.front().t0) +
                     " s to " + num(s.windows.back().t1) +
                     " s) starts after the last snapshot (t = " + num(lastT) +
                     " s) of the finished case; allowed range of windows.start [" +
                     num(series.front().time) + ", " + num(lastT) + ") s");
  const std::vector<double>& solved = in.fluid.solved;
  if (usable == 0 && unpaired > 0)
    throw InputError(s.pairToleranceWhere + ": no window holds a snapshot paired with a solved " +
                     "fluid time within " + num(s.pairTolerance) + " s (snapshots t = " +
                     num(series.front().time) + " to " + num(lastT) + " s; solved fluid times " +
                     (solved.empty() ? std::string("none")
                                     : num(solved.front()) + " to " + num(solved.back()) + " s") +
                     "); allowed range [0, " + num(0.5 * in.scene.writeInterval) +
                     "] s (half controlDict writeInterval)");
}

}  // namespace

std::string FluidPairing::nearestTo(double t) const {
  if (solved.empty()) return "no solved fluid time";
  const double f = solved[nearestIndex(
      solved.size(), [&](size_t i) { return solved[i]; }, t)];
  return "nearest solved fluid time " + num(f) + " s, " + num(std::fabs(f - t)) + " s away";
}

FluidPairing pairFluidTimes(const FluidSource* fluid, const std::vector<SnapshotEntry>& series,
                            double timeTolerance, double pairTolerance) {
  FluidPairing out;
  out.present = fluid != nullptr;
  // Solved fluid times only: the write at t = 0 (the gate opening) is the initial state before
  // the first step (p = -rho g y, U = 0), so it is left out.
  if (fluid)
    for (double t : fluid->times()) (t <= timeTolerance ? out.initial : out.solved).push_back(t);
  const size_t ns = series.size();
  auto snapTime = [&](size_t k) { return series[k].time; };
  out.partner.assign(ns, -1);
  out.paired.assign(out.solved.size(), 0);
  for (size_t f = 0; f < out.solved.size(); ++f) {
    const size_t k = nearestIndex(ns, snapTime, out.solved[f]);
    const double gap = std::fabs(out.solved[f] - series[k].time);
    if (gap > pairTolerance + 1e-12 * std::max(1.0, out.solved[f])) continue;
    if (out.partner[k] < 0 || gap < std::fabs(out.solved[out.partner[k]] - series[k].time))
      out.partner[k] = static_cast<long>(f);
  }
  for (size_t k = 0; k < ns; ++k)
    if (out.partner[k] >= 0) out.paired[out.partner[k]] = 1;
  return out;
}

std::vector<PlannedWindow> planWindows(const PlanInputs& in,
                                       const std::vector<std::pair<double, double>>& stored) {
  std::vector<PlannedWindow> plans;
  for (const TimeWindow& w : in.settings.windows) plans.push_back(planWindow(w, in, stored));
  checkSomeWindowUsable(plans, in);
  return plans;
}

int countWindows(const std::vector<PlannedWindow>& plans, WindowState state) {
  return static_cast<int>(std::count_if(plans.begin(), plans.end(),
                                        [&](const PlannedWindow& p) { return p.state == state; }));
}

void logPlan(std::ostream& log, const std::vector<PlannedWindow>& plans, const PlanInputs& in) {
  const std::string warn = "[mixflowExtract] warning: ";
  const double tol = in.settings.timeTolerance;
  const std::string rule = pairRule(in.settings);
  if (in.fluid.present && !in.fluid.initial.empty())
    log << "[mixflowExtract] the fluid write at t = " << num(in.fluid.initial.front())
        << " s is the initial state before the first step and is not averaged; windows average "
           "snapshots paired with solved fluid times within "
        << num(in.settings.pairTolerance) << " s" << std::endl;
  for (const PlannedWindow& p : plans) {
    const std::string win = "window [" + num(p.window.t0) + ", " + num(p.window.t1) + ")";
    if (p.state == WindowState::Unpaired) {
      log << warn << win << ": no snapshot pairs with a solved fluid time within " << rule
          << "; not extracted" << std::endl;
      continue;
    }
    if (p.state != WindowState::Ready) continue;
    std::vector<double> lone;
    for (size_t k : p.unpairedSnapshots)
      if (in.series[k].time > tol) lone.push_back(in.series[k].time);  // t = 0: said above
    if (!lone.empty())
      log << warn << win << ": snapshots t = " << timeList(lone)
          << " s have no solved fluid time within " << rule << " (" << in.fluid.nearestTo(lone[0])
          << " for t = " << num(lone[0]) << " s); left out, the window averages "
          << p.snapshots.size() << " paired snapshots" << std::endl;
    if (!p.unpairedFluid.empty())
      log << warn << win << ": fluid times t = " << timeList(p.unpairedFluid)
          << " s pair with no snapshot within " << rule << "; not averaged" << std::endl;
  }
  const int skipped = countWindows(plans, WindowState::Skipped);
  if (skipped > 0) {
    double a = 0, b = 0;
    for (const PlannedWindow& p : plans)
      if (p.state == WindowState::Skipped) {
        if (b == 0) a = p.window.t0;
        b = p.window.t1;
      }
    log << warn << skipped << " windows in [" << num(a) << ", " << num(b)
        << ") s start after the last snapshot (t = " << num(in.series.back().time)
        << " s) of the finished case and are not extracted (windows end at " << num(b)
        << " s: windows.end, default controlDict endTime " << num(in.scene.endTime) << " s)"
        << std::endl;
  }
}

void listWindows(std::ostream& log, const std::vector<PlannedWindow>& plans,
                 const std::string& h5) {
  for (const PlannedWindow& p : plans) {
    log << "  window [" << num(p.window.t0) << ", " << num(p.window.t1) << "): ";
    if (p.state == WindowState::Present)
      log << "already in " << h5;
    else if (p.state == WindowState::Deferred)
      log << "waiting for data";
    else if (p.state == WindowState::Skipped)
      log << "after the end of the case";
    else if (p.state == WindowState::Unpaired)
      log << "no snapshot paired with a solved fluid time";
    else
      log << p.snapshots.size() << " snapshots, " << p.fluidTimes.size() << " fluid times";
    log << "\n";
  }
}

}  // namespace mixflow::mx
