#include "Extractor.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <future>
#include <ostream>
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
#include "WindowPlan.h"
#include "WindowResult.h"

#ifndef MIXFLOW_VERSION
#define MIXFLOW_VERSION "unknown"
#endif

namespace mixflow::mx {

namespace fs = std::filesystem;

namespace {

std::string num(double v) { return formatNumber(v, 8); }

// What the case holds, read before anything is planned.
struct CaseInputs {
  dem::Scene scene;
  std::string dictFile;
  ExtractSettings settings;
  AveragingGrid grid;
  std::vector<SnapshotEntry> series;  // not empty
  bool kinetic = false;               // the dumped c_pstress holds the kinetic term
  bool finished = false;              // the DEM wrote postProcessing/dem/summary.json
};

CaseInputs readCase(const ExtractOptions& opt) {
  CaseInputs c;
  c.scene = dem::Scene::read(opt.caseDir);
  c.dictFile = opt.dictFile.empty() ? (fs::path(opt.caseDir) / "system" / "extractDict").string()
                                    : opt.dictFile;
  c.settings = ExtractSettings::read(c.dictFile, c.scene);
  const ExtractSettings& s = c.settings;
  c.grid = AveragingGrid(s.x0, s.x1, s.nx, s.y0, s.y1, s.ny, c.scene.sample.width);
  c.series = readSnapshotSeries(opt.caseDir);
  if (c.series.empty())
    throw InputError((fs::path(opt.caseDir) / "VTK" / "particles.vtk.series").string() +
                     ": lists no snapshot yet");
  c.kinetic = stressHasKineticTerm(opt.caseDir, s.stressKineticTerm);
  c.finished = fs::exists(fs::path(opt.caseDir) / "postProcessing/dem/summary.json");
  return c;
}

// The fluid source given (tests), else the case's OpenFOAM time directories as fluid.source
// says; null without fluid data.
std::shared_ptr<FluidSource> openFluid(const CaseInputs& c, const std::string& caseDir,
                                       std::shared_ptr<FluidSource> given) {
  const ExtractSettings& s = c.settings;
  std::shared_ptr<FluidSource> fluid = std::move(given);
  if (!fluid && s.fluidSource != "none") {
    const bool there = FoamFluidSource::present(caseDir, s.fluidNames);
    if (s.fluidSource == "openfoam" && !there)
      throw InputError(c.dictFile + ": entry 'fluid.source' is openfoam but " + caseDir +
                       " has no time directory with field '" + s.fluidNames.velocity + "'");
    if (there) fluid = std::make_shared<FoamFluidSource>(caseDir, s.fluidNames);
  }
  if (fluid && s.wantDensity() && !(s.liquidDensity > 0))
    throw InputError(c.dictFile + ": entry 'liquidDensity' is needed (allowed range > 0 kg/m3): " +
                     "pressureConvention " + s.pressureConvention +
                     " divides p_f by the liquid's density, and " + c.scene.caseDir +
                     "/constant/sceneProperties (content " + c.scene.content +
                     ") has no liquid.density; give liquidDensity, or pressureConvention raw");
  return fluid;
}

// A finished run with the initial fluid state alone wrote no fluid fields: nothing to pair.
void checkFluidWritten(const CaseInputs& c, const std::string& caseDir, const FluidSource* fluid,
                       const FluidPairing& pairing) {
  if (!fluid || !pairing.solved.empty() || !c.finished) return;
  throw InputError(
      caseDir + ": the fluid fields are missing: the run finished (" +
      (fs::path(caseDir) / "postProcessing/dem/summary.json").string() +
      ") but its only fluid write is the initial state at t = 0 (" + fluid->describe() +
      "); a parallel run's fields are in processor*/ until reconstructPar joins them. Run the "
      "fluid solver (or reconstructPar -case " +
      caseDir + "), or extract the particles alone with fluid { source none; } in " + c.dictFile);
}

// The report with the output files' paths: -output, else extractDict's output, relative to the
// case.
ExtractReport outputFiles(const ExtractOptions& opt, const ExtractSettings& s) {
  std::string base = opt.output.empty() ? s.output : opt.output;
  if (fs::path(base).is_relative()) base = (fs::path(opt.caseDir) / base).string();
  ExtractReport rep;
  rep.h5 = base + ".h5";
  rep.xdmf = base + ".xdmf";
  rep.csv = base + "_regions.csv";
  return rep;
}

// The windows already in the output file, checked read-only against the settings before
// anything is written; none when the file is to be started again.
std::vector<std::pair<double, double>> storedWindows(const std::string& h5,
                                                     const ExtractSettings& s, bool overwrite) {
  if (fs::exists(h5) && !overwrite) return existingWindows(h5, s);
  return {};
}

// Every snapshot to be read exists (its contents are checked when it is read).
void checkSnapshotsExist(const std::vector<PlannedWindow>& plans,
                         const std::vector<SnapshotEntry>& series, const std::string& caseDir) {
  for (const PlannedWindow& p : plans)
    if (p.state == WindowState::Ready)
      for (size_t k : p.snapshots)
        if (!snapshotExists(series[k]))
          throw InputError(series[k].file +
                           ": cannot open file (missing or unreadable; listed in " +
                           (fs::path(caseDir) / "VTK" / "particles.vtk.series").string() +
                           " for t = " + num(series[k].time) + " s)");
}

// Contact stress along the contact lines (particles.stress contacts, or auto when every snapshot
// to read has its contact files), else each particle's virial.
bool chooseContactStress(const std::vector<PlannedWindow>& plans, const CaseInputs& c) {
  std::string lacking;  // the first snapshot to read without its contact files
  for (const PlannedWindow& p : plans)
    if (p.state == WindowState::Ready)
      for (size_t k : p.snapshots)
        if (lacking.empty() && !contactSnapshotExists(c.series[k].file))
          lacking = dem::pairContactPath(c.series[k].file);
  const bool allContacts = lacking.empty();
  const std::string& source = c.settings.stressSource;
  if (source == "contacts" && !allContacts)
    throw InputError(
        c.dictFile + ": entry 'particles.stress' is contacts but snapshots lack their " +
        "contact files VTK/contacts/pairs_<step>.txt and walls_<step>.txt (first: " + lacking +
        "; run the DEM with demDict contactSnapshots on), or set it to " + "virial or auto");
  return source == "contacts" || (source == "auto" && allContacts);
}

void countWindowStates(const std::vector<PlannedWindow>& plans, ExtractReport& rep) {
  rep.present = countWindows(plans, WindowState::Present);
  rep.deferred = countWindows(plans, WindowState::Deferred);
  rep.skipped = countWindows(plans, WindowState::Skipped);
  rep.unpaired = countWindows(plans, WindowState::Unpaired);
}

void logCase(std::ostream& log, const CaseInputs& c, const FluidSource* fluid,
             const FluidPairing& pairing, bool useContacts) {
  const ExtractSettings& s = c.settings;
  log << "[mixflowExtract] case " << c.scene.name << ": " << c.series.size() << " snapshots in ["
      << num(c.series.front().time) << ", " << num(c.series.back().time) << "] s"
      << (c.finished ? " (finished)" : " (running or stopped without summary)") << "; grid " << s.nx
      << " x " << s.ny << " bins of " << num(c.grid.dx()) << " x " << num(c.grid.dy()) << " x "
      << num(c.grid.width()) << " m; fluid: "
      << (fluid
              ? fluid->describe() + " (" + std::to_string(pairing.solved.size()) + " solved times)"
              : std::string("none"))
      << std::endl;
  // The virial route is a documented choice, so falling back to it is said, not warned about.
  log << "[mixflowExtract] kernel " << s.kernelShape;
  if (s.kernelShape != "bins") log << " of width " << num(s.kernelWidthMetres) << " m";
  log << "; contact stress from "
      << (useContacts ? "the contact snapshots (VTK/contacts), walls included"
                      : "each particle's stress/atom virial, without the wall contacts (bins at a "
                        "wall miss their share; the contact-line stress needs the DEM run with "
                        "demDict contactSnapshots on)")
      << std::endl;
  if (!s.liquidDensityWarning.empty())
    log << "[mixflowExtract] warning: " << s.liquidDensityWarning << " (the extractDict entry wins)"
        << std::endl;
}

// The HDF5 root attributes: program, case, settings and the conventions behind the fields.
RootAttributes rootAttributes(const CaseInputs& c, const std::string& caseDir,
                              const FluidSource* fluid, bool useContacts) {
  const ExtractSettings& s = c.settings;
  const dem::Scene& scene = c.scene;
  RootAttributes attrs;
  attrs.text = {
      {"mixflow_version", MIXFLOW_VERSION},
      {"program", "mixflowExtract"},
      {"case_dir", fs::absolute(caseDir).lexically_normal().string()},
      {"case_name", scene.name},
      {"content", scene.content},
      {"channel_side_walls", scene.channel.sideWalls},
      {"extract_dict_file", c.dictFile},
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
                 (c.kinetic ? " + m_i v_i v_i (the dumped compute includes the kinetic term -m v v)"
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
      {"stress_kinetic_term", c.kinetic ? "included" : "excluded"},
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
      {"time_tolerance_s", s.timeTolerance},
      {"pair_tolerance_s", s.pairTolerance},
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
  return attrs;
}

// How the snapshots of a window are read and binned.
struct Binning {
  const CaseInputs& c;
  const FluidSource* fluid;
  CoarseGrainKernel kernel;
  double periodicWidth;  // the width W when z is periodic, else 0
  bool useContacts;
  std::vector<dem::WallPlane> walls;
  int threads;  // snapshot files read at once
};

Binning binningFor(const CaseInputs& c, const FluidSource* fluid, bool useContacts, int threads) {
  const ExtractSettings& s = c.settings;
  return Binning{c,
                 fluid,
                 CoarseGrainKernel(c.grid, s.kernelShape, s.kernelWidthMetres),
                 c.scene.channel.sideWalls == "periodic" ? c.scene.sample.width : 0.0,
                 useContacts,
                 dem::wallPlanes(c.scene),
                 std::max(1, threads)};
}

// Snapshots read so far: how many from their binary twins, and the time spent waiting for them.
struct ReadTally {
  long snapshots = 0, binary = 0;
  double seconds = 0;
};

// Reads a window's snapshots (`threads` files at once) and its fluid times into the bins.
WindowResult binWindow(const PlannedWindow& p, Binning& b, ReadTally& tally) {
  const CaseInputs& c = b.c;
  BinAccumulator acc(c.grid, b.kernel, c.kinetic, b.periodicWidth);
  const int threads = b.threads;
  const bool useContacts = b.useContacts;
  const std::vector<dem::WallPlane>& walls = b.walls;
  using Read = std::pair<ParticleSnapshot, ContactSnapshot>;
  for (size_t first = 0; first < p.snapshots.size(); first += threads) {
    std::vector<std::future<Read>> jobs;
    for (size_t k = first; k < std::min(p.snapshots.size(), first + threads); ++k) {
      const SnapshotEntry& e = c.series[p.snapshots[k]];
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
      tally.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - r0).count();
      tally.binary += fs::path(snap.file).extension() == ".bin";
      acc.addSnapshot(snap, useContacts ? &read.second : nullptr);
      ++tally.snapshots;
    }
  }
  for (double t : p.fluidTimes) acc.addFluid(b.fluid->cells(t));
  WindowResult res = finaliseWindow(p.window, acc, c.grid, c.settings);
  if (!p.fluidTimes.empty()) {
    res.tFirstFluid = p.fluidTimes.front();
    res.tLastFluid = p.fluidTimes.back();
    res.maxPairGap = 0;
    for (size_t k = 0; k < p.snapshots.size(); ++k)
      res.maxPairGap =
          std::max(res.maxPairGap, std::fabs(p.fluidTimes[k] - c.series[p.snapshots[k]].time));
  }
  return res;
}

void logWindow(std::ostream& log, const PlannedWindow& p, const WindowResult& res) {
  long valid = 0;
  for (const auto& m : res.bins) valid += m.valid(fLambdaU);
  log << "[mixflowExtract] window [" << num(p.window.t0) << ", " << num(p.window.t1)
      << "): " << res.snapshots << " snapshots, " << res.fluidTimes << " fluid times";
  if (!p.fluidTimes.empty()) log << " (pairs at most " << num(res.maxPairGap) << " s apart)";
  log << ", " << num(res.particlesMean) << " particles, " << valid << " bins with valid lambda_u"
      << std::endl;
}

// Bins every ready window and appends it to the HDF5 file, which is committed at the end.
void writeWindows(const std::vector<PlannedWindow>& plans, Binning& binning,
                  const RootAttributes& attrs, bool overwrite, std::ostream& log,
                  ExtractReport& rep, ReadTally& tally) {
  H5Output out(rep.h5, binning.c.grid, binning.c.settings, attrs, overwrite);
  for (const PlannedWindow& p : plans) {
    if (p.state != WindowState::Ready) continue;
    const WindowResult res = binWindow(p, binning, tally);
    out.append(res);
    ++rep.written;
    logWindow(log, p, res);
  }
  out.commit();
  rep.snapshotsRead = tally.snapshots;
}

// The XDMF index and the regions CSV, rebuilt from the committed HDF5 file.
void writeIndexes(const ExtractReport& rep) {
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
}

void logTotals(std::ostream& log, const ExtractReport& rep, const ReadTally& tally,
               std::chrono::steady_clock::time_point start) {
  const double secs =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  log << "[mixflowExtract] " << rep.written << " new windows, " << rep.present
      << " already in the file, " << rep.deferred << " waiting for data, " << rep.skipped
      << " after the end of the case";
  if (rep.unpaired) log << ", " << rep.unpaired << " without paired fluid data";
  log << "; " << rep.snapshotsRead << " snapshots read (" << tally.binary << " binary) in "
      << num(secs) << " s (" << num(tally.seconds) << " s reading them)\n  " << rep.h5 << "\n  "
      << rep.xdmf << "\n  " << rep.csv << std::endl;
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
  const auto start = std::chrono::steady_clock::now();
  const CaseInputs c = readCase(opt_);
  const std::shared_ptr<FluidSource> fluid = openFluid(c, opt_.caseDir, fluid_);
  const ExtractSettings& s = c.settings;
  const FluidPairing pairing =
      pairFluidTimes(fluid.get(), c.series, s.timeTolerance, s.pairTolerance);
  checkFluidWritten(c, opt_.caseDir, fluid.get(), pairing);
  ExtractReport rep = outputFiles(opt_, s);
  const PlanInputs planInputs{s, c.scene, c.series, pairing, c.finished};
  const std::vector<PlannedWindow> plans =
      planWindows(planInputs, storedWindows(rep.h5, s, opt_.overwrite));
  checkSnapshotsExist(plans, c.series, opt_.caseDir);
  const bool useContacts = chooseContactStress(plans, c);
  countWindowStates(plans, rep);
  logCase(log_, c, fluid.get(), pairing, useContacts);
  logPlan(log_, plans, planInputs);
  if (opt_.checkOnly) {
    listWindows(log_, plans, rep.h5);
    return rep;
  }
  Binning binning = binningFor(c, fluid.get(), useContacts, opt_.threads);
  ReadTally tally;
  writeWindows(plans, binning, rootAttributes(c, opt_.caseDir, fluid.get(), useContacts),
               opt_.overwrite, log_, rep, tally);
  writeIndexes(rep);
  logTotals(log_, rep, tally, start);
  return rep;
}

}  // namespace mixflow::mx
