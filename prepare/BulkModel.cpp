#include "BulkModel.h"

#include <filesystem>

#include "Dictionary.h"
#include "DriftAlgebra.h"

namespace mixflow::cfd {

namespace {
constexpr double kGravity = 9.81;

// alpha_s + lambda alpha_f >= kDriftDenominatorMin: Lambda = 1 / (alpha_s + lambda alpha_f).
double readDrift(const Dictionary& d, const std::string& key, double alphaS) {
  // Above 1e3 a drift means a phase at rest against the other: the ratio is then meaningless.
  const double lo = alphaS < 1 ? (bulk::kDriftDenominatorMin - alphaS) / (1 - alphaS) : -1e3;
  return d.scalarOr(key, 1.0, Range::closed(lo, 1e3));
}
}  // namespace

double BulkModel::yieldPressureFactor(double fluidDensity) const {
  return yieldPressure == "paper" ? 1.0 : 1.0 - fluidDensity * lambdaP / solidDensity;
}

double BulkModel::maxViscosity(double height, double fluidDensity, double nuFluidMax) const {
  const bulk::Drifts d{lambdaU, lambdaW, lambdaP};
  const double pS = kGravity * height / bulk::lambdaCoefficients(solidFraction, d).p;
  const bulk::SolidRheology s{solidViscosity, tanPhi, cohesion / solidDensity, regularisation};
  const double nuS = bulk::solidViscosity(s, 0.0, yieldPressureFactor(fluidDensity) * pS);
  return mixtureDensity * bulk::mixtureDiffusivity(solidFraction, d, nuS, nuFluidMax);
}

BulkModel readBulkModel(const std::string& caseDir, double sampleSolidFraction, double solidDensity,
                        double fluidDensity) {
  namespace fs = std::filesystem;
  const fs::path file = fs::path(caseDir) / "constant/bulkProperties";
  const Dictionary d =
      fs::exists(file) ? Dictionary::readFile(file.string()) : Dictionary::parse("", file.string());
  d.allowOnly({"solidFraction", "density", "drifts", "solid", "relaxation"});
  BulkModel b;
  b.solidDensity = solidDensity;
  // 0 is the pore liquid alone (the model is then mixflowFoam's); 0.64 random close packing.
  b.solidFraction = d.scalarOr("solidFraction", sampleSolidFraction, Range::closed(0.0, 0.64));

  const Dictionary dr = d.subDictOrEmpty("drifts");
  dr.allowOnly({"lambdaU", "lambdaW", "lambdaP", "source"});
  b.lambdaU = readDrift(dr, "lambdaU", b.solidFraction);
  b.lambdaW = readDrift(dr, "lambdaW", b.solidFraction);
  b.lambdaP = readDrift(dr, "lambdaP", b.solidFraction);
  if (dr.has("source")) b.driftSource = dr.text("source");

  const Dictionary s = d.subDictOrEmpty("solid");
  s.allowOnly({"viscosity", "tanPhi", "cohesion", "regularisation", "yieldPressure"});
  b.solidViscosity = s.scalarOr("viscosity", b.solidViscosity, Range::nonNegative());
  b.tanPhi = s.scalarOr("tanPhi", b.tanPhi, Range::closed(0.0, 5.0));
  b.cohesion = s.scalarOr("cohesion", b.cohesion, Range::nonNegative());
  b.regularisation = s.scalarOr("regularisation", b.regularisation, Range::closed(0.0, 1e5));
  b.yieldPressure = s.wordOr("yieldPressure", b.yieldPressure, {"paper", "buoyancyReduced"});
  if (b.solidViscosity == 0 && (b.tanPhi == 0 && b.cohesion == 0))
    s.fail("viscosity",
           "value 0 with no yield stress (tanPhi 0, cohesion 0) leaves the grains "
           "without any stress; allowed range (0, inf) then");

  b.relaxation = d.scalarOr("relaxation", b.relaxation, Range::openClosed(0.0, 1.0));
  const double rhoStar = b.solidFraction * solidDensity + (1 - b.solidFraction) * fluidDensity;
  b.mixtureDensity = d.scalarOr("density", rhoStar, Range::closed(10.0, 25000.0));
  return b;
}

}  // namespace mixflow::cfd
