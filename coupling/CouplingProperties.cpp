#include "CouplingProperties.h"

#include <algorithm>
#include <sstream>

#include "ForceModel.h"
#include "MixflowProperties.h"
#include "VoidFractionModel.h"

namespace mixflow::coupling {

CouplingProperties CouplingProperties::read(const std::string& file) {
  CouplingProperties p;
  p.dict = Dictionary::readFile(file);
  const Dictionary& d = p.dict;
  std::vector<std::string> allowed = {"FoamFile",           "demScript",
                                      "exchangeEvery",      "forceModels",
                                      "voidFractionModel",  "interpolation",
                                      "sourceDistribution", "voidfractionMin",
                                      "logEvery",           "dragRelaxationLimit",
                                      "maxVelocity",        "dragIntegration",
                                      "dragFluidResponse",  "dragCounterflowLimit",
                                      "pressureCoupling",   "dragReactionVelocity"};
  for (const auto& m : ForceModel::available()) allowed.push_back(m + "Coeffs");
  for (const auto& m : VoidFractionModel::available()) allowed.push_back(m + "Coeffs");
  d.allowOnly(allowed);

  p.demScript = d.text("demScript");
  p.exchangeEvery = d.integerOr("exchangeEvery", 100, 1, 1000000000);
  std::istringstream models(d.text("forceModels"));
  for (std::string m; models >> m;) {
    if (std::find(p.forceModels.begin(), p.forceModels.end(), m) != p.forceModels.end())
      d.fail("forceModels", "model '" + m + "' is listed twice");
    p.forceModels.push_back(m);
  }
  if (p.forceModels.empty()) {
    std::string list;
    for (const auto& m : ForceModel::available()) list += (list.empty() ? "" : " ") + m;
    d.fail("forceModels", "lists no model; give one or more of: " + list);
  }
  p.voidFractionModel = d.wordOr("voidFractionModel", "divided", VoidFractionModel::available());
  p.interpolation = d.wordOr("interpolation", "cell", {"cell", "cellPoint"});
  p.sourceDistribution = d.wordOr("sourceDistribution", "volume", {"volume", "centre"});
  p.dragReactionVelocity =
      d.wordOr("dragReactionVelocity", "particleMean", {"particleMean", "cell"});
  if (d.has("voidfractionMin"))
    p.voidfractionMin =
        d.scalar("voidfractionMin", MixflowProperties::schema().param("voidfractionMin").range);
  p.logEvery = d.integerOr("logEvery", 1, 1, 1000000000);
  p.dragIntegration = d.wordOr("dragIntegration", "implicit", {"implicit", "held"});
  p.dragFluidResponse = d.wordOr("dragFluidResponse", "none", {"none", "share", "continuity"});
  // Default: mixture wherever it applies (implicit drag without a dragFluidResponse mode).
  const bool mixtureApplies = p.dragIntegration == "implicit" && p.dragFluidResponse == "none";
  p.pressureCoupling =
      d.wordOr("pressureCoupling", mixtureApplies ? "mixture" : "fluid", {"fluid", "mixture"});
  if (p.pressureCoupling == "mixture" &&
      (p.dragIntegration != "implicit" || p.dragFluidResponse != "none"))
    d.fail("pressureCoupling",
           "'mixture' needs dragIntegration implicit and dragFluidResponse none");
  p.dragRelaxationLimit = d.scalarOr("dragRelaxationLimit", 0.5, Range::closed(0.0, 1.0));
  p.dragCounterflowLimit = d.scalarOr("dragCounterflowLimit", 0.5, Range::closed(0.0, 1.0));
  p.maxVelocity = d.scalarOr("maxVelocity", 100.0, Range::positive());
  return p;
}

}  // namespace mixflow::coupling
