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
#include "Dictionary.h"
#include "ExtractSettings.h"
#include "H5Output.h"
#include "ParticleSnapshot.h"
#include "Scene.h"
#include "TextOutputs.h"
#include "WindowResult.h"

#ifndef MIXFLOW_VERSION
#define MIXFLOW_VERSION "unknown"
#endif

namespace mixflow::mx {

namespace fs = std::filesystem;

namespace {

std::string num(double v) { return formatNumber(v, 8); }

enum class WindowState { Present, Ready, Deferred, Skipped };

struct Plan {
  TimeWindow window;
  WindowState state = WindowState::Ready;
  std::vector<size_t> snapshots;  // indices into the series
  std::vector<double> fluidTimes;
};

bool sameTime(double a, double b) {
  return std::fabs(a - b) <= 1e-12 * std::max(1.0, std::fabs(a));
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
  const std::vector<double> fluidTimes = fluid ? fluid->times() : std::vector<double>{};
  const bool finished = fs::exists(fs::path(opt_.caseDir) / "postProcessing/dem/summary.json");
  const double tol = s.timeTolerance;
  const double lastT = series.back().time;

  std::string base = opt_.output.empty() ? s.output : opt_.output;
  if (fs::path(base).is_relative()) base = (fs::path(opt_.caseDir) / base).string();
  ExtractReport rep;
  rep.h5 = base + ".h5";
  rep.xdmf = base + ".xdmf";
  rep.csv = base + "_regions.csv";

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
      {"particle_source",
       "LIGGGHTS dump custom/vtk snapshots VTK/particles.vtk.series: x y z, v, mass, radius, "
       "c_pstress[1-6] (compute stress/atom, stress x volume, N m)"},
      {"particle_stress",
       std::string("contact stress x volume C_i = c_pstress_i") +
           (kinetic ? " + m_i v_i v_i (the dumped compute includes the kinetic term -m v v)"
                    : " (the dumped compute has no kinetic term)") +
           "; LIGGGHTS pair virial shared half per particle of each contact; wall contacts (fix "
           "wall/gran) carry no per-atom virial, so bins touching a wall miss the wall-contact "
           "stress; streaming part -sum w m v' v' with v' about the snapshot's bin-mean velocity"},
      {"particle_binning",
       "exact sphere / bin volumes (closed-form corner function, mixture_extract/"
       "SphereBinVolume.h); each particle's velocity, mass and stress are split in the same "
       "proportion"},
      {"fluid_source", fluid ? fluid->describe() : std::string("none (no fluid data)")},
      {"fluid_binning",
       "cells binned by centre with weight alpha_l eps_f V (the cell's liquid volume); saturation "
       "= sum alpha_l eps_f V / sum eps_f V"},
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
      {"liquid_density_kg_m3", s.liquidDensity},
      {"time_tolerance_s", tol},
      {"threshold_min_velocity_m_s", s.thresholds.minVelocity},
      {"threshold_min_pressure_pa", s.thresholds.minPressure},
      {"threshold_min_solid_fraction", s.thresholds.minSolidFraction},
      {"threshold_min_saturation", s.thresholds.minSaturation},
      {"threshold_min_denominator", s.thresholds.minDenominator},
      {"threshold_min_particle_samples", static_cast<double>(s.thresholds.minParticleSamples)},
  };
  if (s.haveViscosities) {
    attrs.numbers.push_back({"nu_solid_m2_s", s.nuSolid});
    attrs.numbers.push_back({"nu_fluid_m2_s", s.nuFluid});
  }

  // Existing windows (an unchanged-settings check happens when the file is opened).
  std::unique_ptr<H5Output> out;
  if (!opt_.checkOnly) out = std::make_unique<H5Output>(rep.h5, grid, s, attrs, opt_.overwrite);

  std::vector<Plan> plans;
  for (const TimeWindow& w : s.windows) {
    Plan p;
    p.window = w;
    if (out)
      for (const auto& [a, b] : out->existingWindows())
        if (sameTime(a, w.t0) && sameTime(b, w.t1)) p.state = WindowState::Present;
    if (p.state == WindowState::Present) {
      plans.push_back(p);
      continue;
    }
    for (size_t k = 0; k < series.size(); ++k)
      if (series[k].time >= w.t0 - tol && series[k].time < w.t1 - tol) p.snapshots.push_back(k);
    for (double t : fluidTimes)
      if (t >= w.t0 - tol && t < w.t1 - tol) p.fluidTimes.push_back(t);
    const bool particlesDone = finished || lastT >= w.t1 - tol;
    const bool fluidDone =
        !fluid || finished || (!fluidTimes.empty() && fluidTimes.back() >= w.t1 - tol);
    if (!particlesDone || !fluidDone) {
      p.state = WindowState::Deferred;
    } else if (p.snapshots.empty()) {
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
    }
    plans.push_back(p);
  }

  log_ << "[mixflowExtract] case " << scene.name << ": " << series.size() << " snapshots in ["
       << num(series.front().time) << ", " << num(lastT) << "] s"
       << (finished ? " (finished)" : " (running or stopped without summary)") << "; grid " << s.nx
       << " x " << s.ny << " bins of " << num(grid.dx()) << " x " << num(grid.dy()) << " x "
       << num(grid.width()) << " m; fluid: "
       << (fluid ? fluid->describe() + " (" + std::to_string(fluidTimes.size()) + " times)"
                 : std::string("none"))
       << std::endl;
  for (const Plan& p : plans) {
    if (p.state == WindowState::Present) ++rep.present;
    if (p.state == WindowState::Deferred) ++rep.deferred;
    if (p.state == WindowState::Skipped) ++rep.skipped;
  }
  if (opt_.checkOnly) {
    for (const Plan& p : plans)
      log_ << "  window [" << num(p.window.t0) << ", " << num(p.window.t1) << "): "
           << (p.state == WindowState::Deferred ? "waiting for data"
               : p.state == WindowState::Skipped
                   ? "after the end of the case"
                   : std::to_string(p.snapshots.size()) + " snapshots, " +
                         std::to_string(p.fluidTimes.size()) + " fluid times")
           << "\n";
    return rep;
  }

  for (const Plan& p : plans) {
    if (p.state != WindowState::Ready) continue;
    BinAccumulator acc(grid, kinetic);
    const int threads = std::max(1, opt_.threads);
    for (size_t b = 0; b < p.snapshots.size(); b += threads) {
      std::vector<std::future<ParticleSnapshot>> jobs;
      for (size_t k = b; k < std::min(p.snapshots.size(), b + threads); ++k) {
        const SnapshotEntry& e = series[p.snapshots[k]];
        jobs.push_back(std::async(threads > 1 ? std::launch::async : std::launch::deferred,
                                  [e] { return readParticleSnapshot(e.file, e.time); }));
      }
      for (auto& j : jobs) {
        acc.addSnapshot(j.get());
        ++rep.snapshotsRead;
      }
    }
    for (double t : p.fluidTimes) acc.addFluid(fluid->cells(t));
    if (fluid && p.fluidTimes.empty())
      log_ << "[mixflowExtract] warning: window [" << num(p.window.t0) << ", " << num(p.window.t1)
           << ") holds no fluid time; liquid quantities are masked (no_liquid)" << std::endl;
    const WindowResult res = finaliseWindow(p.window, acc, grid, s);
    out->append(res);
    ++rep.written;
    long valid = 0;
    for (const auto& m : res.bins) valid += m.valid(fLambdaU);
    log_ << "[mixflowExtract] window [" << num(p.window.t0) << ", " << num(p.window.t1)
         << "): " << res.snapshots << " snapshots, " << res.fluidTimes << " fluid times, "
         << num(res.particlesMean) << " particles, " << valid << " bins with valid lambda_u"
         << std::endl;
  }
  out->commit();
  const StoredOutput stored = readStoredOutput(rep.h5);
  writeXdmf(rep.xdmf, rep.h5, stored);
  writeRegionsCsv(rep.csv, stored);
  const double secs =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  log_ << "[mixflowExtract] " << rep.written << " new windows, " << rep.present
       << " already in the file, " << rep.deferred << " waiting for data, " << rep.skipped
       << " after the end of the case; " << rep.snapshotsRead << " snapshots read in " << num(secs)
       << " s\n  " << rep.h5 << "\n  " << rep.xdmf << "\n  " << rep.csv << std::endl;
  return rep;
}

}  // namespace mixflow::mx
