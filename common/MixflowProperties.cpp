#include "MixflowProperties.h"

#include <filesystem>

#include "Dictionary.h"

namespace mixflow {

namespace {
Schema makeSchema() {
  const MixflowProperties m{};
  return Schema(
      "constant/mixflowProperties",
      {
          wordParam("formulation", m.formulation, {"B"},
                    "volume-averaged equations (docs/model.md §3): fluid momentum with -grad(p); "
                    "the coupling gives particles buoyancy + drag + viscous force and the fluid "
                    "loses f_p. Only B is implemented"),
          wordParam("viscousStress", m.viscousStress, {"full", "voidfractionWeighted"},
                    "full: div(τ) (formulation B as in Zhou et al. 2010); voidfractionWeighted: "
                    "div(ε_f τ) (as CFDEM's solvers do)"),
          switchParam("continuityVoidfractionRate", m.continuityVoidfractionRate,
                      "d(ε_f)/dt in the pressure equation's continuity; off: CFDEMcoupling's "
                      "`useDDTvoidfraction off` (below, \"d(ε_f)/dt in continuity\")"),
          // A floor of 1 would leave no room for particles.
          scalarParam("voidfractionMin", m.voidfractionMin, {0.0, 1.0, false, true}, "",
                      "ε_f below it is a fatal error; the coupling clips its particle volume "
                      "fractions to it (couplingProperties `voidfractionMin` may only raise it)"),
          anyParam("particleRamp",
                   "verification mode of a standalone run: a Function1 of time r(t) scaling the "
                   "particle fields read at the start, ε_f = 1 - r (1 - ε_f,0), fSource = r "
                   "fSource_0 (e.g. `{ type halfCosineRamp; start 0; duration 0.2; }`); "
                   "mixflowCoupled refuses it"),
      });
}
}  // namespace

const Schema& MixflowProperties::schema() {
  static const Schema s = makeSchema();
  return s;
}

MixflowProperties MixflowProperties::read(const std::string& file) {
  MixflowProperties m;
  if (file.empty() || !std::filesystem::exists(file)) return m;
  const Schema& sc = schema();
  const Dictionary d = Dictionary::readFile(file);
  sc.allowOnly(d, "");
  m.formulation = sc.word(d, "formulation");
  m.viscousStress = sc.word(d, "viscousStress");
  m.continuityVoidfractionRate = sc.flag(d, "continuityVoidfractionRate");
  m.voidfractionMin = sc.scalar(d, "voidfractionMin");
  m.particleRamp = d.has("particleRamp");
  return m;
}

}  // namespace mixflow
