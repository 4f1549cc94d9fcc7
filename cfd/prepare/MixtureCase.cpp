#include "MixtureCase.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "CouplingProperties.h"
#include "DemDriver.h"
#include "Dictionary.h"
#include "LiggghtsCommands.h"
#include "Scene.h"
#include "SettledSample.h"

namespace mixflow::cfd {

namespace fs = std::filesystem;

MixtureSetup prepareMixture(LiquidCase& c) {
  MixtureSetup m;
  const dem::Scene scene = dem::Scene::read(c.caseDir);
  m.demTimeStep = scene.timeStepUsed();

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
    const std::string why =
        dem::inputsMismatch(dem::settleInputs(scene), settled.fingerprint,
                            (fs::path(c.caseDir) / "dem" / "settled.inputs").string());
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

  const std::string propsFile = (fs::path(c.caseDir) / "constant" / "couplingProperties").string();
  if (!fs::exists(propsFile))
    throw InputError(propsFile +
                     ": cannot open file: a mixture scene needs its coupling "
                     "properties (coupling/README.md)");
  const coupling::CouplingProperties props = coupling::CouplingProperties::read(propsFile);
  m.exchangeEvery = props.exchangeEvery;
  c.coupledDeltaT = m.exchangeEvery * m.demTimeStep;
  if (c.coupledDeltaT > c.writeInterval)
    props.dict.fail("exchangeEvery",
                    "value " + std::to_string(m.exchangeEvery) + " gives a CFD step of " +
                        std::to_string(c.coupledDeltaT) +
                        " s, longer than controlDict writeInterval; allowed range [1, " +
                        std::to_string(static_cast<long>(c.writeInterval / m.demTimeStep)) + "]");
  m.demScriptPath = props.demScript.front() == '/'
                        ? props.demScript
                        : (fs::path(c.caseDir) / props.demScript).string();

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
  m.demScript = s.str();
  return m;
}

void writeMixtureDemScript(const MixtureSetup& m) {
  const std::string tmp = m.demScriptPath + ".tmp";
  std::ofstream(tmp) << m.demScript;
  fs::rename(tmp, m.demScriptPath);
}

void describeMixture(const MixtureSetup& m, const LiquidCase& c, std::ostream& os) {
  os << "[mixflowPrepare] mixture: " << m.particles << " settled particles, liquid up to the "
     << "settled top y = " << m.settledHeight << " m; CFD step " << c.coupledDeltaT
     << " s = " << m.exchangeEvery << " x DEM step " << m.demTimeStep << " s; DEM script "
     << m.demScriptPath << "\n";
}

}  // namespace mixflow::cfd
