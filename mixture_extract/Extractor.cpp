#include "Extractor.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <future>
#include <iostream>
#include <sstream>

#include "AveragingGrid.h"
#include "BinAccumulator.h"
#include "CoarseGrainKernel.h"
#include "ContactDumps.h"
#include "ContactSnapshot.h"
#include "Dictionary.h"
#include "ExtractSettings.h"
#include "H5Output.h"
#include "H5WindowReader.h"
#include "Scene.h"
#include "SnapshotSeries.h"
#include "TextOutputs.h"
#include "WindowResult.h"

#ifndef MIXFLOW_VERSION
#define MIXFLOW_VERSION "unknown"
#endif

namespace mixflow::mx {

namespace fs = std::filesystem;

namespace {

std::string num(double v) { return formatNumber(v, 8); }

enum class WindowState { Present, Ready, Deferred, Skipped, Unpaired };

struct Plan {
  TimeWindow window;
  WindowState state = WindowState::Ready;
  std::vector<size_t> snapshots;   // indices into the series (paired ones when there is fluid)
  std::vector<double> fluidTimes;  // the snapshots' fluid partners, in the same order
  std::vector<size_t> unpairedSnapshots;  // in the window, without a solved fluid time
  std::vector<double> unpairedFluid;      // solved fluid times in the window without a snapshot
};

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

}  // namespace

bool stressHasKineticTerm(const std::string& caseDir, const std::string& setting) {
  if (setting == "included") return true;
  if (setting == "excluded") return false;
  const std::string path = (fs::path(caseDir) / "dem" / "in.liggghts").string();
  std::ifstream in(path);
  if (!in)
    throw InputError(path +
                     ": cannot open file, so it is unknown whether c_pstress holds the "
                     "kinetic term; set particles { stressKineticTerm included; } (plain "
                     "`compute pstress all stress/atom`) or excluded in system/extractDict");
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::string cmd, id, group, style;
    ls >> cmd >> id >> group >> style;
    if (cmd != "compute" || id != "pstress" || style != "stress/atom") continue;
    std::string kw;
    bool any = false, ke = false;
    while (ls >> kw) {
      if (kw[0] == '#') break;
      any = true;
      ke = ke || kw == "ke";
    }
    return !any || ke;
  }
  throw InputError(path +
                   ": no `compute pstress all stress/atom` line; set particles { "
                   "stressKineticTerm included|excluded; } in system/extractDict");
}

Extractor::Extractor(ExtractOptions options, std::ostream& log)
    : opt_(std::move(options)), log_(log) {}

ExtractReport Extractor::run() {
  const auto wall0 = std::chrono::steady_clock::now();
  const dem::Scene scene = dem::Scene::read(opt_.caseDir);
  const std::string dictFile = opt_.dictFile.empty()
                                   ? (fs::path(opt_.caseDir) / "system" / "extractDict").string()
                                   : opt_.dictFile;
  const ExtractSettings s = ExtractSettings::read(dictFile, scene);
  const AveragingGrid grid(s.x0, s.x1, s.nx, s.y0, s.y1, s.ny, scene.sample.width);
  const std::vector<SnapshotEntry> series = readSnapshotSeries(opt_.caseDir);
  if (series.empty())
    throw InputError((fs::path(opt_.caseDir) / "VTK" / "particles.vtk.series").string() +
                     ": lists no snapshot yet");
  const bool kinetic = stressHasKineticTerm(opt_.caseDir, s.stressKineticTerm);

  std::shared_ptr<FluidSource> fluid = fluid_;
  if (!fluid && s.fluidSource != "none") {
    const bool there = FoamFluidSource::present(opt_.caseDir, s.fluidNames);
    if (s.fluidSource == "openfoam" && !there)
      throw InputError(dictFile + ": entry 'fluid.source' is openfoam but " + opt_.caseDir +
                       " has no time directory with field '" + s.fluidNames.velocity + "'");
    if (there) fluid = std::make_shared<FoamFluidSource>(opt_.caseDir, s.fluidNames);
  }
  if (fluid && s.wantDensity() && !(s.liquidDensity > 0))
    throw InputError(dictFile + ": entry 'liquidDensity' is needed (allowed range > 0 kg/m3): " +
                     "pressureConvention " + s.pressureConvention +
                     " divides p_f by the liquid's density, and " + scene.caseDir +
                     "/constant/sceneProperties (content " + scene.content +
                     ") has no liquid.density; give liquidDensity, or pressureConvention raw");
  const bool finished = fs::exists(fs::path(opt_.caseDir) / "postProcessing/dem/summary.json");
  const double tol = s.timeTolerance, pairTol = s.pairTolerance;
  const double lastT = series.back().time;

  // Solved fluid times only: the write at t = 0 (the gate opening) is the initial state before
  // the first step (p = -rho g y, U = 0), so it is left out.
  std::vector<double> fluidTimes, initialFluid;
  if (fluid)
    for (double t : fluid->times()) (t <= tol ? initialFluid : fluidTimes).push_back(t);
  // A finished run with the initial fluid state alone wrote no fluid fields: nothing to pair.
  if (fluid && fluidTimes.empty() && finished)
    throw InputError(
        opt_.caseDir + ": the fluid fields are missing: the run finished (" +
        (fs::path(opt_.caseDir) / "postProcessing/dem/summary.json").string() +
        ") but its only fluid write is the initial state at t = 0 (" + fluid->describe() +
        "); a parallel run's fields are in processor*/ until reconstructPar joins them. Run the "
        "fluid solver (or reconstructPar -case " +
        opt_.caseDir + "), or extract the particles alone with fluid { source none; } in " +
        dictFile);
  // Each solved fluid time pairs with its nearest snapshot when at most pairTolerance away; a
  // snapshot keeps the nearest of the fluid times that chose it.
  const size_t ns = series.size();
  auto snapTime = [&](size_t k) { return series[k].time; };
  std::vector<long> partner(ns, -1);  // index into fluidTimes
  std::vector<char> fluidPaired(fluidTimes.size(), 0);
  for (size_t f = 0; f < fluidTimes.size(); ++f) {
    const size_t k = nearestIndex(ns, snapTime, fluidTimes[f]);
    const double gap = std::fabs(fluidTimes[f] - series[k].time);
    if (gap > pairTol + 1e-12 * std::max(1.0, fluidTimes[f])) continue;
    if (partner[k] < 0 || gap < std::fabs(fluidTimes[partner[k]] - series[k].time))
      partner[k] = static_cast<long>(f);
  }
  for (size_t k = 0; k < ns; ++k)
    if (partner[k] >= 0) fluidPaired[partner[k]] = 1;
  auto nearestFluid = [&](double t) -> std::string {
    if (fluidTimes.empty()) return "no solved fluid time";
    const double f = fluidTimes[nearestIndex(
        fluidTimes.size(), [&](size_t i) { return fluidTimes[i]; }, t)];
    return "nearest solved fluid time " + num(f) + " s, " + num(std::fabs(f - t)) + " s away";
  };

  std::string base = opt_.output.empty() ? s.output : opt_.output;
  if (fs::path(base).is_relative()) base = (fs::path(opt_.caseDir) / base).string();
  ExtractReport rep;
  rep.h5 = base + ".h5";
  rep.xdmf = base + ".xdmf";
  rep.csv = base + "_regions.csv";

  // Existing windows, checked read-only against the settings before anything is written.
  std::vector<std::pair<double, double>> existing;
  if (fs::exists(rep.h5) && !opt_.overwrite) existing = existingWindows(rep.h5, s);

  const std::string pairRule = "pairTolerance " + num(pairTol) + " s";
  std::vector<Plan> plans;
  for (const TimeWindow& w : s.windows) {
    Plan p;
    p.window = w;
    for (const auto& [a, b] : existing)
      if (sameTime(a, w.t0) && sameTime(b, w.t1)) p.state = WindowState::Present;
    if (p.state == WindowState::Present) {
      plans.push_back(p);
      continue;
    }
    std::vector<size_t> inWindow;
    for (size_t k = 0; k < ns; ++k)
      if (series[k].time >= w.t0 - tol && series[k].time < w.t1 - tol) inWindow.push_back(k);
    for (size_t k : inWindow) {
      if (!fluid) {
        p.snapshots.push_back(k);
      } else if (partner[k] >= 0) {
        p.snapshots.push_back(k);
        p.fluidTimes.push_back(fluidTimes[partner[k]]);
      } else {
        p.unpairedSnapshots.push_back(k);
      }
    }
    for (size_t f = 0; f < fluidTimes.size(); ++f)
      if (!fluidPaired[f] && fluidTimes[f] >= w.t0 - tol && fluidTimes[f] < w.t1 - tol)
        p.unpairedFluid.push_back(fluidTimes[f]);
    const bool particlesDone = finished || lastT >= w.t1 - tol;
    // A snapshot's pairing is final once the fluid has passed it by its partner's gap (a later
    // fluid time would be farther) or, unpaired, by pairTolerance.
    bool fluidDone = !fluid || finished;
    if (!fluidDone && !fluidTimes.empty()) {
      fluidDone = true;
      for (size_t k : inWindow) {
        const double reach =
            partner[k] >= 0 ? std::fabs(fluidTimes[partner[k]] - series[k].time) : pairTol;
        fluidDone = fluidDone && fluidTimes.back() >= series[k].time + reach - 1e-12;
      }
    }
    if (!particlesDone || !fluidDone) {
      p.state = WindowState::Deferred;
    } else if (inWindow.empty()) {
      if (w.t0 - tol > lastT) {
        if (!s.windowsGenerated)
          throw InputError(w.origin + ": window (" + num(w.t0) + " " + num(w.t1) +
                           ") starts after the last snapshot (t = " + num(lastT) +
                           " s) of a finished case; available snapshots span [" +
                           num(series.front().time) + ", " + num(lastT) + "] s");
        p.state = WindowState::Skipped;
      } else {
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
                         " and " + num(after) + " s; snapshots span [" + num(series.front().time) +
                         ", " + num(lastT) +
                         "] s); widen the window to at least the snapshot interval (controlDict "
                         "writeInterval " +
                         num(scene.writeInterval) + " s)");
      }
    } else if (p.snapshots.empty()) {
      std::vector<double> t;
      for (size_t k : p.unpairedSnapshots) t.push_back(series[k].time);
      const std::string why = "window [" + num(w.t0) + ", " + num(w.t1) +
                              ") holds the snapshots t = " + timeList(t) +
                              " s, none paired with a solved fluid time within " + pairRule + " (" +
                              nearestFluid(t.front()) + " for t = " + num(t.front()) +
                              " s; the t = 0 fluid write is the unsolved initial state)";
      if (!s.windowsGenerated)
        throw InputError(w.origin + ": " + why + "; move the window, or raise " +
                         s.pairToleranceWhere + " (allowed range [0, " +
                         num(0.5 * scene.writeInterval) + "] s, half controlDict writeInterval)");
      p.state = WindowState::Unpaired;
    }
    plans.push_back(p);
  }
  // Every snapshot to be read exists (its contents are checked when it is read).
  for (const Plan& p : plans)
    if (p.state == WindowState::Ready)
      for (size_t k : p.snapshots)
        if (!snapshotExists(series[k]))
          throw InputError(series[k].file +
                           ": cannot open file (missing or unreadable; listed in " +
                           (fs::path(opt_.caseDir) / "VTK" / "particles.vtk.series").string() +
                           " for t = " + num(series[k].time) + " s)");
  // Contact stress along the contact lines when the snapshots to read have their contact files.
  std::string lacking;  // the first snapshot to read without its contact files
  for (const Plan& p : plans)
    if (p.state == WindowState::Ready)
      for (size_t k : p.snapshots)
        if (lacking.empty() && !contactSnapshotExists(series[k].file))
          lacking = dem::pairContactPath(series[k].file);
  const bool allContacts = lacking.empty();
  if (s.stressSource == "contacts" && !allContacts)
    throw InputError(
        dictFile + ": entry 'particles.stress' is contacts but snapshots lack their " +
        "contact files VTK/contacts/pairs_<step>.txt and walls_<step>.txt (first: " + lacking +
        "; run the DEM with demDict contactSnapshots on), or set it to " + "virial or auto");
  const bool useContacts =
      s.stressSource == "contacts" || (s.stressSource == "auto" && allContacts);
  const std::vector<dem::WallPlane> walls = dem::wallPlanes(scene);
  const CoarseGrainKernel kernel(grid, s.kernelShape, s.kernelWidthMetres);
  const double periodicWidth = scene.channel.sideWalls == "periodic" ? scene.sample.width : 0.0;
  for (const Plan& p : plans) {
    if (p.state == WindowState::Present) ++rep.present;
    if (p.state == WindowState::Deferred) ++rep.deferred;
    if (p.state == WindowState::Skipped) ++rep.skipped;
    if (p.state == WindowState::Unpaired) ++rep.unpaired;
  }
  const int usable = static_cast<int>(plans.size()) - rep.skipped - rep.unpaired;
  if (usable == 0 && rep.skipped > 0)
    throw InputError(s.windowStartWhere + ": every window (" + num(s.windows.front().t0) +
                     " s to " + num(s.windows.back().t1) +
                     " s) starts after the last snapshot (t = " + num(lastT) +
                     " s) of the finished case; allowed range of windows.start [" +
                     num(series.front().time) + ", " + num(lastT) + ") s");
  if (usable == 0 && rep.unpaired > 0)
    throw InputError(
        s.pairToleranceWhere + ": no window holds a snapshot paired with a solved " +
        "fluid time within " + num(pairTol) + " s (snapshots t = " + num(series.front().time) +
        " to " + num(lastT) + " s; solved fluid times " +
        (fluidTimes.empty() ? std::string("none")
                            : num(fluidTimes.front()) + " to " + num(fluidTimes.back()) + " s") +
        "); allowed range [0, " + num(0.5 * scene.writeInterval) +
        "] s (half controlDict writeInterval)");

  RootAttributes attrs;
  attrs.text = {
      {"mixflow_version", MIXFLOW_VERSION},
      {"program", "mixflowExtract"},
      {"case_dir", fs::absolute(opt_.caseDir).lexically_normal().string()},
      {"case_name", scene.name},
      {"content", scene.content},
      {"channel_side_walls", scene.channel.sideWalls},
      {"extract_dict_file", dictFile},
      {"extract_dict", s.dictText},
      {"coordinates",
       "x along the channel, y vertical up, z across the width; fields averaged across the width"},
      {"pressure_convention",
       s.pressureConvention + " (raw: lambda_p = p_f / p_s; density: lambda_p = (p_f / rho_f) / "
                              "(p_s / rho_s), the paper's convention; names carry _raw/_density)"},
      {"liquid_density_source", s.liquidDensitySource},
      {"particle_source",
       "LIGGGHTS dump custom/vtk snapshots VTK/particles.vtk.series (their binary dump twins "
       "particles_<step>.bin where written): x y z, v, mass, radius, "
       "c_pstress[1-6] (compute stress/atom, stress x volume, N m)"},
      {"particle_stress",
       useContacts
           ? std::string(
                 "contact stress -sum f (x) b over the contacts of the contact snapshots "
                 "(VTK/contacts: compute pair/gran/local, fix wall/gran store_force), b the "
                 "branch vector centre to centre (to the contact point for a wall), shared "
                 "along the contact line by the kernel; streaming part -sum w m v' v' with v' "
                 "about the coarse-grained velocity at the bin")
           : std::string("contact stress x volume C_i = c_pstress_i") +
                 (kinetic ? " + m_i v_i v_i (the dumped compute includes the kinetic term -m v v)"
                          : " (the dumped compute has no kinetic term)") +
                 "; LIGGGHTS pair virial shared half per particle of each contact; wall "
                 "contacts (fix wall/gran) carry no per-atom virial, so bins touching a wall "
                 "miss the wall-contact stress; streaming part -sum w m v' v' with v' about the "
                 "coarse-grained velocity at the bin"},
      {"stress_source", useContacts ? "contacts" : "virial"},
      {"kernel", s.kernelShape},
      {"particle_binning",
       "exact sphere / bin volumes (closed-form corner function, mixture_extract/"
       "SphereBinVolume.h); each particle's velocity, mass and stress are split in the same "
       "proportion"},
      {"fluid_source", fluid ? fluid->describe() : std::string("none (no fluid data)")},
      {"fluid_binning",
       "cells binned by centre with weight alpha_l eps_f V (the cell's liquid volume); saturation "
       "= sum alpha_l eps_f V / sum eps_f V"},
      {"fluid_times",
       "solved fluid times only: the t = 0 write (the initial state before the first step, p = "
       "-rho g y) is left out. Each solved fluid time pairs with its nearest particle snapshot "
       "when at most pair_tolerance_s away (a snapshot keeps the nearest); with fluid data a "
       "window averages its paired snapshots and their fluid times only, so both phases are "
       "sampled at the same instants (the t = 0 snapshot has no solved partner and is left "
       "out); /windows/max_pair_gap gives the largest offset"},
      {"stress_kinetic_term", kinetic ? "included" : "excluded"},
  };
  attrs.numbers = {
      {"sample_length_m", scene.sample.length},
      {"sample_height_m", scene.sample.height},
      {"sample_width_m", scene.sample.width},
      {"sample_solid_fraction", scene.sample.solidFraction},
      {"channel_length_m", scene.channel.length},
      {"channel_height_m", scene.channel.height},
      {"particle_diameter_m", scene.particles.diameter},
      {"particle_density_kg_m3", scene.particles.density},
      {"young_modulus_factor", scene.dem.youngModulusFactor},
      {"dem_time_step_s", scene.timeStepUsed()},
      {"end_time_s", scene.endTime},
      {"write_interval_s", scene.writeInterval},
      {"time_tolerance_s", tol},
      {"pair_tolerance_s", pairTol},
      {"kernel_width_m", s.kernelShape == "bins" ? 0.0 : s.kernelWidthMetres},
      {"threshold_min_velocity_m_s", s.thresholds.minVelocity},
      {"threshold_min_pressure_pa", s.thresholds.minPressure},
      {"threshold_min_solid_fraction", s.thresholds.minSolidFraction},
      {"threshold_min_saturation", s.thresholds.minSaturation},
      {"threshold_min_denominator", s.thresholds.minDenominator},
      {"threshold_min_particle_samples", static_cast<double>(s.thresholds.minParticleSamples)},
      {"threshold_min_liquid_share", s.thresholds.minLiquidShare},
  };
  if (s.liquidDensity > 0) attrs.numbers.push_back({"liquid_density_kg_m3", s.liquidDensity});
  if (s.haveViscosities) {
    attrs.numbers.push_back({"nu_solid_m2_s", s.nuSolid});
    attrs.numbers.push_back({"nu_fluid_m2_s", s.nuFluid});
  }

  log_ << "[mixflowExtract] case " << scene.name << ": " << series.size() << " snapshots in ["
       << num(series.front().time) << ", " << num(lastT) << "] s"
       << (finished ? " (finished)" : " (running or stopped without summary)") << "; grid " << s.nx
       << " x " << s.ny << " bins of " << num(grid.dx()) << " x " << num(grid.dy()) << " x "
       << num(grid.width()) << " m; fluid: "
       << (fluid ? fluid->describe() + " (" + std::to_string(fluidTimes.size()) + " solved times)"
                 : std::string("none"))
       << std::endl;
  const std::string warn = "[mixflowExtract] warning: ";
  // The virial route is a documented choice, so falling back to it is said, not warned about.
  log_ << "[mixflowExtract] kernel " << s.kernelShape;
  if (!kernel.exactBins()) log_ << " of width " << num(s.kernelWidthMetres) << " m";
  log_ << "; contact stress from "
       << (useContacts ? "the contact snapshots (VTK/contacts), walls included"
                       : "each particle's stress/atom virial, without the wall contacts (bins at a "
                         "wall miss their share; the contact-line stress needs the DEM run with "
                         "demDict contactSnapshots on)")
       << std::endl;
  if (!s.liquidDensityWarning.empty())
    log_ << warn << s.liquidDensityWarning << " (the extractDict entry wins)" << std::endl;
  if (fluid && !initialFluid.empty())
    log_ << "[mixflowExtract] the fluid write at t = " << num(initialFluid.front())
         << " s is the initial state before the first step and is not averaged; windows average "
            "snapshots paired with solved fluid times within "
         << num(pairTol) << " s" << std::endl;
  for (const Plan& p : plans) {
    const std::string win = "window [" + num(p.window.t0) + ", " + num(p.window.t1) + ")";
    if (p.state == WindowState::Unpaired) {
      log_ << warn << win << ": no snapshot pairs with a solved fluid time within " << pairRule
           << "; not extracted" << std::endl;
      continue;
    }
    if (p.state != WindowState::Ready) continue;
    std::vector<double> lone;
    for (size_t k : p.unpairedSnapshots)
      if (series[k].time > tol) lone.push_back(series[k].time);  // t = 0: said above
    if (!lone.empty())
      log_ << warn << win << ": snapshots t = " << timeList(lone)
           << " s have no solved fluid time within " << pairRule << " (" << nearestFluid(lone[0])
           << " for t = " << num(lone[0]) << " s); left out, the window averages "
           << p.snapshots.size() << " paired snapshots" << std::endl;
    if (!p.unpairedFluid.empty())
      log_ << warn << win << ": fluid times t = " << timeList(p.unpairedFluid)
           << " s pair with no snapshot within " << pairRule << "; not averaged" << std::endl;
  }
  if (rep.skipped > 0) {
    double a = 0, b = 0;
    for (const Plan& p : plans)
      if (p.state == WindowState::Skipped) {
        if (b == 0) a = p.window.t0;
        b = p.window.t1;
      }
    log_ << warn << rep.skipped << " windows in [" << num(a) << ", " << num(b)
         << ") s start after the last snapshot (t = " << num(lastT)
         << " s) of the finished case and are not extracted (windows end at " << num(b)
         << " s: windows.end, default controlDict endTime " << num(scene.endTime) << " s)"
         << std::endl;
  }
  if (opt_.checkOnly) {
    for (const Plan& p : plans) {
      log_ << "  window [" << num(p.window.t0) << ", " << num(p.window.t1) << "): ";
      if (p.state == WindowState::Present)
        log_ << "already in " << rep.h5;
      else if (p.state == WindowState::Deferred)
        log_ << "waiting for data";
      else if (p.state == WindowState::Skipped)
        log_ << "after the end of the case";
      else if (p.state == WindowState::Unpaired)
        log_ << "no snapshot paired with a solved fluid time";
      else
        log_ << p.snapshots.size() << " snapshots, " << p.fluidTimes.size() << " fluid times";
      log_ << "\n";
    }
    return rep;
  }

  H5Output out(rep.h5, grid, s, attrs, opt_.overwrite);
  double readSecs = 0;
  long binaryRead = 0;  // of rep.snapshotsRead, read from their binary twins
  for (const Plan& p : plans) {
    if (p.state != WindowState::Ready) continue;
    BinAccumulator acc(grid, kernel, kinetic, periodicWidth);
    const int threads = std::max(1, opt_.threads);
    using Read = std::pair<ParticleSnapshot, ContactSnapshot>;
    for (size_t b = 0; b < p.snapshots.size(); b += threads) {
      std::vector<std::future<Read>> jobs;
      for (size_t k = b; k < std::min(p.snapshots.size(), b + threads); ++k) {
        const SnapshotEntry& e = series[p.snapshots[k]];
        jobs.push_back(std::async(
            threads > 1 ? std::launch::async : std::launch::deferred, [e, useContacts, &walls] {
              return Read{readSnapshot(e),
                          useContacts ? readContactSnapshot(e.file, walls) : ContactSnapshot{}};
            }));
      }
      for (auto& j : jobs) {
        // Time spent waiting for the snapshots (all of reading them with -threads 1).
        const auto r0 = std::chrono::steady_clock::now();
        Read read = j.get();
        const ParticleSnapshot& snap = read.first;
        readSecs += std::chrono::duration<double>(std::chrono::steady_clock::now() - r0).count();
        binaryRead += fs::path(snap.file).extension() == ".bin";
        acc.addSnapshot(snap, useContacts ? &read.second : nullptr);
        ++rep.snapshotsRead;
      }
    }
    for (double t : p.fluidTimes) acc.addFluid(fluid->cells(t));
    WindowResult res = finaliseWindow(p.window, acc, grid, s);
    if (!p.fluidTimes.empty()) {
      res.tFirstFluid = p.fluidTimes.front();
      res.tLastFluid = p.fluidTimes.back();
      res.maxPairGap = 0;
      for (size_t k = 0; k < p.snapshots.size(); ++k)
        res.maxPairGap =
            std::max(res.maxPairGap, std::fabs(p.fluidTimes[k] - series[p.snapshots[k]].time));
    }
    out.append(res);
    ++rep.written;
    long valid = 0;
    for (const auto& m : res.bins) valid += m.valid(fLambdaU);
    log_ << "[mixflowExtract] window [" << num(p.window.t0) << ", " << num(p.window.t1)
         << "): " << res.snapshots << " snapshots, " << res.fluidTimes << " fluid times";
    if (!p.fluidTimes.empty()) log_ << " (pairs at most " << num(res.maxPairGap) << " s apart)";
    log_ << ", " << num(res.particlesMean) << " particles, " << valid << " bins with valid lambda_u"
         << std::endl;
  }
  out.commit();
  try {
    const StoredOutput stored = readStoredOutput(rep.h5);
    writeXdmf(rep.xdmf, rep.h5, stored);
    writeRegionsCsv(rep.csv, stored);
  } catch (const std::exception& e) {
    throw IndexWriteError(std::string(e.what()) + "\n  " + rep.h5 + " holds the " +
                          std::to_string(rep.written) +
                          " new windows; run mixflowExtract again (nothing to add) to rewrite " +
                          rep.xdmf + " and " + rep.csv + " from it");
  }
  const double secs =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  log_ << "[mixflowExtract] " << rep.written << " new windows, " << rep.present
       << " already in the file, " << rep.deferred << " waiting for data, " << rep.skipped
       << " after the end of the case";
  if (rep.unpaired) log_ << ", " << rep.unpaired << " without paired fluid data";
  log_ << "; " << rep.snapshotsRead << " snapshots read (" << binaryRead << " binary) in "
       << num(secs) << " s (" << num(readSecs) << " s reading them)\n  " << rep.h5 << "\n  "
       << rep.xdmf << "\n  " << rep.csv << std::endl;
  return rep;
}

}  // namespace mixflow::mx
