// Which time windows a run extracts, and from which snapshots and fluid times. Each solved fluid
// time pairs with its nearest snapshot when at most pairTolerance away (a snapshot keeps the
// nearest of the fluid times that chose it); with fluid data a window averages its paired
// snapshots and their fluid times only, without it every snapshot in the window.
#pragma once

#include <iosfwd>
#include <string>
#include <utility>
#include <vector>

#include "ExtractSettings.h"
#include "FluidSource.h"
#include "SnapshotSeries.h"

namespace mixflow::dem {
struct Scene;
}

namespace mixflow::mx {

// The fluid's times split into the initial state and the solved ones, and their snapshot partners.
struct FluidPairing {
  bool present = false;         // the case has fluid data
  std::vector<double> solved;   // fluid times after t = 0 (within timeTolerance), ascending
  std::vector<double> initial;  // the write at t = 0: the state before the first step
  std::vector<long> partner;    // per snapshot: index into `solved`, or -1
  std::vector<char> paired;     // per solved time: a snapshot kept it
  // "nearest solved fluid time <t> s, <d> s away" (or "no solved fluid time"), for messages.
  std::string nearestTo(double t) const;
};

// fluid: null without fluid data.
FluidPairing pairFluidTimes(const FluidSource* fluid, const std::vector<SnapshotEntry>& series,
                            double timeTolerance, double pairTolerance);

enum class WindowState { Present, Ready, Deferred, Skipped, Unpaired };

struct PlannedWindow {
  TimeWindow window;
  WindowState state = WindowState::Ready;
  std::vector<size_t> snapshots;   // indices into the series (paired ones when there is fluid)
  std::vector<double> fluidTimes;  // the snapshots' fluid partners, in the same order
  std::vector<size_t> unpairedSnapshots;  // in the window, without a solved fluid time
  std::vector<double> unpairedFluid;      // solved fluid times in the window without a snapshot
};

// What the windows are planned from.
struct PlanInputs {
  const ExtractSettings& settings;
  const dem::Scene& scene;                   // writeInterval and endTime, for the messages
  const std::vector<SnapshotEntry>& series;  // not empty
  const FluidPairing& fluid;
  bool finished = false;  // the DEM wrote postProcessing/dem/summary.json
};

// The settings' windows in their order: Present (among `stored`, the output file's windows),
// Deferred (a snapshot or fluid time may still come), Skipped (generated, starting after the last
// snapshot of a finished case), Unpaired (generated, no snapshot paired), else Ready. Throws
// InputError naming the entry for a listed window without snapshots or pairs, and when no window
// can ever be extracted.
std::vector<PlannedWindow> planWindows(const PlanInputs& in,
                                       const std::vector<std::pair<double, double>>& stored);

int countWindows(const std::vector<PlannedWindow>& plans, WindowState state);

// The pairing as the windows use it: the t = 0 fluid write left out, snapshots and fluid times
// without a partner, windows without a pair or after the end of the case.
void logPlan(std::ostream& log, const std::vector<PlannedWindow>& plans, const PlanInputs& in);

// One line per window: what a run does with it (-check).
void listWindows(std::ostream& log, const std::vector<PlannedWindow>& plans, const std::string& h5);

}  // namespace mixflow::mx
