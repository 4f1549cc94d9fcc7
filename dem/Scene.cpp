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
// Solid grains from expanded polystyrene beads (about 15 kg/m3) to osmium (22 600 kg/m3); outside
// it the value is a typo, and one like 1e300 overflows the particle mass inside LIGGGHTS.
const Range kGrainDensityRange = Range::closed(10.0, 25000.0);

std::string shortNum(double v) { return formatNumber(v, 4); }

void readSample(const Dictionary& d, SampleSpec& s) {
  d.allowOnly({"length", "height", "width", "solidFraction"});
  s.length = d.scalar("length", Range::positive());
  s.height = d.scalar("height", Range::positive());
  s.width = d.scalar("width", Range::positive());
  // Above random close packing (0.64) a monodisperse sample cannot be made by settling.
  s.solidFraction = d.scalarOr("solidFraction", s.solidFraction, Range::openClosed(0.0, 0.64));
}

void readChannel(const Dictionary& d, ChannelSpec& c) {
  d.allowOnly({"length", "height", "sideWalls"});
  c.length = d.scalar("length", Range::positive());
  c.height = d.scalar("height", Range::positive());
  c.sideWalls = d.wordOr("sideWalls", c.sideWalls, {"walls", "periodic"});
}

void readParticles(const Dictionary& d, ParticleMaterial& p) {
  d.allowOnly({"diameter", "density", "youngModulus", "wallYoungModulus", "poissonRatio",
               "restitution", "friction", "wallFriction", "rollingFriction", "rollingModel",
               "rollingViscousDamping"});
  p.diameter = d.scalarOr("diameter", p.diameter, Range::positive());
  p.density = d.scalarOr("density", p.density, kGrainDensityRange);
  p.youngModulus = d.scalarOr("youngModulus", p.youngModulus, Range::positive());
  p.wallYoungModulus = d.scalarOr("wallYoungModulus", p.wallYoungModulus, Range::positive());
  p.poisson = d.scalarOr("poissonRatio", p.poisson, {0.0, 0.5, false, true});
  // LIGGGHTS' damping formula needs e > 0; e = 1 is elastic.
  p.restitution = d.scalarOr("restitution", p.restitution, Range::openClosed(0.0, 1.0));
  p.friction = d.scalarOr("friction", p.friction, Range::nonNegative());
  p.wallFriction = d.scalarOr("wallFriction", p.wallFriction, Range::nonNegative());
  p.rollingFriction = d.scalarOr("rollingFriction", p.rollingFriction, Range::nonNegative());
  p.rollingModel = d.wordOr("rollingModel", p.rollingModel, {"cdt", "epsd2", "off"});
  p.rollingViscousDamping =
      d.scalarOr("rollingViscousDamping", p.rollingViscousDamping, Range::nonNegative());
}

void readSettle(const Dictionary& d, SettleSpec& s) {
  d.allowOnly({"friction", "maxTime", "kineticTolerance", "fillSpacing", "relaxTime", "seed",
               "checkpointInterval"});
  s.friction = d.scalarOr("friction", s.friction, Range::nonNegative());
  s.maxTime = d.scalarOr("maxTime", s.maxTime, Range::positive());
  s.kineticTolerance = d.scalarOr("kineticTolerance", s.kineticTolerance, Range::positive());
  // Spacing below 1.02 d leaves no room for the jitter; above 2 d the fill column gets very tall.
  s.fillSpacing = d.scalarOr("fillSpacing", s.fillSpacing, Range::closed(1.02, 2.0));
  s.relaxTime = d.scalarOr("relaxTime", s.relaxTime, Range::nonNegative());
  s.seed = d.integerOr("seed", s.seed, 1, 900000000);
  s.checkpointInterval =
      d.scalarOr("checkpointInterval", s.checkpointInterval, Range::nonNegative());
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

double ParticleMaterial::volume() const { return kPi / 6.0 * diameter * diameter * diameter; }
double ParticleMaterial::mass() const { return density * volume(); }

Scene Scene::read(const std::string& caseDir) {
  namespace fs = std::filesystem;
  if (!fs::is_directory(caseDir)) throw InputError(caseDir + ": case directory does not exist");
  Scene s;
  s.caseDir = caseDir;
  s.name = fs::path(caseDir).lexically_normal().filename().string();
  if (s.name.empty() || s.name == ".")
    s.name = fs::absolute(caseDir).parent_path().filename().string();

  const Dictionary scene = Dictionary::readFile((fs::path(caseDir) / "constant/sceneProperties"));
  scene.allowOnly({"content", "sample", "channel", "particles", "liquid"});
  s.content = scene.word("content", {"particles", "liquid", "mixture"});
  readSample(scene.subDict("sample"), s.sample);
  readChannel(scene.subDict("channel"), s.channel);
  if (s.content != "liquid") readParticles(scene.subDictOrEmpty("particles"), s.particles);
  // The liquid's density enters the Savage number (rho_s - rho_f); the rest of liquid{} is the
  // fluid half's (mixflowPrepare validates it).
  if (s.content == "mixture")
    s.fluidDensity = scene.subDict("liquid").scalar("density", Range::positive());

  const Dictionary dem = Dictionary::readFile((fs::path(caseDir) / "system/demDict"));
  readDem(dem, s.dem);
  readSettle(dem.subDictOrEmpty("settle"), s.settle);

  // controlDict holds many OpenFOAM entries; the DEM half reads only these two.
  const Dictionary control = Dictionary::readFile((fs::path(caseDir) / "system/controlDict"));
  const RunTimes times = readRunTimes(control);
  s.endTime = times.endTime;
  s.writeInterval = times.writeInterval;

  // Cross-entry checks, named by the entry that has to change.
  const double d = s.particles.diameter;
  const std::pair<const char*, double> sizes[] = {
      {"length", s.sample.length}, {"height", s.sample.height}, {"width", s.sample.width}};
  for (const auto& [key, size] : sizes)
    if (size < d)
      scene.subDict("sample").fail(key, "value " + shortNum(size) +
                                            " m is below one particle diameter (" + shortNum(d) +
                                            " m); allowed range [" + shortNum(d) + ", inf)");
  if (s.channel.length <= s.sample.length + d)
    scene.subDict("channel").fail("length", "value " + shortNum(s.channel.length) +
                                                " must exceed the sample length plus one "
                                                "diameter (" +
                                                shortNum(s.sample.length + d) + " m)");
  if (s.channel.height < s.sample.height)
    scene.subDict("channel").fail("height", "value " + shortNum(s.channel.height) +
                                                " must be at least the sample height (" +
                                                shortNum(s.sample.height) + " m)");
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
