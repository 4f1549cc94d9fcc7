// Fluid fields for the extractor, read through this small interface so that the binning does not
// depend on OpenFOAM (FoamFluidSource reads mixflowCoupled's or mixflowFoam's time directories;
// SyntheticFluidSource feeds tests): for a time, every fluid cell's centre, volume, liquid
// fraction alpha_l (VOF, share of the fluid that is liquid), fluid volume fraction eps_f
// (= 1 - particle fraction of the cell), velocity U (x, y) and pressure p.
// Cells are binned by centre with weight alpha_l eps_f V (the liquid volume of the cell).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace mixflow::mx {

struct FluidCells {
  std::vector<double> x, y;    // cell centre (m); z is averaged over
  std::vector<double> volume;  // V (m3)
  std::vector<double> alphaL;  // liquid fraction of the fluid (-)
  std::vector<double> epsF;    // fluid volume fraction (-)
  std::vector<double> ux, uy;  // fluid velocity (m/s)
  std::vector<double> p;       // pressure (Pa)
  size_t size() const { return x.size(); }
  void resize(size_t n);
};

class FluidSource {
 public:
  virtual ~FluidSource() = default;
  virtual std::vector<double> times() const = 0;  // ascending
  virtual FluidCells cells(double time) const = 0;
  virtual std::string describe() const = 0;  // written to the output attributes
};

// Test source: a regular lattice of cells (nx x ny over a box, one cell across the width) with the
// state given by a function of (x, y, t).
struct FluidState {
  double alphaL = 1, epsF = 1, ux = 0, uy = 0, p = 0;
};
class SyntheticFluidSource : public FluidSource {
 public:
  using Field = std::function<FluidState(double x, double y, double t)>;
  SyntheticFluidSource(double x0, double x1, int nx, double y0, double y1, int ny, double width,
                       std::vector<double> times, Field field);
  std::vector<double> times() const override { return times_; }
  FluidCells cells(double time) const override;
  std::string describe() const override;

 private:
  double x0_, x1_, y0_, y1_, width_;
  int nx_, ny_;
  std::vector<double> times_;
  Field field_;
};

// Settings of the OpenFOAM reader (extractDict `fluid { ... }`).
struct FoamFieldNames {
  // "auto": alpha.liquid (mixflowPrepare's cases) if the time has it, else alpha.water
  // (interFoam's tutorials); "none": alpha_l = 1.
  std::string liquidFraction = "auto";
  std::string voidFraction = "voidfraction";  // "none": eps_f = 1 (pure-liquid cases)
  std::string velocity = "U";
  std::string pressure = "p";  // static pressure in Pa (interFoam family)
  std::string centres = "C";   // postProcess -func writeCellCentres
  std::string volumes = "V";   // postProcess -func writeCellVolumes
};

// OpenFOAM ASCII time directories of <caseDir> (or of <caseDir>/processor* when decomposed; the
// processors' cells are concatenated). Fields: volScalarField / volVectorField with internalField
// `uniform v` or `nonuniform List<...> N ( ... )`. C and V are looked up in the time directory,
// then in 0/ and constant/ (a static mesh).
class FoamFluidSource : public FluidSource {
 public:
  FoamFluidSource(std::string caseDir, FoamFieldNames names);
  std::vector<double> times() const override { return times_; }
  FluidCells cells(double time) const override;
  std::string describe() const override;
  // True when the case holds at least one time directory with the velocity field.
  static bool present(const std::string& caseDir, const FoamFieldNames& names);

 private:
  std::string caseDir_;
  FoamFieldNames names_;
  std::vector<std::string> roots_;  // caseDir or its processor* directories
  std::vector<double> times_;
  std::vector<std::string> timeNames_;
};

}  // namespace mixflow::mx
