#include "ExtractSettings.h"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "Dictionary.h"
#include "Scene.h"
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

}  // namespace

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
  d.allowOnly({"grid", "windows", "thresholds", "pressureConvention", "liquidDensity", "viscosity",
               "fluid", "particles", "timeTolerance", "pairTolerance", "regions", "output"});

  const Dictionary& g = d.subDict("grid");
  g.allowOnly({"x", "y"});
  // The domain widened by one particle radius: grains overlap the floor and walls by their contact
  // deflection, and a grid that starts at -r holds all of their volume.
  const double r = scene.particles.radius();
  readAxis(g, "x", -r, scene.channel.length + r,
           "channel.length in constant/sceneProperties, +- one particle radius", s.x0, s.x1, s.nx);
  readAxis(g, "y", -r, scene.channel.height + r,
           "channel.height in constant/sceneProperties, +- one particle radius", s.y0, s.y1, s.ny);

  const Dictionary& w = d.subDict("windows");
  w.allowOnly({"list", "start", "end", "width"});
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
    const double start = w.scalarOr("start", 0.0, Range::nonNegative());
    const double end = w.scalarOr("end", scene.endTime, Range::positive());
    const double width = w.scalar("width", Range::positive());
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
  t.allowOnly({"minVelocity", "minPressure", "minSolidFraction", "minSaturation", "minDenominator",
               "minParticleSamples", "minLiquidShare"});
  Thresholds& th = s.thresholds;
  th.minVelocity = t.scalarOr("minVelocity", th.minVelocity, Range::positive());
  th.minPressure = t.scalarOr("minPressure", th.minPressure, Range::positive());
  th.minSolidFraction = t.scalarOr("minSolidFraction", th.minSolidFraction, Range::closed(0, 1));
  th.minSaturation = t.scalarOr("minSaturation", th.minSaturation, Range::closed(0, 1));
  th.minDenominator = t.scalarOr("minDenominator", th.minDenominator, Range::positive());
  th.minParticleSamples = t.integerOr("minParticleSamples", th.minParticleSamples, 1, 1000000000);
  th.minLiquidShare = t.scalarOr("minLiquidShare", th.minLiquidShare, Range::closed(0, 1));

  s.pressureConvention =
      d.wordOr("pressureConvention", s.pressureConvention, {"raw", "density", "both"});
  // The liquid's density: an explicit liquidDensity wins over sceneProperties liquid.density (a
  // mixture's liquid), with a warning when the two differ.
  const std::string sceneFile = scene.caseDir + "/constant/sceneProperties";
  if (d.has("liquidDensity")) {
    s.liquidDensity = d.scalar("liquidDensity", Range::positive());
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
    v.allowOnly({"solid", "fluid"});
    s.haveViscosities = true;
    s.nuSolid = v.scalar("solid", Range::nonNegative());
    s.nuFluid = v.scalar("fluid", Range::nonNegative());
  }

  const Dictionary f = d.subDictOrEmpty("fluid");
  f.allowOnly(
      {"source", "liquidFraction", "voidFraction", "velocity", "pressure", "centres", "volumes"});
  s.fluidSource = f.wordOr("source", s.fluidSource, {"auto", "none", "openfoam"});
  FoamFieldNames& fn = s.fluidNames;
  fn.liquidFraction = f.wordOr("liquidFraction", fn.liquidFraction, {});
  fn.voidFraction = f.wordOr("voidFraction", fn.voidFraction, {});
  fn.velocity = f.wordOr("velocity", fn.velocity, {});
  fn.pressure = f.wordOr("pressure", fn.pressure, {});
  fn.centres = f.wordOr("centres", fn.centres, {});
  fn.volumes = f.wordOr("volumes", fn.volumes, {});

  const Dictionary p = d.subDictOrEmpty("particles");
  p.allowOnly({"stressKineticTerm"});
  s.stressKineticTerm =
      p.wordOr("stressKineticTerm", s.stressKineticTerm, {"auto", "included", "excluded"});

  // Snapshot times are step * dt, off the nominal multiples of writeInterval by up to dt / 2.
  s.timeTolerance = d.scalarOr("timeTolerance", 0.5 * scene.timeStepUsed(), Range::nonNegative());
  // A coupled run writes the fluid at the first CFD step at or after each multiple of
  // writeInterval, so a fluid time lags its snapshot by up to one CFD step; beyond half the
  // interval a fluid time could pair with the neighbouring snapshot.
  s.pairTolerance = d.scalarOr("pairTolerance", 0.1 * scene.writeInterval,
                               Range::closed(0, 0.5 * scene.writeInterval));
  s.pairToleranceWhere = d.where("pairTolerance");

  if (d.has("regions")) {
    const Dictionary& r = d.subDict("regions");
    for (const std::string& name : r.keys()) {
      const Dictionary& rd = r.subDict(name);
      rd.allowOnly({"x", "y"});
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

  if (d.has("output")) {
    s.output = d.text("output");
    if (s.output.empty() || s.output.find(' ') != std::string::npos)
      d.fail("output",
             "must be one file base name (no spaces), e.g. postProcessing/mixture/mixture");
  }
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
    << fluidNames.centres << ' ' << fluidNames.volumes << "; stress " << stressKineticTerm
    << "; tol " << timeTolerance << "; pairing " << pairTolerance << " solved-times-only; regions";
  for (const auto& r : regions)
    s << ' ' << r.name << ' ' << r.x0 << ' ' << r.x1 << ' ' << r.y0 << ' ' << r.y1;
  return s.str();
}

}  // namespace mixflow::mx
