// The quasi two-phase bulk model of a mixture scene (docs/bulk_model.md), chosen by system/cfdDict
// `mixtureModel bulk;` and set by constant/bulkProperties (optional: every entry has a default,
// declared once in schema(), whose table docs/parameters.md "Bulk model" shows). SI input;
// writeFoamCase derives the kinematic coefficients of mixflowBulkFoam's bulkMixture viscosity model
// from it.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "Schema.h"

namespace mixflow::cfd {

struct BulkModel {
  static const Schema& schema();

  double solidFraction = 0;  // alpha_s: bulkProperties solidFraction, else sample.solidFraction
  // Drifts u_f = lambdaU u_s, w_f = lambdaW w_s; the pore-pressure closure: the ratio chi
  // (porePressureRatio) or p_f = lambdaP p_s (kinematic pressures).
  double lambdaU = 1, lambdaW = 1, lambdaP = 1;
  std::string pressureClosure = "porePressureRatio";  // porePressureRatio | lambdaP
  double porePressureRatio = 0;                       // chi

  std::string driftSource = "default (lambda = 1)";  // what set them (mixflowCalibrate records it)
  // drifts.fields on: the solver takes lambdaU, lambdaW and the closure's chi or lambdaP cell by
  // cell from the fields constant/lambdaU, ... (stage C of docs/calibration.md); fieldDrifts
  // holds their distinct cell triples, so that the time-step bound sees every cell.
  bool driftFields = false;
  std::vector<std::array<double, 3>> fieldDrifts;
  // Cells of the drift fields' nonuniform internalFields (-1: all uniform), and the first file
  // read, for the check against the mesh mixflowPrepare makes (LiquidCase::read).
  long driftFieldCells = -1;
  std::string driftFieldFile;
  // drifts.timeVarying on (with fields): the fields change in time, one set per extraction window
  // in constant/drifts/<t>/ (t the window's centre in s, ascending in driftWindowTimes), taken at
  // the solver's time as driftInterpolation says; fieldDrifts then holds every window's cells.
  bool driftTimeVarying = false;
  std::string driftInterpolation = "linear";  // linear | nearest
  std::vector<double> driftWindowTimes;
  // Solid rheology: coulombViscoplastic, tau_ys = cohesion + tanPhi p_s, regularised as Domnik
  // et al. (nu_s and tanPhi calibrated on the dry scene P against its DEM run,
  // docs/calibration.md); or muI (Jop et al. 2006) with the same pressure and regularisation.
  std::string solidRheology = "coulombViscoplastic";  // coulombViscoplastic | muI
  double solidViscosity = 0.02;                       // nu_s (m2/s, kinematic as in the paper)
  double tanPhi = 0.45;                               // pressure coefficient of the yield stress
  double cohesion = 0;                                // Pa
  double regularisation = 100;                        // m_y (s)
  std::string yieldPressure = "buoyancyReduced";      // paper | buoyancyReduced
  // mu(I): GDR MiDi (2004) / Jop et al. (2006) glass beads; d: sceneProperties particles.diameter.
  double muS = 0.3818628674187188;  // tan 20.9 deg
  double mu2 = 0.6434683848584607;  // tan 32.76 deg
  double inertialNumber0 = 0.279;   // I_0
  double grainDiameter = 0;         // d (m)
  // Basal sliding law of the mixture at the bed (the bottom patch): noSlip, or coulomb with the
  // wall shear stress limited to tanDelta times the mixture's pressure (bulkCoulombSlip).
  std::string basalLaw = "noSlip";  // noSlip | coulomb
  double tanDelta = 0.7;            // tan(delta_m); the DEM's wall friction coefficient
  double relaxation = 1;      // under-relaxation of the viscosity between correctors (1: none)
  double solidDensity = 0;    // rho_s (kg/m3): sceneProperties particles.density
  double mixtureDensity = 0;  // rho* (kg/m3): bulkProperties density, else alpha_s rho_s +
                              // alpha_f rho_f

  bool poreRatio() const;         // pressure porePressureRatio
  std::string poreField() const;  // the closure's field: porePressureRatio or lambdaP
  // Largest dynamic viscosity (Pa s) the mixture reaches: at rest, at the kinematic pressure g H
  // of a column of height H, with the pore liquid at its cap (nuFluidMax, m2/s); with drift
  // fields, the largest over their cells' drifts inside the allowed range (the solver refuses
  // the others).
  double maxViscosity(double height, double fluidDensity, double nuFluidMax) const;
  double maxViscosity(double height, double fluidDensity, double nuFluidMax,
                      const std::array<double, 3>& drifts) const;
};

// Reads caseDir/constant/bulkProperties (absent: all defaults) for a mixture of liquid density
// fluidDensity whose grains (sceneProperties particles) have solidDensity and grainDiameter;
// sampleSolidFraction is sceneProperties sample.solidFraction. Throws InputError naming file,
// entry and allowed range.
BulkModel readBulkModel(const std::string& caseDir, double sampleSolidFraction, double solidDensity,
                        double fluidDensity, double grainDiameter);

}  // namespace mixflow::cfd
