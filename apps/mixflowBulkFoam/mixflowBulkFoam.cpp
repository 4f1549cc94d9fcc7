// mixflowBulkFoam: the quasi two-phase bulk mixture model (Pokhrel et al. 2017; docs/bulk_model.md)
// of a grain-liquid mixture under air, on mixflowFoam's VOF algorithm (cfd/vofSolver, whose
// step files it includes): the non-air phase alpha.liquid is the mixture, U its volumetric flux
// u_m = alpha_s u_s + alpha_f u_f, rho* its constant density (as the paper, which has no mixture
// density), and its viscosity the bulkMixture model (bulkMixtureViscosity.H: Coulomb-viscoplastic
// solid, the pore liquid's rheology, the drifts lambda). The Lambda-weighted convection enters as
// div(u_m u_m) plus the drift stress (bulkDriftStress.H). Constant solid fraction; constant drifts,
// fixed drift fields constant/lambdaU, lambdaW, lambdaP (bulkProperties drifts { fields on; }) or
// fields that change in time, the windows constant/drifts/<t>/ (timeVarying on; bulkDriftSeries.H);
// the reconstructed u_s, u_f, P_s, P_f are written with the fields (writeBulkFields.H).
// With solid fraction 0 it is mixflowFoam with the pore liquid (tests/cfd bulk.*).

#include <iostream>

#include "CMULES.H"
#include "EulerDdtScheme.H"
#include "Function1.H"
#include "MixflowProperties.h"
#include "Progress.h"
#include "bulkMixtureViscosity.H"
#include "fvCFD.H"
#include "RunTime.H"
#include "fvOptions.H"
#include "gaussConvectionScheme.H"
#include "immiscibleIncompressibleTwoPhaseMixture.H"
#include "localIOdictionary.H"
#include "pimpleControl.H"
#include "subCycle.H"
#include "turbulentTransportModel.H"
#include "upwind.H"

int main(int argc, char *argv[]) {
  argList::addNote(
      "mixflowBulkFoam: quasi two-phase bulk mixture model (mixture/air VOF, constant solid "
      "fraction and drifts, Coulomb-viscoplastic solid and the pore liquid's rheology)");

  // clang-format off
#include "createStandaloneSolver.H"
#include "createBulkFields.H"
  // clang-format on

  const std::string progressName = "bulk";
  // The drift stress as the step's explicit force (fSource), from U of the last step.
  auto beforeFluidStep = [&] {
    // clang-format off
#include "bulkDriftStress.H"
    // clang-format on
  };
  // The reconstructed phase fields, at write times.
  auto afterFluidStep = [&] {
    // clang-format off
#include "writeBulkFields.H"
    // clang-format on
  };
  // clang-format off
#include "standaloneTimeLoop.H"
  // clang-format on

  return 0;
}
