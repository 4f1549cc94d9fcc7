#include "MixtureCase.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "CouplingProperties.h"
#include "DemDriver.h"
#include "Dictionary.h"
#include "ForceModel.h"
#include "LiftedGate.h"
#include "LiggghtsCommands.h"
#include "Scene.h"
#include "SettledSample.h"
#include "VoidFractionModel.h"

namespace mixflow::cfd {

namespace fs = std::filesystem;

namespace {

constexpr double kGravity = 9.81;  // as constant/g (FoamCaseWriter)

std::string num(double v) { return formatNumber(v, 3); }

// The smallest cell edge against the particle diameter (kCellDiametersMin, kCellDiametersWarn).
void checkCellsAgainstGrains(const LiquidCase& c, MixtureSetup& m) {
  const double h = c.minCellSize(), d = m.diameter, ratio = h / d;
  const Dictionary cfd = Dictionary::readFile((fs::path(c.caseDir) / "system/cfdDict").string());
  const std::string asked =
      cfd.has("cellSize") ? "" : " (auto: H / 20 = " + num(c.sample.height / 20.0) + " m)";
  const std::string cells = "cells of " + num(h) + " m (the smallest edge) are " + num(ratio) +
                            " particle diameters (d = " + num(d) + " m)";
  if (ratio < kCellDiametersMin * (1 - 1e-9))
    cfd.fail("cellSize", cells + asked +
                             ": unresolved coupling averages the grains over each cell and needs "
                             "cells of at least " +
                             num(kCellDiametersMin) + " d (" + num(kCellDiametersWarn) +
                             " d advised); allowed range [" + num(kCellDiametersMin * d) + ", " +
                             num(c.sample.height / 4.0) + "] m");
  if (ratio < kCellDiametersWarn * (1 - 1e-9) && !c.numerics.coarseCellsReason.empty())
    m.notes.push_back(cfd.where("cellSize") + ": " + cells + asked + ", below the " +
                      num(kCellDiametersWarn) + " d advised for unresolved coupling, because (" +
                      cfd.where("coarseCellsReason") + "): " + c.numerics.coarseCellsReason);
  else if (ratio < kCellDiametersWarn * (1 - 1e-9))
    m.warnings.push_back(cfd.where("cellSize") + ": " + cells + asked +
                         ": unresolved coupling is meant for cells of at least " +
                         num(kCellDiametersWarn) +
                         " d; below that a cell holds few grains, and its void fraction (with the "
                         "drag laws' bed correlations that use it) jumps as grains cross faces. "
                         "cellSize >= " +
                         num(kCellDiametersWarn * d) + " m meets it");
}

// The coupled step: Courant number estimate at the dam-break front speed, and writeInterval.
void checkCoupledStep(const LiquidCase& c, const coupling::CouplingProperties& props,
                      MixtureSetup& m) {
  const double dx = std::min(c.dx(), c.dy());
  m.frontSpeed = 2.0 * std::sqrt(kGravity * c.sample.height);
  m.courant = c.coupledDeltaT * m.frontSpeed / dx;
  // The largest exchangeEvery whose estimate stays at or below a Courant number co.
  const auto largest = [&](double co) {
    return static_cast<long>(std::floor(co * dx / (m.frontSpeed * m.demTimeStep) * (1 + 1e-9)));
  };
  const std::string estimate =
      "gives a CFD step of " + num(c.coupledDeltaT) + " s = " + std::to_string(m.exchangeEvery) +
      " x DEM step " + num(m.demTimeStep) +
      " s, whose Courant number estimate dt 2 sqrt(g H) / dx = " + num(m.courant) +
      " (2 sqrt(g H) = " + num(m.frontSpeed) +
      " m/s, Ritter's dam-break front speed for H = " + num(c.sample.height) +
      " m; dx = " + num(dx) + " m)";
  if (m.courant > kCourantMax) {
    const long most = largest(kCourantMax);
    props.dict.fail("exchangeEvery",
                    "value " + std::to_string(m.exchangeEvery) + " " + estimate + " exceeds " +
                        num(kCourantMax) + ": the fluid step would outrun its cells; " +
                        (most >= 1 ? "allowed range [1, " + std::to_string(most) + "]"
                                   : "even exchangeEvery 1 exceeds it: lower the DEM step or "
                                     "coarsen the mesh"));
  }
  if (m.courant > c.numerics.maxCo)
    m.warnings.push_back(props.dict.where("exchangeEvery") + ": value " +
                         std::to_string(m.exchangeEvery) + " " + estimate +
                         " is above system/cfdDict maxCo " + num(c.numerics.maxCo) +
                         " (the front alone; air jets run faster); exchangeEvery <= " +
                         std::to_string(largest(c.numerics.maxCo)) + " keeps it below");
  if (c.coupledDeltaT > c.writeInterval)
    props.dict.fail("exchangeEvery",
                    "value " + std::to_string(m.exchangeEvery) + " gives a CFD step of " +
                        std::to_string(c.coupledDeltaT) +
                        " s, longer than controlDict writeInterval; allowed range [1, " +
                        std::to_string(static_cast<long>(c.writeInterval / m.demTimeStep)) + "]");
}

// Terminal velocity of a lone sphere under Di Felice's single-particle drag,
// Cd = (0.63 + 4.8 / sqrt(Re))^2 (coupling/models/force/DiFeliceDrag.cpp at eps_f = 1); 0 if it
// does not sink.
double terminalVelocity(double d, double rhoS, double rhoF, double mu) {
  if (rhoS <= rhoF || mu <= 0) return 0;
  const double weight = (rhoS - rhoF) * kGravity * d * d * d / 6.0;  // over pi
  const auto drag = [&](double u) {
    const double cd = std::pow(0.63 + 4.8 / std::sqrt(rhoF * u * d / mu), 2);
    return 0.5 * cd * rhoF * u * u * d * d / 4.0;  // over pi
  };
  double lo = 1e-30, hi = 1e3;
  for (int i = 0; i < 200; ++i) {
    const double mid = std::sqrt(lo * hi);
    (drag(mid) < weight ? lo : hi) = mid;
  }
  return std::sqrt(lo * hi);
}

// The held drag's relaxation number of a lone grain at its terminal velocity:
// s = beta T / m = (1 - rho_f / rho_s) g T / u_t. Held over T, the speed's deviation from u_t
// is multiplied by 1 - n s per interval, n = d ln F / d ln u of the drag at Re_t (1 in Stokes
// flow, 1 + 0.63 sqrt(Re) / (0.63 sqrt(Re) + 4.8) for Di Felice's): unstable above n s = 2.
void checkDragRelaxation(const LiquidCase& c, const dem::Scene& scene,
                         const coupling::CouplingProperties& props, MixtureSetup& m) {
  const double d = scene.particles.diameter, rho = scene.particles.density;
  const bool capped = c.liquid.yieldStressModel();
  const double mu = capped ? c.liquid.viscosityCap : c.liquid.viscosity;
  const double ut = terminalVelocity(d, rho, c.liquid.density, mu);
  if (ut <= 0) return;
  const double perSecond = (1 - c.liquid.density / rho) * kGravity / ut;  // s / T
  m.relaxation = perSecond * c.coupledDeltaT;
  if (props.dragIntegration != "held") return;
  const double root = 0.63 * std::sqrt(c.liquid.density * ut * d / mu);
  const double slope = 1 + root / (root + 4.8);
  const double limit =
      props.dragRelaxationLimit > 0 ? props.dragRelaxationLimit : kHeldRelaxationMax / slope;
  const long most = static_cast<long>(std::floor(limit / (perSecond * m.demTimeStep) * (1 + 1e-9)));
  const std::string what = "value " + std::to_string(m.exchangeEvery) +
                           " gives an exchange interval T = " + num(c.coupledDeltaT) +
                           " s at which a lone grain's drag relaxation number beta T / m = " +
                           "(1 - rho_f / rho_s) g T / u_t is " + num(m.relaxation) +
                           " (Di Felice terminal velocity u_t = " + num(ut) +
                           " m/s for d = " + num(d) + " m, rho_s = " + num(rho) +
                           " kg/m3, mu = " + num(mu) + " Pa s" +
                           (capped ? ", the liquid's viscosityCap" : "") + ")";
  if (m.relaxation <= limit) return;
  if (props.dragRelaxationLimit <= 0 && !capped)
    props.dict.fail("exchangeEvery",
                    what + " > 2 / n = " + num(limit) + " (n = d ln F / d ln u = " + num(slope) +
                        " at Re_t = " + num(c.liquid.density * ut * d / mu) +
                        "): a drag held over the interval without dragRelaxationLimit makes the "
                        "settling speed oscillate and grow there (results/stability); "
                        "dragIntegration implicit is stable at any interval; " +
                        (most >= 1 ? "allowed range [1, " + std::to_string(most) + "]"
                                   : "even exchangeEvery 1 exceeds it: lower the DEM step"));
  else if (props.dragRelaxationLimit <= 0)
    m.warnings.push_back(props.dict.where("exchangeEvery") + ": " + what +
                         " > 2 / n = " + num(limit) +
                         ": a held drag without dragRelaxationLimit oscillates and grows where "
                         "the liquid is at its cap; exchangeEvery <= " +
                         std::to_string(most) + ", or dragIntegration implicit");
  else
    m.warnings.push_back(props.dict.where("exchangeEvery") + ": " + what +
                         " > dragRelaxationLimit " + num(props.dragRelaxationLimit) +
                         ": the held drag is clamped to limit x m / T, so a grain settles up to "
                         "s / limit times faster than its drag law gives (results/stability); "
                         "exchangeEvery <= " +
                         std::to_string(most) +
                         ", or dragIntegration implicit (exact at any interval)");
}

// The liquid's law in the coupling's terms (SI, dynamic), as mixflowCoupled reads it back from
// the transportProperties that writeFoamCase makes of c (Newtonian: no cap).
coupling::LiquidLaw liquidLaw(const LiquidCase& c) {
  coupling::LiquidLaw law;
  law.density = c.liquid.density;
  law.airDensity = c.air.density;
  law.airViscosity = c.air.viscosity;
  if (c.liquid.yieldStressModel()) {
    law.yieldStress = c.liquid.yieldStress;
    law.consistency = c.liquid.consistency;
    law.flowIndex = c.liquid.flowIndex;
    law.viscosityCap = c.liquid.viscosityCap;
  } else {
    law.consistency = c.liquid.viscosity;
  }
  return law;
}

// The sample-independent part of checkMixture for a scene already read.
void checkMixture(LiquidCase& c, const dem::Scene& scene, MixtureSetup& m) {
  m.diameter = scene.particles.diameter;
  m.demTimeStep = scene.timeStepUsed();

  const std::string propsFile = (fs::path(c.caseDir) / "constant" / "couplingProperties").string();
  if (!fs::exists(propsFile))
    throw InputError(propsFile +
                     ": cannot open file: a mixture scene needs its coupling "
                     "properties (coupling/README.md)");
  const coupling::CouplingProperties props = coupling::CouplingProperties::read(propsFile);
  // The models as mixflowCoupled builds them (FoamCoupling): unknown names and wrong Coeffs
  // entries are found here. mixflowFoam's formulation B with the full viscous stress, as the
  // case files mixflowPrepare writes select, and the liquid's law as transportProperties gives
  // it to the drag viscosity closures (dragViscosity auto depends on it).
  coupling::ForceContext context;
  context.g = coupling::Vec3(0, -kGravity, 0);
  context.liquid = liquidLaw(c);
  for (const auto& name : props.forceModels) coupling::ForceModel::New(name, props.dict, context);
  coupling::VoidFractionModel::New(props.voidFractionModel, props.dict);

  m.exchangeEvery = props.exchangeEvery;
  c.coupledDeltaT = m.exchangeEvery * m.demTimeStep;
  checkCoupledStep(c, props, m);
  checkDragRelaxation(c, scene, props, m);
  checkCellsAgainstGrains(c, m);
  m.demScriptPath = props.demScript.front() == '/'
                        ? props.demScript
                        : (fs::path(c.caseDir) / props.demScript).string();
}

}  // namespace

MixtureSetup checkMixture(LiquidCase& c) {
  MixtureSetup m;
  const dem::Scene scene = dem::Scene::read(c.caseDir);
  m.particles = scene.particleCount();
  m.settledHeight = c.sample.height;
  checkMixture(c, scene, m);
  return m;
}

MixtureSetup prepareMixture(LiquidCase& c) {
  MixtureSetup m;
  m.settled = true;
  const dem::Scene scene = dem::Scene::read(c.caseDir);

  const fs::path statePath = fs::path(c.caseDir) / "dem" / "settled.state";
  if (!fs::exists(statePath))
    throw InputError(statePath.string() +
                     ": cannot open file: the settled sample is missing (run mixflowDem -case " +
                     c.caseDir + " -settleOnly first; Allrun does)");
  const Dictionary st = Dictionary::readFile(statePath.string());
  const dem::SettleReport settled = dem::readSettledDict(st.subDict("settled"));
  // The DEM settings may have been edited since the settling: the restart would then carry
  // overlaps and a box made for others (dem/SettledSample.h). Samples settled before the inputs
  // were recorded have no fingerprint and are taken as they are.
  if (!settled.fingerprint.empty()) {
    const std::string why = dem::inputsMismatch(
        dem::settleInputs(scene), settled.fingerprint,
        (fs::path(c.caseDir) / "dem" / "settled.inputs").string(), dem::settleEntries(scene),
        (fs::path(c.caseDir) / "dem" / "settled.entries").string());
    if (!why.empty())
      throw InputError(statePath.string() + ": entry 'settled/fingerprint': " + why +
                       ": the sample was settled from other DEM inputs than the case now has. "
                       "Settle again (Allrun does)");
  }
  m.particles = settled.particles;
  m.settledHeight = settled.settledHeight;
  if (m.settledHeight <= 0 || m.settledHeight >= c.channel.height)
    throw InputError(statePath.string() + ": entry 'settled/height': value " +
                     std::to_string(m.settledHeight) + " outside the channel (0, " +
                     std::to_string(c.channel.height) + ") m");
  c.sample.height = m.settledHeight;
  checkMixture(c, scene, m);

  // The settled sample restarted without the gate. ${mixflowCase} is defined by mixflowCoupled
  // (the case directory), so the case can be moved or copied.
  std::ostringstream s;
  s << "# Written by mixflowPrepare for the mixture scene " << c.name
    << ": the settled sample (mixflowDem -settleOnly)\n# restarted with the scene's contacts and "
       "walls, no gate; its step 0 (t = 0) is the gate opening.\n";
  for (const std::string& line :
       dem::resumeSetupCommands(scene, "${mixflowCase}/dem/settled.restart", m.demTimeStep)) {
    // mixflowCoupled sets a processor grid matching the fluid decomposition unless the scene asks
    // for its own.
    if (line.rfind("processors", 0) == 0 && scene.dem.processors == "* * *") continue;
    s << line << "\n";
  }
  if (scene.gate.lifted()) {
    // The grains' plate at h(t) of the script's step (0 fresh, the restart's on a resume), then
    // lifted at the law's speed and parked once past the column (dem/LiftedGate.h).
    const dem::LiftedGate gate(scene, m.settledHeight);
    s << "# The lifted gate (sceneProperties gate): a plate at x = L, lower edge h(t).\n";
    for (const std::string& line :
         gate.parkedCommands("${mixflowCase}/dem/gate.stl", m.demTimeStep))
      s << line << "\n";
    m.gateStl = gate.stl(0.0);
    m.gateStlPath = (fs::path(c.caseDir) / "dem" / "gate.stl").string();
  }
  m.demScript = s.str();
  return m;
}

void writeMixtureDemScript(const MixtureSetup& m) {
  const std::string tmp = m.demScriptPath + ".tmp";
  std::ofstream(tmp) << m.demScript;
  fs::rename(tmp, m.demScriptPath);
  if (!m.gateStl.empty()) {
    // Next to the settled sample (the script reads ${mixflowCase}/dem/gate.stl).
    std::ofstream(m.gateStlPath + ".tmp") << m.gateStl;
    fs::rename(m.gateStlPath + ".tmp", m.gateStlPath);
  }
}

void describeMixture(const MixtureSetup& m, const LiquidCase& c, std::ostream& os) {
  const double cellDiameters = c.minCellSize() / m.diameter;
  if (m.settled)
    os << "[mixflowPrepare] mixture: " << m.particles << " settled particles, liquid up to the "
       << "settled top y = " << m.settledHeight << " m; ";
  else
    os << "[mixflowPrepare] mixture before settling: about " << m.particles
       << " particles (phi L H W / V_p), liquid up to the nominal sample height " << m.settledHeight
       << " m; ";
  os << "CFD step " << c.coupledDeltaT << " s = " << m.exchangeEvery << " x DEM step "
     << m.demTimeStep << " s, Courant number estimate " << num(m.courant)
     << " at 2 sqrt(g H) = " << num(m.frontSpeed)
     << " m/s; lone-grain drag relaxation beta T / m = " << num(m.relaxation) << "; cells of "
     << num(cellDiameters) << " d; DEM script " << m.demScriptPath << "\n";
  if (!m.settled)
    os << "[mixflowPrepare] checked without the settled sample; left to mixflowPrepare after "
          "mixflowDem -settleOnly: the settled height inside the channel, the sample's DEM inputs "
          "against the case's, and the Courant estimate at the settled height\n";
  for (const auto& n : m.notes) os << "[mixflowPrepare] note: " << n << "\n";
  for (const auto& w : m.warnings) os << "[mixflowPrepare] warning: " << w << "\n";
}

}  // namespace mixflow::cfd
