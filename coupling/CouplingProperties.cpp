#include "CouplingProperties.h"

#include <algorithm>
#include <sstream>

#include "ForceModel.h"
#include "MixflowProperties.h"
#include "Schema.h"
#include "VoidFractionModel.h"

namespace mixflow::coupling {

namespace {
Schema makeSchema() {
  const CouplingProperties c{};
  const MixflowProperties m{};
  Param demScript = textParam("demScript", "",
                              "the LIGGGHTS input of the coupled run "
                              "(mixflowPrepare writes system/in.liggghts)");
  demScript.required = true;
  Param forceModels =
      textParam("forceModels", "",
                "the forces on the grains, one or more of: " + joinWords(ForceModel::available()) +
                    " (each reads its `<model>Coeffs` block)");
  forceModels.required = true;
  std::vector<Param> params = {
      demScript,
      integerParam("exchangeEvery", c.exchangeEvery, 1, 1000000000,
                   "DEM steps per exchange; the CFD step is exchangeEvery × the DEM step"),
      forceModels,
      wordParam("voidFractionModel", c.voidFractionModel, VoidFractionModel::available(),
                "how a grain's volume is shared among cells (its `<model>Coeffs` block)"),
      wordParam("interpolation", c.interpolation, {"cell", "cellPoint"},
                "how the fluid is sampled at a grain"),
      wordParam(
          "sourceDistribution", c.sourceDistribution, {"volume", "centre"},
          "where a grain's reaction force goes: the cells its volume covers, or its centre's"),
      wordParam("dragReactionVelocity", c.dragReactionVelocity, {"particleMean", "cell"},
                "the grain velocity in the fluid's share of the drag: mean over the interval, or "
                "at the exchange (parameters below, \"Drag reaction velocity\")"),
      scalarParam("voidfractionMin", m.voidfractionMin, {0.0, 1.0, false, true}, "",
                  "ε_f floor of the coupling; may only raise mixflowProperties' voidfractionMin")
          .shownDefault("mixflowProperties `voidfractionMin`"),
      integerParam("logEvery", c.logEvery, 1, 1000000000,
                   "exchanges per line of the log and row of postProcessing/coupling/exchange.csv"),
      wordParam("dragIntegration", c.dragIntegration, {"implicit", "held"},
                "implicit: β, U held over the interval and the drag updated with the grain's "
                "velocity at every DEM step (stable for any β); held: the whole force held"),
      wordParam("dragFluidResponse", c.dragFluidResponse, {"none", "share", "continuity"},
                "implicit only: the fluid velocity the drag sees within the interval (below)"),
      wordParam("dragCoefficientUpdate", c.dragCoefficientUpdate, {"slip", "exchange"},
                "implicit only: slip: β of the grain's slip at every DEM step (the laws "
                "evaluated with the exchange's fluid sample); exchange: β of the exchange held"),
      wordParam("implicitDragDefect", c.implicitDragDefect, {"returned", "kept"},
                "implicit only: the fluid step's implicit drag β_T (U_held − U_new), which no "
                "grain received, returned in the next step's explicit source (the fluid gets the "
                "grains' drag impulse exactly) or kept (below, \"Implicit drag defect\")"),
      wordParam("dragFluidVelocity", c.dragFluidVelocity, {"held", "extrapolated"},
                "pressureCoupling mixture only: the fluid velocity the drag sees over the "
                "interval, held at the fluid step's or going on at that step's rate of change "
                "(below, \"Fluid velocity seen by the drag\")"),
      wordParam("pressureCoupling", c.pressureCoupling, {"fluid", "mixture"},
                "mixture: the pressure equation counts the share of the grains' volume the "
                "implicit drag carries (mixture continuity); fluid: the fluid's alone (below)")
          .shownDefault("mixture where it applies (implicit, dragFluidResponse none), else fluid"),
      scalarParam("dragRelaxationLimit", c.dragRelaxationLimit, Range::closed(0.0, 1.0), "",
                  "held only: β ≤ limit × m / T (T the exchange interval); 0 = no limit"),
      scalarParam("dragCounterflowLimit", c.dragCounterflowLimit, Range::closed(0.0, 1.0), "",
                  "held only: β ≤ limit / c × m / T, c = (1 − ε_f) / ε_f; 0 = no limit"),
      scalarParam("maxVelocity", c.maxVelocity, Range::positive(), "m/s",
                  "a fluid speed above it anywhere stops the run with the place and time"),
  };
  for (const auto& name : ForceModel::available())
    params.push_back(dictParam(name + "Coeffs", "coefficients of force model " + name));
  for (const auto& name : VoidFractionModel::available())
    params.push_back(dictParam(name + "Coeffs", "coefficients of void-fraction model " + name));
  return Schema("constant/couplingProperties", params);
}
}  // namespace

const Schema& CouplingProperties::schema() {
  static const Schema s = makeSchema();
  return s;
}

CouplingProperties CouplingProperties::read(const std::string& file) {
  const Schema& sc = schema();
  CouplingProperties p;
  p.dict = Dictionary::readFile(file);
  const Dictionary& d = p.dict;
  sc.allowOnly(d, "");

  p.demScript = sc.text(d, "demScript");
  p.exchangeEvery = sc.integer(d, "exchangeEvery");
  std::istringstream models(sc.text(d, "forceModels"));
  for (std::string m; models >> m;) {
    if (std::find(p.forceModels.begin(), p.forceModels.end(), m) != p.forceModels.end())
      d.fail("forceModels", "model '" + m + "' is listed twice");
    p.forceModels.push_back(m);
  }
  if (p.forceModels.empty())
    d.fail("forceModels",
           "lists no model; give one or more of: " + joinWords(ForceModel::available()));
  p.voidFractionModel = sc.word(d, "voidFractionModel");
  p.interpolation = sc.word(d, "interpolation");
  p.sourceDistribution = sc.word(d, "sourceDistribution");
  p.dragReactionVelocity = sc.word(d, "dragReactionVelocity");
  if (d.has("voidfractionMin")) p.voidfractionMin = sc.scalar(d, "voidfractionMin");
  p.logEvery = sc.integer(d, "logEvery");
  p.dragIntegration = sc.word(d, "dragIntegration");
  p.dragFluidResponse = sc.word(d, "dragFluidResponse");
  p.dragCoefficientUpdate = sc.word(d, "dragCoefficientUpdate");
  p.implicitDragDefect = sc.word(d, "implicitDragDefect");
  p.dragFluidVelocity = sc.word(d, "dragFluidVelocity");
  // Default: mixture wherever it applies (implicit drag without a dragFluidResponse mode).
  const bool mixtureApplies = p.dragIntegration == "implicit" && p.dragFluidResponse == "none";
  p.pressureCoupling = d.has("pressureCoupling") ? sc.word(d, "pressureCoupling")
                                                 : (mixtureApplies ? "mixture" : "fluid");
  if (p.pressureCoupling == "mixture" && !mixtureApplies)
    d.fail("pressureCoupling",
           "'mixture' needs dragIntegration implicit and dragFluidResponse none");
  if (p.dragFluidVelocity == "extrapolated" && p.pressureCoupling != "mixture")
    d.fail("dragFluidVelocity",
           "'extrapolated' needs pressureCoupling mixture (the fluid "
           "velocity sampled again after the fluid step)");
  p.dragRelaxationLimit = sc.scalar(d, "dragRelaxationLimit");
  p.dragCounterflowLimit = sc.scalar(d, "dragCounterflowLimit");
  p.maxVelocity = sc.scalar(d, "maxVelocity");
  return p;
}

}  // namespace mixflow::coupling
