#include "ExtractSettings.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <utility>

#include "CfdDict.h"
#include "Dictionary.h"
#include "Scene.h"
#include "Schema.h"
#include "WindowResult.h"

namespace mixflow::mx {

namespace {

std::string num(double v) { return formatNumber(v, 6); }

std::string ordinal(size_t k) {
  const size_t n = k + 1;
  const char* suf = (n % 100 >= 11 && n % 100 <= 13) ? "th"
                    : n % 10 == 1                    ? "st"
                    : n % 10 == 2                    ? "nd"
                    : n % 10 == 3                    ? "rd"
                                                     : "th";
  return std::to_string(n) + suf;
}

// "x (x0 x1 n)" inside the domain [lo, hi].
void readAxis(const Dictionary& g, const std::string& key, double lo, double hi,
              const std::string& domainWhy, double& a, double& b, int& n) {
  const std::vector<double> v = g.scalars(key, Range::any());
  if (v.size() != 3) g.fail(key, "needs three values (" + key + "0 " + key + "1 n" + key + ")");
  a = v[0];
  b = v[1];
  if (!(b > a)) g.fail(key, "needs " + key + "1 > " + key + "0; found " + num(a) + " " + num(b));
  if (a < lo || b > hi)
    g.fail(key, "range [" + num(a) + ", " + num(b) + "] is outside the domain [" + num(lo) + ", " +
                    num(hi) + "] (" + domainWhy + ")");
  if (v[2] != std::floor(v[2]) || v[2] < 1 || v[2] > 100000)
    g.fail(key, "bin count " + num(v[2]) + " must be a whole number in [1, 100000]");
  n = static_cast<int>(v[2]);
}

// Bins no finer than `smallest` (m: a grain, or a fluid cell), said as `why`: a finer bin
// averages parts of single grains or of single cells (and makes a large file of noise).
void checkBinSize(const Dictionary& g, const std::string& key, double a, double b, int n,
                  double smallest, const std::string& why) {
  const double bin = (b - a) / n;
  if (bin >= smallest * (1 - 1e-9)) return;
  const long most = std::max(1L, static_cast<long>(std::floor((b - a) / smallest * (1 + 1e-9))));
  g.fail(key,
         "bins of " + num(bin) + " m (" + num(b - a) + " m in " + std::to_string(n) +
             " bins) are finer than " + why + " (" + num(smallest) +
             " m): a bin would average parts of single grains or cells; allowed bin count [1, " +
             std::to_string(most) + "] (bins of at least " + num(smallest) + " m)");
}

// The fluid cell edges along x and y as mixflowPrepare cuts the channel (system/cfdDict cellSize,
// auto H / 20); none when the case has no cfdDict.
bool fluidCellSize(const dem::Scene& scene, double& dx, double& dy) {
  const std::string path = scene.caseDir + "/system/cfdDict";
  if (!std::ifstream(path)) return false;
  const CfdDict cfd = CfdDict::read(Dictionary::readFile(path));
  const double h = cfd.numerics.cellSize > 0 ? cfd.numerics.cellSize : scene.sample.height / 20.0;
  dx = scene.channel.length / std::max(1L, std::lround(scene.channel.length / h));
  dy = scene.channel.height / std::max(1L, std::lround(scene.channel.height / h));
  return true;
}

// Vector entries (read by readAxis, the window list and the regions): text declarations whose
// allowed column states the rule the code checks.
Param vectorParam(std::string path, std::string unit, std::string allowed, std::string meaning,
                  bool required) {
  Param p = textParam(std::move(path), "", std::move(meaning));
  p.unit = std::move(unit);
  p.required = required;
  return p.alsoAllowed(std::move(allowed));
}

Schema makeSchema() {
  const ExtractSettings s{};
  const Thresholds t{};
  const FoamFieldNames f{};
  const std::string field = "a field name";
  return Schema(
      "system/extractDict",
      {
          dictParam("grid", "the averaging grid in (x, y), averaged across the width (required)"),
          // The domain is widened by one particle radius r: grains overlap the floor and walls by
          // their contact deflection, and a grid that starts at -r holds all of their volume.
          vectorParam("grid.x", "m",
                      "x0 < x1 in [−r, channel.length + r]; nx whole in [1, 100000]; bins ≥ d "
                      "(and, when the fluid is read, ≥ the fluid cell of cfdDict cellSize)",
                      "`x0 x1 nx`: nx bins from x0 to x1 (r the particle radius)", true),
          vectorParam("grid.y", "m",
                      "y0 < y1 in [−r, channel.height + r]; ny whole in [1, 100000]; bins as x",
                      "`y0 y1 ny`: ny bins from y0 to y1", true),
          dictParam("windows", "the time windows: a list, or start/end/width (required)"),
          vectorParam("windows.list", "s", "pairs t0 < t1, t ≥ 0; not with start/end/width",
                      "explicit windows `((t0 t1) (t0 t1) ...)`; every window must hold a "
                      "particle snapshot",
                      false)
              .shownDefault("(none)"),
          scalarParam("windows.start", 0, Range::nonNegative(), "s",
                      "start of the first generated window"),
          scalarParam("windows.end", 0, Range::positive(), "s",
                      "end of the generated windows (the last one is cut there)")
              .alsoAllowed("> start")
              .shownDefault("controlDict `endTime`"),
          requiredScalar("windows.width", Range::positive(), "s",
                         "width of the generated windows from start to end")
              .alsoAllowed("at most 100000 windows")
              .shownDefault("(required without list)"),
          dictParam("thresholds", "below these a bin's quantity is masked (NaN and flagged)"),
          scalarParam("thresholds.minVelocity", t.minVelocity, Range::positive(), "m/s",
                      "magnitude of u_s (w_s) below → λ_u (λ_w) masked"),
          scalarParam("thresholds.minPressure", t.minPressure, Range::positive(), "Pa",
                      "magnitude of p_s below → λ_p masked"),
          scalarParam("thresholds.minSolidFraction", t.minSolidFraction, Range::closed(0, 1), "",
                      "α_s below → the bin is not in the mixture"),
          scalarParam("thresholds.minSaturation", t.minSaturation, Range::closed(0, 1), "",
                      "liquid share of the bin's fluid volume below → not saturated"),
          scalarParam("thresholds.minDenominator", t.minDenominator, Range::positive(), "",
                      "magnitude of α_s + λ α_f below → Λ masked"),
          integerParam("thresholds.minParticleSamples", t.minParticleSamples, 1, 1000000000,
                       "particle-snapshot samples in the bin below → u_s, p_s masked"),
          scalarParam("thresholds.minLiquidShare", t.minLiquidShare, Range::closed(0, 1), "",
                      "liquid share of the bin's fluid volume below → u_f, p_f masked"),
          wordParam("pressureConvention", s.pressureConvention, {"raw", "density", "both"},
                    "which λ_p are written: raw p_f/p_s, density (p_f/ρ_f)/(p_s/ρ_s) (the "
                    "paper's convention), or both"),
          scalarParam("liquidDensity", 0, Range::positive(), "kg/m³",
                      "ρ_f of the density convention; when given it wins over liquid.density, "
                      "with a warning if they differ; needed with fluid data and the density "
                      "convention when the scene has no liquid (ρ_s is sceneProperties "
                      "`particles.density`)")
              .shownDefault("sceneProperties `liquid.density`"),
          dictParam("viscosity", "ν_s and ν_f for the Λ_η coefficients (Eqs. 36, 40, 43)"),
          requiredScalar("viscosity.solid", Range::nonNegative(), "m²/s",
                         "ν_s; with ν_f the Λ_η themselves are written, without `viscosity` only "
                         "their coefficients")
              .shownDefault("(none; required in `viscosity`)"),
          requiredScalar("viscosity.fluid", Range::nonNegative(), "m²/s", "ν_f")
              .shownDefault("(none; required in `viscosity`)"),
          dictParam("fluid", "where the fluid fields come from"),
          wordParam("fluid.source", s.fluidSource, {"auto", "none", "openfoam"},
                    "auto: the OpenFOAM time directories when one holds the velocity field; "
                    "none: particles only"),
          wordParam("fluid.liquidFraction", f.liquidFraction, {},
                    "α_l field; auto: alpha.liquid (mixflowPrepare's cases) if the time has it, "
                    "else alpha.water (interFoam's tutorials); none: α_l = 1")
              .alsoAllowed("auto, none or " + field),
          wordParam("fluid.voidFraction", f.voidFraction, {},
                    "ε_f field; none: ε_f = 1 (pure-liquid cases)")
              .alsoAllowed("none or " + field),
          wordParam("fluid.velocity", f.velocity, {}, "fluid velocity field").alsoAllowed(field),
          wordParam("fluid.pressure", f.pressure, {},
                    "static pressure field in Pa (interFoam family)")
              .alsoAllowed(field),
          wordParam("fluid.centres", f.centres, {},
                    "cell centres (`postProcess -func writeCellCentres`), from the time "
                    "directory, else 0/ or constant/")
              .alsoAllowed(field),
          wordParam("fluid.volumes", f.volumes, {},
                    "cell volumes (`postProcess -func writeCellVolumes`), from the time "
                    "directory, else 0/ or constant/")
              .alsoAllowed(field),
          dictParam("particles", "how the particle snapshots are read"),
          wordParam("particles.stressKineticTerm", s.stressKineticTerm,
                    {"auto", "included", "excluded"},
                    "whether c_pstress holds the kinetic term −m v v; auto: from the `compute "
                    "pstress` line of dem/in.liggghts"),
          wordParam("particles.stress", s.stressSource, {"auto", "contacts", "virial"},
                    "the contact stress: contacts: −Σ f ⊗ b along each contact line (centre to "
                    "centre, centre to contact point for a wall), from the contact snapshots "
                    "(demDict contactSnapshots on); virial: each particle's stress/atom virial "
                    "spread as the particle, without wall contacts; auto: contacts when every "
                    "snapshot to read has its contact files, else virial (said in the log)"),
          dictParam("kernel", "the coarse-graining function, for both phases"),
          wordParam("kernel.shape", s.kernelShape, {"bins", "lucy", "gaussian"},
                    "bins: exact bins (a particle by its volume inside the bin, a contact line by "
                    "its length inside, a fluid cell by its centre); lucy: Lucy polynomial of "
                    "cutoff 2 w; gaussian: Gaussian of standard deviation w cut at 3 w; kernels "
                    "are evaluated at the bin centres, points (particle and cell centres) and "
                    "contact lines weighted by the kernel"),
          scalarParam("kernel.width", s.kernelWidth, Range::closed(0.5, 10), "d",
                      "w in particle diameters (lucy, gaussian); fields plateau for 1 < w/d < 3 "
                      "(mixture_extract/README.md)"),
          // Snapshot times are step * dt, off the nominal multiples of writeInterval by up to
          // dt / 2.
          scalarParam("timeTolerance", 0, Range::nonNegative(), "s",
                      "a window holds the snapshots with t0 − tol ≤ t < t1 − tol")
              .shownDefault("½ DEM time step"),
          // A coupled run writes the fluid at the first CFD step at or after each multiple of
          // writeInterval, so a fluid time lags its snapshot by up to one CFD step; beyond half
          // the interval a fluid time could pair with the neighbouring snapshot.
          scalarParam("pairTolerance", 0, Range::nonNegative(), "s",
                      "a fluid time pairs with the nearest particle snapshot at most this far "
                      "from it")
              .alsoAllowed("≤ ½ controlDict `writeInterval`")
              .shownDefault("0.1 × controlDict `writeInterval`"),
          dictParam("regions",
                    "named regions averaged per window; default one region `all` = "
                    "the grid"),
          dictParam("regions.<name>", "one region: the bins whose centre lies inside"),
          vectorParam("regions.<name>.x", "m",
                      "x0 < x1; overlapping the grid and holding at least one bin centre",
                      "`x0 x1` of the region", true),
          vectorParam("regions.<name>.y", "m", "y0 < y1", "`y0 y1` of the region", true),
          textParam("output", s.output, "file base of the outputs, relative to the case")
              .alsoAllowed("one name without spaces"),
      });
}

}  // namespace

const Schema& ExtractSettings::schema() {
  static const Schema sc = makeSchema();
  return sc;
}

ExtractSettings ExtractSettings::read(const std::string& dictFile, const dem::Scene& scene) {
  ExtractSettings s;
  s.dictFile = dictFile;
  if (!std::ifstream(dictFile))
    throw InputError(
        dictFile +
        ": cannot open file (missing or unreadable); mixflowExtract needs the averaging "
        "grid and the time windows from it (example in mixture_extract/README.md)");
  s.dictText = readTextFile(dictFile);
  const Dictionary d = Dictionary::parse(s.dictText, dictFile);
  const Schema& sc = schema();
  sc.allowOnly(d, "");

  const Dictionary& g = d.subDict("grid");
  sc.allowOnly(g, "grid");
  // The domain widened by one particle radius: grains overlap the floor and walls by their contact
  // deflection, and a grid that starts at -r holds all of their volume.
  const double r = scene.particles.radius();
  readAxis(g, "x", -r, scene.channel.length + r,
           "channel.length in constant/sceneProperties, +- one particle radius", s.x0, s.x1, s.nx);
  readAxis(g, "y", -r, scene.channel.height + r,
           "channel.height in constant/sceneProperties, +- one particle radius", s.y0, s.y1, s.ny);

  const Dictionary& w = d.subDict("windows");
  sc.allowOnly(w, "windows");
  if (w.has("list")) {
    for (const char* k : {"start", "end", "width"})
      if (w.has(k)) w.fail(k, "give either 'list' or 'start/end/width', not both");
    const std::vector<double> v = w.scalars("list", Range::nonNegative());
    if (v.empty() || v.size() % 2)
      w.fail("list", "needs pairs (t0 t1), e.g. list ((0 0.1) (0.1 0.2)); found " +
                         std::to_string(v.size()) + " numbers");
    for (size_t k = 0; k < v.size(); k += 2) {
      TimeWindow tw{v[k], v[k + 1], w.where("list") + " (" + ordinal(k / 2) + " pair)"};
      if (!(tw.t1 > tw.t0))
        w.fail("list", "the " + ordinal(k / 2) + " pair (" + num(tw.t0) + " " + num(tw.t1) +
                           ") needs t1 > t0");
      s.windows.push_back(tw);
    }
  } else {
    s.windowsGenerated = true;
    const double start = sc.scalar(w, "windows.start");
    const double end = w.has("end") ? sc.scalar(w, "windows.end") : scene.endTime;
    const double width = sc.scalar(w, "windows.width");
    s.windowStart = start;
    s.windowWidth = width;
    s.windowStartWhere = w.where("start");
    s.windowWidthWhere = w.where("width");
    if (!(end > start)) w.fail("end", "value " + num(end) + " must exceed start " + num(start));
    const long count = std::lround(std::ceil((end - start) / width - 1e-9));
    if (count > 100000) w.fail("width", "gives " + std::to_string(count) + " windows (max 100000)");
    for (long k = 0; k < count; ++k) {
      const double t0 = start + k * width, t1 = std::min(start + (k + 1) * width, end);
      s.windows.push_back({t0, t1, w.where("width") + " (window " + std::to_string(k) + ")"});
    }
  }

  const Dictionary t = d.subDictOrEmpty("thresholds");
  sc.allowOnly(t, "thresholds");
  Thresholds& th = s.thresholds;
  th.minVelocity = sc.scalar(t, "thresholds.minVelocity");
  th.minPressure = sc.scalar(t, "thresholds.minPressure");
  th.minSolidFraction = sc.scalar(t, "thresholds.minSolidFraction");
  th.minSaturation = sc.scalar(t, "thresholds.minSaturation");
  th.minDenominator = sc.scalar(t, "thresholds.minDenominator");
  th.minParticleSamples = sc.integer(t, "thresholds.minParticleSamples");
  th.minLiquidShare = sc.scalar(t, "thresholds.minLiquidShare");

  s.pressureConvention = sc.word(d, "pressureConvention");
  // The liquid's density: an explicit liquidDensity wins over sceneProperties liquid.density (a
  // mixture's liquid), with a warning when the two differ.
  const std::string sceneFile = scene.caseDir + "/constant/sceneProperties";
  if (d.has("liquidDensity")) {
    s.liquidDensity = sc.scalar(d, "liquidDensity");
    s.liquidDensitySource = d.where("liquidDensity");
    if (scene.fluidDensity > 0 && scene.fluidDensity != s.liquidDensity)
      s.liquidDensityWarning = d.where("liquidDensity") + " = " + num(s.liquidDensity) +
                               " kg/m3 overrides liquid.density = " + num(scene.fluidDensity) +
                               " kg/m3 of " + sceneFile;
  } else if (scene.fluidDensity > 0) {
    s.liquidDensity = scene.fluidDensity;
    s.liquidDensitySource = sceneFile + ": entry 'liquid.density'";
  } else {
    s.liquidDensitySource = "none: " + sceneFile + " (content " + scene.content +
                            ") has no liquid and " + dictFile + " no liquidDensity";
  }
  s.solidDensity = scene.particles.density;
  if (d.has("viscosity")) {
    const Dictionary& v = d.subDict("viscosity");
    sc.allowOnly(v, "viscosity");
    s.haveViscosities = true;
    s.nuSolid = sc.scalar(v, "viscosity.solid");
    s.nuFluid = sc.scalar(v, "viscosity.fluid");
  }

  const Dictionary f = d.subDictOrEmpty("fluid");
  sc.allowOnly(f, "fluid");
  s.fluidSource = sc.word(f, "fluid.source");
  FoamFieldNames& fn = s.fluidNames;
  fn.liquidFraction = sc.word(f, "fluid.liquidFraction");
  fn.voidFraction = sc.word(f, "fluid.voidFraction");
  fn.velocity = sc.word(f, "fluid.velocity");
  fn.pressure = sc.word(f, "fluid.pressure");
  fn.centres = sc.word(f, "fluid.centres");
  fn.volumes = sc.word(f, "fluid.volumes");

  // Bins against the grains and, when the fluid is read, the fluid cells.
  const double dGrain = scene.particles.diameter;
  const std::string grain =
      "a grain (particles.diameter in " + scene.caseDir + "/constant/sceneProperties)";
  checkBinSize(g, "x", s.x0, s.x1, s.nx, dGrain, grain);
  checkBinSize(g, "y", s.y0, s.y1, s.ny, dGrain, grain);
  double cellX = 0, cellY = 0;
  if (s.fluidSource != "none" && fluidCellSize(scene, cellX, cellY)) {
    const std::string cell = "a fluid cell (cellSize in " + scene.caseDir + "/system/cfdDict)";
    checkBinSize(g, "x", s.x0, s.x1, s.nx, cellX, cell);
    checkBinSize(g, "y", s.y0, s.y1, s.ny, cellY, cell);
  }

  const Dictionary p = d.subDictOrEmpty("particles");
  sc.allowOnly(p, "particles");
  s.stressKineticTerm = sc.word(p, "particles.stressKineticTerm");
  s.stressSource = sc.word(p, "particles.stress");
  const Dictionary k = d.subDictOrEmpty("kernel");
  sc.allowOnly(k, "kernel");
  s.kernelShape = sc.word(k, "kernel.shape");
  s.kernelWidth = sc.scalar(k, "kernel.width");
  s.kernelWidthMetres = s.kernelWidth * scene.particles.diameter;

  // The DEM step is validated (it throws above its limit) even when timeTolerance is given.
  const double halfStep = 0.5 * scene.timeStepUsed();
  s.timeTolerance = d.has("timeTolerance") ? sc.scalar(d, "timeTolerance") : halfStep;
  // The declared range's upper end is half the scene's writeInterval (see the declaration).
  const Param& pt = sc.param("pairTolerance");
  s.pairTolerance = d.scalarOr("pairTolerance", 0.1 * scene.writeInterval,
                               Range::closed(pt.range.lo, 0.5 * scene.writeInterval));
  s.pairToleranceWhere = d.where("pairTolerance");

  if (d.has("regions")) {
    const Dictionary& r = d.subDict("regions");
    for (const std::string& name : r.keys()) {
      const Dictionary& rd = r.subDict(name);
      sc.allowOnly(rd, "regions.<name>");
      Region reg{name};
      const std::vector<double> x = rd.scalars("x", Range::any());
      const std::vector<double> y = rd.scalars("y", Range::any());
      if (x.size() != 2 || !(x[1] > x[0])) rd.fail("x", "needs two values x0 < x1");
      if (y.size() != 2 || !(y[1] > y[0])) rd.fail("y", "needs two values y0 < y1");
      reg.x0 = x[0];
      reg.x1 = x[1];
      reg.y0 = y[0];
      reg.y1 = y[1];
      if (reg.x1 <= s.x0 || reg.x0 >= s.x1 || reg.y1 <= s.y0 || reg.y0 >= s.y1)
        rd.fail("x", "region [" + num(reg.x0) + ", " + num(reg.x1) + "] x [" + num(reg.y0) + ", " +
                         num(reg.y1) + "] does not overlap the grid [" + num(s.x0) + ", " +
                         num(s.x1) + "] x [" + num(s.y0) + ", " + num(s.y1) + "]");
      const AveragingGrid grid(s.x0, s.x1, s.nx, s.y0, s.y1, s.ny, 1.0);
      if (regionBins(grid, reg).empty())
        rd.fail("x", "region contains no bin centre of the grid; make it at least one bin wide");
      s.regions.push_back(reg);
    }
  }
  if (s.regions.empty()) s.regions.push_back({"all", s.x0, s.x1, s.y0, s.y1});

  s.output = sc.text(d, "output");
  if (s.output.empty() || s.output.find(' ') != std::string::npos)
    d.fail("output", "must be one file base name (no spaces), e.g. postProcessing/mixture/mixture");
  return s;
}

std::string ExtractSettings::fingerprint() const {
  std::ostringstream s;
  s << std::setprecision(17) << "grid " << x0 << ' ' << x1 << ' ' << nx << ' ' << y0 << ' ' << y1
    << ' ' << ny << "; thresholds " << thresholds.minVelocity << ' ' << thresholds.minPressure
    << ' ' << thresholds.minSolidFraction << ' ' << thresholds.minSaturation << ' '
    << thresholds.minDenominator << ' ' << thresholds.minParticleSamples << ' '
    << thresholds.minLiquidShare << "; pressure " << pressureConvention << ' ' << liquidDensity
    << ' ' << solidDensity << "; viscosity " << haveViscosities << ' ' << nuSolid << ' ' << nuFluid
    << "; fluid " << fluidSource << ' ' << fluidNames.liquidFraction << ' '
    << fluidNames.voidFraction << ' ' << fluidNames.velocity << ' ' << fluidNames.pressure << ' '
    << fluidNames.centres << ' ' << fluidNames.volumes << "; stress " << stressKineticTerm << ' '
    << stressSource << "; kernel " << kernelShape << ' '
    << (kernelShape == "bins" ? 0.0 : kernelWidth) << "; tol " << timeTolerance << "; pairing "
    << pairTolerance << " solved-times-only; regions";
  for (const auto& r : regions)
    s << ' ' << r.name << ' ' << r.x0 << ' ' << r.x1 << ' ' << r.y0 << ' ' << r.y1;
  return s.str();
}

}  // namespace mixflow::mx
