#include "Scene.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "ContactTimes.h"
#include "Dictionary.h"

namespace mixflow::dem {

namespace {
constexpr double kGravity = 9.81;
std::string shortNum(double v) { return formatNumber(v, 4); }
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
      SceneProperties::read(Dictionary::readFile((fs::path(caseDir) / "constant/sceneProperties")),
                            SceneProperties::Half::grains);
  s.content = scene.content;
  s.sample = scene.sample;
  s.channel = scene.channel;
  s.gate = scene.gate;
  s.particles = scene.particles;
  // The liquid's density enters the Savage number (rho_s - rho_f).
  if (s.content == "mixture") s.fluidDensity = scene.liquid.density;

  const Dictionary dem = Dictionary::readFile((fs::path(caseDir) / "system/demDict"));
  const DemDict demDict = DemDict::read(dem);
  s.dem = demDict.dem;
  s.settle = demDict.settle;

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
  if (s.stiffensSettled() && s.settle.stiffenFrom >= s.dem.youngModulusFactor)
    dem.subDict("settle").fail("stiffenFrom", "value " + shortNum(s.settle.stiffenFrom) +
                                                  " must be below youngModulusFactor (" +
                                                  shortNum(s.dem.youngModulusFactor) +
                                                  "): the sample is stiffened to it; "
                                                  "allowed range 0 (no stiffening) or (0, " +
                                                  shortNum(s.dem.youngModulusFactor) + ")");
  return s;
}

Scene Scene::settledScene() const {
  Scene full = *this;
  full.dem.rayleighFraction = settle.rayleighFraction;
  return full;
}

Scene Scene::settlingScene() const {
  Scene soft = settledScene();
  if (!stiffensSettled()) return soft;
  soft.dem.youngModulusFactor = settle.stiffenFrom;
  soft.dem.timeStep = 0;
  return soft;
}

Scene Scene::stiffeningScene(long k) const {
  Scene step = settledScene();
  if (k >= settle.stiffenSteps) return step;
  const double x = static_cast<double>(k) / static_cast<double>(settle.stiffenSteps);
  step.dem.youngModulusFactor =
      settle.stiffenFrom * std::pow(dem.youngModulusFactor / settle.stiffenFrom, x);
  step.dem.timeStep = 0;
  return step;
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

std::string Scene::autoStepWarning() const {
  const double asked = dem.rayleighFraction * rayleighTime();
  const double used = timeStepUsed();
  if (dem.timeStep > 0 || asked <= used * (1 + 1e-9)) return "";
  return caseDir + "/system/demDict: rayleighFraction " + shortNum(dem.rayleighFraction) +
         " asks for dt = " + shortNum(asked) + " s, above the stability limit " + shortNum(used) +
         " s (maxRayleighFraction, maxHertzFraction): the step is the limit, " +
         shortNum(used / rayleighTime()) + " T_R";
}

long Scene::particleCount() const {
  const double v = sample.length * sample.height * sample.width * sample.solidFraction;
  return std::lround(v / particles.volume());
}

}  // namespace mixflow::dem
