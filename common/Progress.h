// Progress line for long runs: simulated time, wall time and an estimate to finish.
#pragma once

#include <chrono>
#include <ctime>
#include <iosfwd>
#include <string>

namespace mixflow {

class Progress {
 public:
  // Prints at most every minInterval wall seconds (and always on force / at the end).
  Progress(std::string label, double startTime, double endTime, std::ostream& out,
           double minInterval = 5.0);
  void update(double simTime, bool force = false, const std::string& extra = "");
  double wallSeconds() const;
  double cpuSeconds() const;  // this process's CPU since construction

  static std::string hms(double seconds);

 private:
  std::string label_;
  double start_, end_;
  std::ostream& out_;
  double minInterval_;
  double lastPrint_ = -1e300;
  std::chrono::steady_clock::time_point t0_;
  std::clock_t cpu0_;
};

}  // namespace mixflow
