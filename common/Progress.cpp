#include "Progress.h"

#include <cmath>
#include <cstdio>
#include <ostream>

namespace mixflow {

Progress::Progress(std::string label, double startTime, double endTime, std::ostream& out,
                   double minInterval)
    : label_(std::move(label)),
      start_(startTime),
      end_(endTime),
      out_(out),
      minInterval_(minInterval),
      t0_(std::chrono::steady_clock::now()),
      cpu0_(std::clock()) {}

double Progress::wallSeconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
}

double Progress::cpuSeconds() const {
  return static_cast<double>(std::clock() - cpu0_) / CLOCKS_PER_SEC;
}

std::string Progress::hms(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "--:--:--";
  const long s = std::lround(seconds);
  char buf[32];
  std::snprintf(buf, sizeof buf, "%02ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
  return buf;
}

void Progress::update(double simTime, bool force, const std::string& extra) {
  const double wall = wallSeconds();
  if (!force && wall - lastPrint_ < minInterval_) return;
  lastPrint_ = wall;
  const double done = (simTime - start_) / std::max(end_ - start_, 1e-300);
  const double eta = done > 0 ? wall * (1.0 - done) / done : NAN;
  char buf[256];
  std::snprintf(buf, sizeof buf, "[%s] t = %.4f s of %.4f s (%5.1f %%), wall %s, to finish %s",
                label_.c_str(), simTime, end_, 100.0 * std::min(done, 1.0), hms(wall).c_str(),
                hms(eta).c_str());
  out_ << buf << extra << std::endl;
}

}  // namespace mixflow
