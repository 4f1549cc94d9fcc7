#include "BulkModel.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <set>

#include "Dictionary.h"
#include "DriftAlgebra.h"
#include "FoamFieldFile.h"
#include "Schema.h"

namespace mixflow::cfd {

namespace {
constexpr double kGravity = 9.81;

Schema makeSchema() {
  const BulkModel b{};
  const std::string drift = "α_s + λ α_f ≥ 0.01";  // Λ = 1 / (α_s + λ α_f) stays finite
  return Schema(
      "constant/bulkProperties",
      {
          // 0 is the pore liquid alone (the model is then mixflowFoam's); 0.64 random close
          // packing.
          scalarParam("solidFraction", 0, Range::closed(0.0, 0.64), "",
                      "α_s of the mixture, constant")
              .shownDefault("sceneProperties `sample.solidFraction`"),
          scalarParam("density", 0, Range::closed(10.0, 25000.0), "kg/m³",
                      "ρ*, the mixture's constant density")
              .shownDefault("α_s ρ_s + α_f ρ_f")
              .plausible(Range::closed(10.0, 25000.0), "a mixture of grains and a fluid",
                         {{"g/cm³", 1e3}}),
          dictParam("drifts", "the drift coefficients (kinematic pressures)"),
          scalarParam("drifts.lambdaU", b.lambdaU, Range::closed(-1e3, 1e3), "", "u_f = λ_u u_s")
              .alsoAllowed(drift),
          scalarParam("drifts.lambdaW", b.lambdaW, Range::closed(-1e3, 1e3), "", "w_f = λ_w w_s")
              .alsoAllowed(drift),
          wordParam("drifts.pressure", b.pressureClosure, {"porePressureRatio", "lambdaP"},
                    "the pore-pressure closure (docs/bulk_model.md): porePressureRatio, the "
                    "excess pore pressure χ times the grains' buoyant load, σ′ = (1 − χ) α_s "
                    "(ρ_s − ρ_f) p_m (no pole; χ = 0 is λ_p = 1); lambdaP, the paper's p_f = λ_p "
                    "p_s, p_m = (α_s + λ_p α_f) p_s"),
          scalarParam("drifts.porePressureRatio", b.porePressureRatio,
                      Range{bulk::kPoreRatioMin, bulk::kPoreRatioMax, false, true}, "",
                      "χ = (P_f − ρ_f p_m) / (α_s (ρ_s − ρ_f) p_m): 0 hydrostatic pore liquid, 1 "
                      "liquefied, < 0 suction (−1: as large as the grains' buoyant load)")
              .only({"porePressureRatio"}),
          scalarParam("drifts.lambdaP", b.lambdaP, Range::closed(-1e3, 1e3), "", "p_f = λ_p p_s")
              .only({"lambdaP"})
              .alsoAllowed(drift),
          switchParam("drifts.fields", b.driftFields,
                      "take λ_u, λ_w and χ (or λ_p) cell by cell from the volScalarFields "
                      "constant/lambdaU, lambdaW and porePressureRatio (or lambdaP) "
                      "(`calibrate_drifts.py --fields`; each cell held to the constants' range); "
                      "off: the constants"),
          switchParam("drifts.timeVarying", b.driftTimeVarying,
                      "with `fields on`: fields that change in time, one set per extraction "
                      "window, constant/drifts/<t>/lambdaU, lambdaW, porePressureRatio or lambdaP "
                      "(t the window's "
                      "centre in s; `calibrate_drifts.py --fields --per-window`; every window's "
                      "cells held to the constants' range), taken at the solver's time as "
                      "`interpolation` says; off: the fixed fields"),
          wordParam("drifts.interpolation", b.driftInterpolation, {"linear", "nearest"},
                    "with `timeVarying on`: linear in time between the two windows around t, or "
                    "the fields of the window whose centre is nearest t; before the first and "
                    "after the last window their fields hold"),
          textParam("drifts.source", b.driftSource,
                    "what set the drifts (scripts/calibrate_drifts.py records the case and its "
                    "file's sha256)"),
          dictParam("solid", "the grains' rheology; its `rheology` selects its entries"),
          wordParam(
              "solid.rheology", b.solidRheology, {"coulombViscoplastic", "muI"},
              "coulombViscoplastic: ν_se = ν_s + τ_ys (1 − e^{−m_y D})/D; muI (Jop et al. "
              "2006): ν_se = μ(I) κ_y p_s (1 − e^{−m_y D})/D, μ(I) = μ_s + (μ_2 − μ_s)/(I_0/I "
              "+ 1), I = D d/√(κ_y p_s); D = √(2 D:D), the shear rate of a simple shear"),
          scalarParam("solid.viscosity", b.solidViscosity, Range::nonNegative(), "m²/s",
                      "ν_s of coulombViscoplastic; with tanφ 0.45 the bulk P follows its DEM "
                      "front within an RMS 2.8 % (full width; 3.7 % on the mixtures' 0.12 m "
                      "slice) and misses its deposit h(x) by 30 % (24 %); mixflow calibrate-solid, "
                      "results/bulk_model/solid_calibration*.json")
              .only({"coulombViscoplastic"})
              .alsoAllowed("> 0 without a yield stress"),
          scalarParam("solid.tanPhi", b.tanPhi, Range::closed(0.0, 5.0), "",
                      "tanφ of coulombViscoplastic, the yield stress's pressure coefficient; "
                      "calibrated on P's front with ν_s (the grid's best by the front, 0.4 with "
                      "0.03 m²/s, is the same at full width and on the slice)")
              .only({"coulombViscoplastic"}),
          scalarParam("solid.cohesion", b.cohesion, Range::nonNegative(), "Pa",
                      "τ_c of coulombViscoplastic")
              .only({"coulombViscoplastic"}),
          scalarParam("solid.muS", b.muS, Range::closed(0.0, 5.0), "",
                      "μ_s of muI; default tan 20.9°, glass beads (GDR MiDi 2004, Jop et al. "
                      "2006); a dry layer (λ_p = 0) rests below tan θ = μ_s (docs/bulk_model.md)")
              .only({"muI"}),
          scalarParam("solid.mu2", b.mu2, Range::closed(0.0, 5.0), "",
                      "μ_2 of muI, the friction as I → ∞; default tan 32.76°, glass beads")
              .only({"muI"})
              .alsoAllowed("≥ μ_s"),
          scalarParam("solid.I0", b.inertialNumber0, Range::openClosed(0.0, 100.0), "",
                      "I_0 of muI, the inertial number of μ = (μ_s + μ_2)/2; default glass beads")
              .only({"muI"}),
          scalarParam("solid.grainDiameter", b.grainDiameter, Range::openClosed(0.0, 1.0), "m",
                      "d of muI's inertial number")
              .only({"muI"})
              .shownDefault("sceneProperties `particles.diameter`"),
          scalarParam("solid.regularisation", b.regularisation, Range::closed(0.0, 1e5), "s",
                      "m_y of ν_se = ν_s + τ_ys (1 − e^{−m_y D})/D (D the strain rate's "
                      "magnitude); at rest ν_s + m_y τ_ys; muI: the same factor, at rest "
                      "μ_s κ_y p_s m_y, a creep rate ≤ ln(μ_s/(μ_s − τ/(κ_y p_s)))/m_y below μ_s")
              .alsoAllowed("> 0 for muI"),
          wordParam("solid.yieldPressure", b.yieldPressure, {"paper", "buoyancyReduced"},
                    "the yield's pressure: the solid's partial pressure P_s/ρ_s (paper; κ_y = 1) "
                    "or the effective stress σ′/(α_s ρ_s) (buoyancyReduced; κ_y = 1 − ρ_f λ_p/ρ_s) "
                    "in τ_ys = τ_c/ρ_s + tanφ κ_y p_s (muI: the pressure of μ(I) and of I)"),
          dictParam("basal", "the mixture's sliding law at the bed (the bottom wall)"),
          wordParam("basal.law", b.basalLaw, {"noSlip", "coulomb"},
                    "noSlip, or coulomb: the bed's shear stress limited to tan δ_m ρ* p_m "
                    "(bulkCoulombSlip; the bed sticks below it; the air stays no-slip)"),
          scalarParam("basal.tanDelta", b.tanDelta, Range::closed(0.0, 5.0), "",
                      "μ_m = tan δ_m of the coulomb law (0: free slip); default the DEM's wall "
                      "friction, not calibrated"),
          scalarParam("relaxation", b.relaxation, Range::openClosed(0.0, 1.0), "",
                      "under-relaxation of the viscosity between PIMPLE correctors"),
      });
}

// The declared drift, in the range that keeps alpha_s + lambda alpha_f >= kDriftDenominatorMin.
double readDrift(const Dictionary& d, const std::string& key, double alphaS) {
  const Param& p = BulkModel::schema().param("drifts." + key);
  return d.scalarOr(key, p.number,
                    Range::closed(bulk::driftLowerBound(alphaS, p.range.lo), p.range.hi));
}

namespace fs = std::filesystem;

// The drift fields lambdaU, lambdaW, lambdaP of DIR: their cells' distinct (lambdaU, lambdaW,
// lambdaP) triples go into DISTINCT, so that the time-step bound sees every cell; every file
// must hold CELLS cells (set by the first nonuniform file, -1 before). The values are
// range-checked cell by cell by mixflowBulkFoam, which has the mesh; here a missing file is
// refused at ENTRY of the drifts block, with MISSING saying what writes it.
void addFieldDrifts(const fs::path& dir, const Dictionary& dr, const std::string& entry,
                    const std::string& missing, const std::string& poreField, long& cells,
                    std::string& firstFile, std::set<std::array<double, 3>>& distinct) {
  std::vector<std::vector<double>> values;
  for (const std::string f : {std::string("lambdaU"), std::string("lambdaW"), poreField}) {
    const fs::path field = dir / f;
    if (!fs::exists(field))
      dr.fail(entry, "on, but there is no " + field.string() + " (" + missing + ")");
    long n = -1;
    values.push_back(readInternalField(field.string(), 1, n));
    if (n >= 0 && cells >= 0 && n != cells)
      throw InputError(field.string() + ": internalField has " + std::to_string(n) +
                       " cells, the other drift fields " + std::to_string(cells));
    if (n >= 0 && cells < 0) firstFile = field.string();
    if (n >= 0) cells = n;
  }
  const auto at = [](const std::vector<double>& v, long i) { return v.size() == 1 ? v[0] : v[i]; };
  for (long i = 0; i < std::max(cells, 1L); ++i)
    distinct.insert({at(values[0], i), at(values[1], i), at(values[2], i)});
}

// The windows of time-varying drift fields: the subdirectories of DIR named by a number, as
// OpenFOAM names time directories (mixflowBulkFoam lists them so), ascending by time.
std::vector<std::pair<double, std::string>> driftWindows(const fs::path& dir,
                                                         const Dictionary& dr) {
  std::vector<std::pair<double, std::string>> windows;
  if (fs::is_directory(dir)) {
    for (const auto& e : fs::directory_iterator(dir)) {
      const std::string name = e.path().filename().string();
      double t = 0;
      const auto r = std::from_chars(name.data(), name.data() + name.size(), t);
      if (e.is_directory() && r.ec == std::errc() && r.ptr == name.data() + name.size() &&
          std::isfinite(t))
        windows.emplace_back(t, name);
    }
  }
  if (windows.empty())
    dr.fail("timeVarying", "on, but " + dir.string() +
                               " holds no window (a directory named by its time, e.g. 0.05/, "
                               "with lambdaU, lambdaW, lambdaP; scripts/calibrate_drifts.py "
                               "--fields --per-window writes them)");
  std::sort(windows.begin(), windows.end());
  for (size_t i = 1; i < windows.size(); ++i)
    if (windows[i].first == windows[i - 1].first)
      dr.fail("timeVarying", dir.string() +
                                 " has two windows at t = " + docNumber(windows[i].first) + ": " +
                                 windows[i - 1].second + "/ and " + windows[i].second + "/");
  return windows;
}
}  // namespace

const Schema& BulkModel::schema() {
  static const Schema s = makeSchema();
  return s;
}

bool BulkModel::poreRatio() const { return pressureClosure == "porePressureRatio"; }

std::string BulkModel::poreField() const { return poreRatio() ? "porePressureRatio" : "lambdaP"; }

double BulkModel::maxViscosity(double height, double fluidDensity, double nuFluidMax) const {
  const double pore = poreRatio() ? porePressureRatio : lambdaP;
  double mu = maxViscosity(height, fluidDensity, nuFluidMax, {lambdaU, lambdaW, pore});
  const Schema& sc = schema();
  const auto inRange = [&](double v, const std::string& key) {
    const Range& r = sc.param("drifts." + key).range;
    if (key == "porePressureRatio") return r.contains(v);
    return v >= bulk::driftLowerBound(solidFraction, r.lo) && v <= r.hi;
  };
  for (const auto& c : fieldDrifts)
    if (inRange(c[0], "lambdaU") && inRange(c[1], "lambdaW") && inRange(c[2], poreField()))
      mu = std::max(mu, maxViscosity(height, fluidDensity, nuFluidMax, c));
  return mu;
}

double BulkModel::maxViscosity(double height, double fluidDensity, double nuFluidMax,
                               const std::array<double, 3>& cell) const {
  // The drifts of a field cell (lambdaU, lambdaW, the closure's value), the rest the constants'.
  const bulk::Drifts d = poreRatio() ? bulk::Drifts{cell[0], cell[1], lambdaP, cell[2]}
                                     : bulk::Drifts{cell[0], cell[1], cell[2], porePressureRatio};
  const bulk::PorePressure pore{poreRatio() ? bulk::PoreClosure::ratio : bulk::PoreClosure::lambdaP,
                                yieldPressure == "buoyancyReduced", solidDensity, fluidDensity};
  const double py = kGravity * height * bulk::yieldPressureFactor(solidFraction, d, pore);
  const double nuS =
      solidRheology == "muI"
          ? bulk::solidViscosity(
                bulk::MuIRheology{muS, mu2, inertialNumber0, grainDiameter, regularisation}, 0.0,
                py)
          : bulk::solidViscosity(bulk::SolidRheology{solidViscosity, tanPhi,
                                                     cohesion / solidDensity, regularisation},
                                 0.0, py);
  return mixtureDensity * bulk::mixtureDiffusivity(solidFraction, d, nuS, nuFluidMax);
}

BulkModel readBulkModel(const std::string& caseDir, double sampleSolidFraction, double solidDensity,
                        double fluidDensity, double grainDiameter) {
  const fs::path file = fs::path(caseDir) / "constant/bulkProperties";
  const Dictionary d =
      fs::exists(file) ? Dictionary::readFile(file.string()) : Dictionary::parse("", file.string());
  const Schema& sc = BulkModel::schema();
  sc.allowOnly(d, "");
  BulkModel b;
  b.solidDensity = solidDensity;
  b.solidFraction = d.has("solidFraction") ? sc.scalar(d, "solidFraction") : sampleSolidFraction;

  const Dictionary dr = d.subDictOrEmpty("drifts");
  sc.allowOnly(dr, "drifts");
  b.lambdaU = readDrift(dr, "lambdaU", b.solidFraction);
  b.lambdaW = readDrift(dr, "lambdaW", b.solidFraction);
  b.pressureClosure = sc.word(dr, "drifts.pressure");
  // An entry of the other closure is named as such, not silently ignored.
  const std::vector<std::string> closureKeys = sc.keys("drifts", b.pressureClosure);
  for (const auto& k : dr.keys())
    if (std::find(closureKeys.begin(), closureKeys.end(), k) == closureKeys.end())
      dr.fail(k, "is not a parameter of pressure " + b.pressureClosure + " (drifts.pressure)");
  if (b.poreRatio())
    b.porePressureRatio = sc.scalar(dr, "drifts.porePressureRatio");
  else
    b.lambdaP = readDrift(dr, "lambdaP", b.solidFraction);
  b.driftSource = sc.text(dr, "drifts.source");
  // Drifts set by hand without a source are named as such, not as the default.
  if (!dr.has("source") &&
      (dr.has("lambdaU") || dr.has("lambdaW") || dr.has("lambdaP") || dr.has("porePressureRatio")))
    b.driftSource = file.string() + " drifts";
  b.driftFields = sc.flag(dr, "drifts.fields");
  b.driftTimeVarying = sc.flag(dr, "drifts.timeVarying");
  b.driftInterpolation = sc.word(dr, "drifts.interpolation");
  if (b.driftTimeVarying && !b.driftFields)
    dr.fail("timeVarying",
            "on needs fields on (the windows replace the fixed fields); allowed: "
            "off without fields");
  if (dr.has("interpolation") && !b.driftTimeVarying)
    dr.fail("interpolation", "applies to time-varying drift fields only (drifts.timeVarying on)");
  if (b.driftFields) {
    // The files must be there (a case without them fails before anything is written) and the
    // values of every window feed the time-step bound.
    std::set<std::array<double, 3>> distinct;
    long cells = -1;
    const fs::path constant = fs::path(caseDir) / "constant";
    if (b.driftTimeVarying) {
      for (const auto& [t, name] : driftWindows(constant / "drifts", dr)) {
        addFieldDrifts(constant / "drifts" / name, dr, "timeVarying",
                       "scripts/calibrate_drifts.py --fields --per-window writes lambdaU, "
                       "lambdaW and " +
                           b.poreField() + " in every window",
                       b.poreField(), cells, b.driftFieldFile, distinct);
        b.driftWindowTimes.push_back(t);
      }
    } else {
      addFieldDrifts(constant, dr, "fields",
                     "a volScalarField; scripts/calibrate_drifts.py --fields writes lambdaU, "
                     "lambdaW and " +
                         b.poreField(),
                     b.poreField(), cells, b.driftFieldFile, distinct);
    }
    b.fieldDrifts.assign(distinct.begin(), distinct.end());
    b.driftFieldCells = cells;
  }

  const Dictionary s = d.subDictOrEmpty("solid");
  sc.allowOnly(s, "solid");
  b.solidRheology = sc.word(s, "solid.rheology");
  // An entry of the other law is named as such, not silently ignored.
  const std::vector<std::string> allowed = sc.keys("solid", b.solidRheology);
  for (const auto& k : s.keys())
    if (std::find(allowed.begin(), allowed.end(), k) == allowed.end())
      s.fail(k, "is not a parameter of rheology " + b.solidRheology + " (solid.rheology)");
  b.regularisation = sc.scalar(s, "solid.regularisation");
  b.yieldPressure = sc.word(s, "solid.yieldPressure");
  if (b.solidRheology == "muI") {
    b.muS = sc.scalar(s, "solid.muS");
    b.mu2 = sc.scalar(s, "solid.mu2");
    b.inertialNumber0 = sc.scalar(s, "solid.I0");
    b.grainDiameter = s.has("grainDiameter") ? sc.scalar(s, "solid.grainDiameter") : grainDiameter;
    if (b.mu2 < b.muS)
      s.fail("mu2", "value " + docNumber(b.mu2) + " is below muS " + docNumber(b.muS) +
                        "; allowed range [muS, 5]");
    if (b.regularisation == 0)
      s.fail("regularisation", "value 0 leaves muI without any stress; allowed range (0, 1e5]");
    if (!(b.grainDiameter > 0))
      s.fail("grainDiameter",
             "missing: sceneProperties particles.diameter is not positive; "
             "allowed range (0, 1] m");
  } else {
    b.solidViscosity = sc.scalar(s, "solid.viscosity");
    b.tanPhi = sc.scalar(s, "solid.tanPhi");
    b.cohesion = sc.scalar(s, "solid.cohesion");
    if (b.solidViscosity == 0 && (b.tanPhi == 0 && b.cohesion == 0))
      s.fail("viscosity",
             "value 0 with no yield stress (tanPhi 0, cohesion 0) leaves the grains "
             "without any stress; allowed range (0, inf) then");
  }

  const Dictionary basal = d.subDictOrEmpty("basal");
  sc.allowOnly(basal, "basal");
  b.basalLaw = sc.word(basal, "basal.law");
  b.tanDelta = sc.scalar(basal, "basal.tanDelta");

  b.relaxation = sc.scalar(d, "relaxation");
  const double rhoStar = b.solidFraction * solidDensity + (1 - b.solidFraction) * fluidDensity;
  b.mixtureDensity = d.has("density") ? sc.scalar(d, "density") : rhoStar;
  return b;
}

}  // namespace mixflow::cfd
