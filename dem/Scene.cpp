#include "Scene.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <utility>

#include "ContactTimes.h"
#include "Dictionary.h"

namespace mixflow::dem {

namespace {
constexpr double kGravity = 9.81;
std::string shortNum(double v) { return formatNumber(v, 4); }

void readSettle(const Dictionary& d, SettleSpec& s) {
  d.allowOnly({"friction", "maxTime", "kineticTolerance", "fillSpacing", "relaxTime", "seed"});
  s.friction = d.scalarOr("friction", s.friction, Range::nonNegative());
  s.maxTime = d.scalarOr("maxTime", s.maxTime, Range::positive());
  s.kineticTolerance = d.scalarOr("kineticTolerance", s.kineticTolerance, Range::positive());
  // Spacing below 1.02 d leaves no room for the jitter; above 2 d the fill column gets very tall.
  s.fillSpacing = d.scalarOr("fillSpacing", s.fillSpacing, Range::closed(1.02, 2.0));
  s.relaxTime = d.scalarOr("relaxTime", s.relaxTime, Range::nonNegative());
  s.seed = d.integerOr("seed", s.seed, 1, 900000000);
}

void readDem(const Dictionary& d, DemSpec& m) {
  d.allowOnly({"youngModulusFactor", "timeStep", "rayleighFraction", "maxRayleighFraction",
               "maxHertzFraction", "limitForce", "sampleInterval", "frontGapDiameters",
               "velocityProfile", "stopWhenArrested", "arrestKineticTolerance", "arrestMinTime",
               "arrestFrontDiameters", "arrestWindow", "processors", "settle", "savage"});
  m.youngModulusFactor =
      d.scalarOr("youngModulusFactor", m.youngModulusFactor, Range::openClosed(0.0, 1.0));
  if (const auto v = d.scalarOrAuto("timeStep", Range::positive())) m.timeStep = *v;
  m.rayleighFraction = d.scalarOr("rayleighFraction", m.rayleighFraction, Range::openClosed(0, 1));
  m.maxRayleighFraction =
      d.scalarOr("maxRayleighFraction", m.maxRayleighFraction, Range::openClosed(0, 1));
  m.maxHertzFraction = d.scalarOr("maxHertzFraction", m.maxHertzFraction, Range::openClosed(0, 1));
  m.limitForce = d.switchOr("limitForce", m.limitForce);
  m.sampleInterval = d.scalarOr("sampleInterval", m.sampleInterval, Range::positive());
  m.frontGapDiameters = d.scalarOr("frontGapDiameters", m.frontGapDiameters, Range::positive());
  const Dictionary vp = d.subDictOrEmpty("velocityProfile");
  vp.allowOnly({"x", "time", "binDiameters"});
  m.profileX = vp.scalarOr("x", m.profileX, Range::any());
  m.profileTime = vp.scalarOr("time", m.profileTime, Range::nonNegative());
  m.profileBinDiameters = vp.scalarOr("binDiameters", m.profileBinDiameters, Range::positive());
  const Dictionary sv = d.subDictOrEmpty("savage");
  sv.allowOnly({"x", "layers", "tanPhi"});
  m.savageX = sv.scalarOr("x", m.savageX, Range::any());
  m.savageLayers = static_cast<int>(sv.integerOr("layers", m.savageLayers, 2, 50));
  m.savageTanPhi = sv.scalarOr("tanPhi", m.savageTanPhi, Range::positive());
  m.stopWhenArrested = d.switchOr("stopWhenArrested", m.stopWhenArrested);
  m.arrestKineticTolerance =
      d.scalarOr("arrestKineticTolerance", m.arrestKineticTolerance, Range::positive());
  m.arrestMinTime = d.scalarOr("arrestMinTime", m.arrestMinTime, Range::nonNegative());
  m.arrestFrontDiameters =
      d.scalarOr("arrestFrontDiameters", m.arrestFrontDiameters, Range::nonNegative());
  m.arrestWindow = d.scalarOr("arrestWindow", m.arrestWindow, Range::positive());
  if (d.has("processors")) {
    m.processors = d.text("processors");
    std::istringstream in(m.processors);
    std::string t;
    int n = 0;
    while (in >> t) {
      ++n;
      if (t != "*" && (t.find_first_not_of("0123456789") != std::string::npos || t == "0"))
        d.fail("processors", "each of the three entries must be * or a positive integer");
    }
    if (n != 3) d.fail("processors", "needs three entries (x y z), e.g. \"* 1 1\"");
  }
}
}  // namespace

Scene Scene::read(const std::string& caseDir) {
  namespace fs = std::filesystem;
  if (!fs::is_directory(caseDir)) throw InputError(caseDir + ": case directory does not exist");
  Scene s;
  s.caseDir = caseDir;
  s.name = fs::path(caseDir).lexically_normal().filename().string();
  if (s.name.empty() || s.name == ".")
    s.name = fs::absolute(caseDir).parent_path().filename().string();

  const SceneProperties scene =
      SceneProperties::read(Dictionary::readFile((fs::path(caseDir) / "constant/sceneProperties")));
  s.content = scene.content;
  s.sample = scene.sample;
  s.channel = scene.channel;
  s.particles = scene.particles;
  // The liquid's density enters the Savage number (rho_s - rho_f).
  if (s.content == "mixture") s.fluidDensity = scene.liquid.density;

  const Dictionary dem = Dictionary::readFile((fs::path(caseDir) / "system/demDict"));
  readDem(dem, s.dem);
  readSettle(dem.subDictOrEmpty("settle"), s.settle);

  // controlDict holds many OpenFOAM entries; the DEM half reads only these two.
  const Dictionary control = Dictionary::readFile((fs::path(caseDir) / "system/controlDict"));
  const RunTimes times = readRunTimes(control);
  s.endTime = times.endTime;
  s.writeInterval = times.writeInterval;

  // Cross-entry checks, named by the entry that has to change.
  if (s.dem.sampleInterval > s.writeInterval)
    dem.fail("sampleInterval", "value " + shortNum(s.dem.sampleInterval) +
                                   " must not exceed controlDict writeInterval (" +
                                   shortNum(s.writeInterval) + " s)");
  if (s.dem.timeStep > 0) {
    const double limit = s.stableTimeStepLimit();
    if (s.dem.timeStep > limit)
      dem.fail("timeStep", "value " + shortNum(s.dem.timeStep) +
                               " s is above the stability limit " + shortNum(limit) +
                               " s = min(maxRayleighFraction * T_R, "
                               "maxHertzFraction * t_Hertz) with T_R = " +
                               shortNum(s.rayleighTime()) + " s for the softened modulus " +
                               shortNum(s.youngModulusUsed()) + " Pa; allowed range (0, " +
                               shortNum(limit) + "]");
  }
  return s;
}

double Scene::rayleighTime() const {
  return mixflow::dem::rayleighTime(particles.radius(), particles.density, youngModulusUsed(),
                                    particles.poisson);
}

double Scene::maxImpactSpeed() const { return std::sqrt(2.0 * kGravity * sample.height); }

double Scene::hertzTimeMin() const {
  const double r = particles.radius(), m = particles.mass(), nu = particles.poisson;
  const double v = maxImpactSpeed();
  const double ePP = effectiveModulus(youngModulusUsed(), nu, youngModulusUsed(), nu);
  const double ePW = effectiveModulus(youngModulusUsed(), nu, wallYoungModulusUsed(), nu);
  const double tPP = hertzContactTime(ePP, 0.5 * r, 0.5 * m, v);
  const double tPW = hertzContactTime(ePW, r, m, v);
  return std::min(tPP, tPW);
}

double Scene::stableTimeStepLimit() const {
  return std::min(dem.maxRayleighFraction * rayleighTime(), dem.maxHertzFraction * hertzTimeMin());
}

double Scene::timeStepUsed() const {
  if (dem.timeStep > 0) return dem.timeStep;
  return std::min(dem.rayleighFraction * rayleighTime(), stableTimeStepLimit());
}

long Scene::particleCount() const {
  const double v = sample.length * sample.height * sample.width * sample.solidFraction;
  return std::lround(v / particles.volume());
}

}  // namespace mixflow::dem
