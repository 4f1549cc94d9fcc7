#include "LiquidCase.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <vector>

#include "Dictionary.h"

namespace mixflow::cfd {

namespace {
std::string shortNum(double v) { return formatNumber(v, 6); }
}  // namespace

double LiquidCase::maxViscosity() const {
  if (bulkModel()) {
    const double nuFluid = liquid.yieldStressModel() ? liquid.nu0() : liquid.nu();
    return bulk.maxViscosity(sample.height, liquid.density, nuFluid);
  }
  return liquid.yieldStressModel() ? liquid.viscosityCap : liquid.viscosity;
}

double LiquidCase::minCellSize() const {
  double h = std::min(dx(), dy());
  if (numerics.dimensions == 3) h = std::min(h, dz());
  return h;
}

double LiquidCase::viscousNumber() const {
  const double dt = coupledDeltaT > 0 ? coupledDeltaT : maxDeltaTUsed();
  const double h = minCellSize();
  return maxViscosity() * dt / (phaseDensity() * h * h);
}

int LiquidCase::nCorrectorsUsed() const {
  if (numerics.nCorrectors > 0) return numerics.nCorrectors;
  // Measured on a 2-D column (bench/piso_correctors.py, results/bench/piso_correctors.csv):
  // up to D = 20, 3 correctors stay within 0.7 % of a 20-corrector run's front advance; at
  // D = 40 they are 38 % off and 10 are within 0.2 %; at D = 100 three and four diverge.
  return viscousNumber() <= kViscousNumberFewCorrectors ? 3 : 10;
}

double LiquidCase::pressureToleranceUsed() const {
  if (numerics.pressureTolerance > 0) return numerics.pressureTolerance;
  // Measured on arrested Bingham slumps: 1e-7 lets them restart (tau_y 100 Pa, D = 4000: the
  // kinetic energy after arrest reaches 11 E_p0), 1e-9 holds them at D = 4000, but at D = 1.6e4
  // (2.5 mm cells) 1.25e-10 lets the front creep 8 % past x_f and 1e-11 still restarts to
  // 2e-5 E_p0, while 1e-12 holds: the need grows as D^2, not D.
  const double r = std::min(1.0, kViscousNumberFewCorrectors / viscousNumber());
  return std::max(kPressureTolerance * r * r, kPressureToleranceMin);
}

double LiquidCase::maxDeltaTUsed() const {
  if (coupledDeltaT > 0) return numerics.maxDeltaT;
  const double h = minCellSize();
  return std::min(numerics.maxDeltaT, kViscousNumberMax * phaseDensity() * h * h / maxViscosity());
}

LiquidCase LiquidCase::read(const std::string& caseDir) {
  namespace fs = std::filesystem;
  if (!fs::is_directory(caseDir)) throw InputError(caseDir + ": case directory does not exist");
  LiquidCase c;
  c.caseDir = caseDir;
  c.name = fs::path(caseDir).lexically_normal().filename().string();
  if (c.name.empty() || c.name == ".")
    c.name = fs::absolute(caseDir).lexically_normal().parent_path().filename().string();

  const Dictionary sceneDict =
      Dictionary::readFile((fs::path(caseDir) / "constant/sceneProperties"));
  if (SceneProperties::readContent(sceneDict) == "particles")
    sceneDict.fail("content",
                   "'particles' needs no fluid case (run mixflowDem); mixflowPrepare prepares "
                   "content liquid or mixture (and checks any content with -check)");
  const SceneProperties scene = SceneProperties::read(sceneDict, SceneProperties::Half::fluid);
  c.content = scene.content;
  c.sample = scene.sample;
  c.channel = scene.channel;
  c.liquid = scene.liquid;
  c.air = scene.air;
  c.gate = scene.gate;
  c.surfaceTension = scene.surfaceTension;

  const Dictionary cfd = Dictionary::readFile((fs::path(caseDir) / "system/cfdDict"));
  const CfdDict cfdDict = CfdDict::read(cfd);
  c.numerics = cfdDict.numerics;
  c.observables = cfdDict.observables;
  if (c.numerics.mixtureModel == "bulk") {
    if (c.content != "mixture")
      cfd.fail("mixtureModel",
               "bulk models a mixture of grains and liquid; this scene's content "
               "is " +
                   c.content + " (allowed: cfdDem for it)");
    c.bulk = readBulkModel(caseDir, c.sample.solidFraction, scene.particles.density,
                           c.liquid.density, scene.particles.diameter);
  }

  // The user's controlDict: it includes controlDict.generated (FoamCaseWriter) and is not
  // rewritten.
  const Dictionary control = Dictionary::readFile((fs::path(caseDir) / "system/controlDict"));
  const RunTimes times = readRunTimes(control);
  c.endTime = times.endTime;
  c.writeInterval = times.writeInterval;

  // Cross-entry checks, named by the entry that has to change.
  double h = c.numerics.cellSize > 0 ? c.numerics.cellSize : c.sample.height / 20.0;
  c.nx = std::max(1, static_cast<int>(std::lround(c.channel.length / h)));
  c.ny = std::max(1, static_cast<int>(std::lround(c.channel.height / h)));
  c.nz = c.numerics.dimensions == 2
             ? 1
             : std::max(1, static_cast<int>(std::lround(c.sample.width / h)));
  const double cellsOverH = c.sample.height / c.dy();
  if (cellsOverH < 4.0)
    cfd.fail("cellSize", "value " + shortNum(h) + " m leaves " + shortNum(cellsOverH) +
                             " cells over the sample height " + shortNum(c.sample.height) +
                             " m; at least 4 are needed, allowed range (0, " +
                             shortNum(c.sample.height / 4.0) + "]");
  const double cells = double(c.nx) * c.ny * c.nz;
  // The bulk model's drift fields hold one value per cell of the mesh made here.
  if (c.bulkModel() && c.bulk.driftFields && c.bulk.driftFieldCells >= 0 &&
      c.bulk.driftFieldCells != static_cast<long>(cells))
    throw InputError(c.bulk.driftFieldFile + ": internalField has " +
                     std::to_string(c.bulk.driftFieldCells) + " cells, but the mesh of " +
                     (fs::path(caseDir) / "system/cfdDict").string() + " (cellSize " + shortNum(h) +
                     " m) has " + shortNum(cells) + " = " + std::to_string(c.nx) + " x " +
                     std::to_string(c.ny) + " x " + std::to_string(c.nz) +
                     "; allowed: " + shortNum(cells) +
                     " values, or uniform (calibrate_drifts.py --fields writes them on the "
                     "case's mesh: run mixflowPrepare and blockMesh first)");
  if (cells > 5e7)
    cfd.fail("cellSize", "value " + shortNum(h) + " m gives " + shortNum(cells) +
                             " cells (limit 5e7); use a larger cell size or dimensions 2");
  if (c.gate.lifted()) {
    // The plate's cells are those whose centres lie in [L, L + thickness). It must be two cells
    // thick: the pressure equation takes a face's 1/A as the mean of its two cells', so a face
    // between a held cell and a free one is half open, and a one-cell plate lets the liquid
    // through (measured: 28 % of a held water column beyond it after 0.2 s; two cells: 2e-22).
    if (c.gate.thickness == 0) c.gate.thickness = kGatePlateCells * c.dx();
    const double room = c.channel.length - c.sample.length;
    const double least = kGatePlateCells * c.dx();
    if (c.gate.thickness < least * (1 - 1e-9) || c.gate.thickness >= room)
      sceneDict.subDict("gate").fail(
          "thickness", "value " + shortNum(c.gate.thickness) +
                           " m: the plate must hold two cells along x (cfdDict cellSize gives " +
                           shortNum(c.dx()) +
                           " m; one cell lets the liquid through) and end "
                           "before the outlet; allowed range [" +
                           shortNum(least) + ", " + shortNum(room) + ")");
  }
  if (c.observables.sectionX >= c.channel.length) {
    // The paper's section (1.38 m) is outside a short test channel: no section then. A section
    // asked for explicitly must lie inside.
    const Dictionary ob = cfd.subDictOrEmpty("observables");
    if (ob.has("sectionX"))
      ob.fail("sectionX", "value " + shortNum(c.observables.sectionX) +
                              " must lie inside the channel, allowed range (0, " +
                              shortNum(c.channel.length) + ")");
    c.observables.sectionX = -1;
  }
  return c;
}

}  // namespace mixflow::cfd
