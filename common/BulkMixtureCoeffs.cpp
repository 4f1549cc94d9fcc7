#include "BulkMixtureCoeffs.h"

#include <algorithm>

#include "Dictionary.h"
#include "DriftAlgebra.h"

namespace mixflow {

namespace {
Schema makeSchema() {
  // The drifts' own bound alpha_s + lambda alpha_f >= 0.01 (Lambda = 1 / that stays finite) is
  // checked by mixflowPrepare and, cell by cell for fields, by the solver.
  const std::string drift = "α_s + λ α_f ≥ 0.01";
  const char* solid = "coulombViscoplastic";
  return Schema(
      "constant/transportProperties bulkMixtureCoeffs",
      {
          requiredScalar("solidFraction", Range::closed(0.0, 0.64), "", "α_s"),
          requiredScalar("lambdaU", Range::closed(-1e3, 1e3), "", "λ_u").alsoAllowed(drift),
          requiredScalar("lambdaW", Range::closed(-1e3, 1e3), "", "λ_w").alsoAllowed(drift),
          requiredScalar("lambdaP", Range::closed(-1e3, 1e3), "", "λ_p (pressureClosure lambdaP)")
              .alsoAllowed(drift),
          wordParam("pressureClosure", "porePressureRatio", {"porePressureRatio", "lambdaP"},
                    "how p_m splits into the pore pressure and the effective stress "
                    "(bulkProperties `drifts.pressure`)"),
          scalarParam("porePressureRatio", 0,
                      Range{bulk::kPoreRatioMin, bulk::kPoreRatioMax, false, true}, "",
                      "χ of pressureClosure porePressureRatio"),
          wordParam("solidRheology", solid, {solid, "muI"}, "the solid's law"),
          requiredScalar("solidViscosity", Range::nonNegative(), "m²/s", "ν_s").only({solid}),
          requiredScalar("tanPhi", Range::closed(0.0, 5.0), "", "tanφ").only({solid}),
          requiredScalar("cohesion", Range::nonNegative(), "m²/s²", "τ_c / ρ_s").only({solid}),
          requiredScalar("muS", Range::closed(0.0, 5.0), "", "μ_s").only({"muI"}),
          requiredScalar("mu2", Range::closed(0.0, 5.0), "", "μ_2").only({"muI"}),
          requiredScalar("I0", Range::openClosed(0.0, 100.0), "", "I_0").only({"muI"}),
          requiredScalar("grainDiameter", Range::openClosed(0.0, 1.0), "m", "d").only({"muI"}),
          requiredScalar("regularisation", Range::closed(0.0, 1e5), "s", "m_y"),
          requiredWord("yieldPressure", {"paper", "buoyancyReduced"},
                       "the pressure of the yield stress: P_s/ρ_s (paper) or σ′/(α_s ρ_s)"),
          requiredScalar("fluidTau0", Range::nonNegative(), "m²/s²", "the pore liquid's τ_0/ρ_f"),
          requiredScalar("fluidK", Range::nonNegative(), "m²/sⁿ",
                         "the pore liquid's k/ρ_f (ν_f when Newtonian)"),
          requiredScalar("fluidN", Range::positive(), "", "the pore liquid's flow index n"),
          requiredScalar("fluidNu0", Range::nonNegative(), "m²/s",
                         "the pore liquid's viscosity cap (0: none)"),
          requiredScalar("mixtureDensity", Range::positive(), "kg/m³", "ρ*"),
          requiredScalar("solidDensity", Range::positive(), "kg/m³", "ρ_s"),
          requiredScalar("fluidDensity", Range::positive(), "kg/m³", "ρ_f"),
          requiredScalar("airDensity", Range::positive(), "kg/m³", "ρ_air"),
          requiredScalar("relaxation", Range::openClosed(0.0, 1.0), "",
                         "under-relaxation of the viscosity"),
          switchParam("driftFields", false,
                      "drifts from the fields constant/lambdaU, lambdaW and lambdaP or "
                      "porePressureRatio"),
          switchParam("driftTimeVarying", false, "the fields of the windows constant/drifts/<t>/"),
          wordParam("driftInterpolation", "linear", {"linear", "nearest"},
                    "the windows' interpolation in time"),
      });
}
}  // namespace

const Schema& BulkMixtureCoeffs::schema() {
  static const Schema s = makeSchema();
  return s;
}

void BulkMixtureCoeffs::check(const std::string& file, const std::string& phase) {
  const Schema& sc = schema();
  const Dictionary d = Dictionary::readFile(file).subDict(phase).subDict("bulkMixtureCoeffs");
  sc.allowOnly(d, "");
  const std::string rheology = sc.word(d, "solidRheology");
  for (const auto& p : sc.params()) {
    if (!p.onlyFor.empty() &&
        std::find(p.onlyFor.begin(), p.onlyFor.end(), rheology) == p.onlyFor.end()) {
      if (d.has(p.path)) d.fail(p.path, "is not a parameter of solidRheology " + rheology);
      continue;
    }
    switch (p.type) {
      case Param::Type::Scalar:
        sc.scalar(d, p.path);
        break;
      case Param::Type::Word:
        sc.word(d, p.path);
        break;
      case Param::Type::Switch:
        sc.flag(d, p.path);
        break;
      default:
        break;
    }
  }
}

}  // namespace mixflow
