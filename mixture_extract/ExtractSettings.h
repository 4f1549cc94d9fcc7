// Settings of mixflowExtract, read from <case>/system/extractDict (OpenFOAM syntax, validated by
// common/Dictionary: a wrong entry stops with the file, the entry and the allowed range).
// Entries and defaults: ExtractSettings::schema(), shown in docs/parameters.md.
#pragma once

#include <string>
#include <vector>

#include "FluidSource.h"

namespace mixflow {
class Schema;
}
namespace mixflow::dem {
struct Scene;
}

namespace mixflow::mx {

struct TimeWindow {
  double t0 = 0, t1 = 0;  // snapshots with t0 - tol <= t < t1 - tol belong to the window
  std::string origin;     // entry that defined it, for messages: "windows.list (3rd pair)"
};

struct Region {
  std::string name;
  double x0 = 0, x1 = 0, y0 = 0, y1 = 0;  // bins whose centre lies inside belong to the region
};

struct Thresholds {
  double minVelocity = 1e-3;       // m/s: |u_s| (|w_s|) below -> lambda_u (lambda_w) masked
  double minPressure = 1.0;        // Pa: |p_s| below -> lambda_p masked
  double minSolidFraction = 0.05;  // alpha_s below -> bin not in the mixture
  double minSaturation = 0.9;      // liquid share of the bin's fluid volume below -> not saturated
  double minDenominator = 1e-6;    // |alpha_s + lambda alpha_f| below -> Lambda masked
  long minParticleSamples = 1;     // particle-snapshot samples in the bin below -> u_s, p_s masked
  double minLiquidShare = 0.01;  // liquid share of the bin's fluid volume below -> u_f, p_f masked
};

struct ExtractSettings {
  std::string dictFile;
  std::string dictText;  // the file as read (stored in the output)
  double x0 = 0, x1 = 0, y0 = 0, y1 = 0;
  int nx = 0, ny = 0;
  std::vector<TimeWindow> windows;
  bool windowsGenerated = false;            // start/end/width (true) or an explicit list (false)
  double windowStart = 0, windowWidth = 0;  // windows.start, windows.width (generated windows)
  std::string windowStartWhere, windowWidthWhere;  // "file: entry 'windows.width' (line N)"
  Thresholds thresholds;
  std::string pressureConvention = "both";  // raw | density | both
  // kg/m3 (density convention of lambda_p): extractDict liquidDensity if given, else
  // sceneProperties liquid.density; 0 when neither exists (a dry scene).
  double liquidDensity = 0;
  std::string liquidDensitySource;   // where liquidDensity came from (stored in the output)
  std::string liquidDensityWarning;  // set when liquidDensity overrides a different liquid.density
  double solidDensity = 0;           // kg/m3, from sceneProperties particles.density
  bool haveViscosities = false;
  double nuSolid = 0, nuFluid = 0;   // m2/s, for the Lambda_eta coefficients (Eqs. 36, 40, 43)
  std::string fluidSource = "auto";  // auto | none | openfoam
  FoamFieldNames fluidNames;
  std::string stressKineticTerm = "auto";  // auto | included | excluded
  // Contact stress: auto (contact snapshots when the case has them, else virial) | contacts
  // (along each contact line, walls included) | virial (each particle's stress/atom).
  std::string stressSource = "auto";
  std::string kernelShape = "bins";  // bins | lucy | gaussian (CoarseGrainKernel.h)
  double kernelWidth = 2;            // w in particle diameters (lucy, gaussian)
  double kernelWidthMetres = 0;      // w in metres
  double timeTolerance = 0;          // s
  // s: a fluid time pairs with the nearest particle snapshot at most this far from it.
  double pairTolerance = 0;
  std::string pairToleranceWhere;
  std::vector<Region> regions;
  std::string output = "postProcessing/mixture/mixture";  // case-relative base name

  // Every entry of system/extractDict once: type, default, range or words, unit, meaning.
  static const Schema& schema();
  static ExtractSettings read(const std::string& dictFile, const dem::Scene& scene);
  // Canonical text of every setting that changes per-window results (not the window list): an
  // existing output is appended to only when this is unchanged.
  std::string fingerprint() const;
  bool wantRaw() const { return pressureConvention != "density"; }
  bool wantDensity() const { return pressureConvention != "raw"; }
};

}  // namespace mixflow::mx
