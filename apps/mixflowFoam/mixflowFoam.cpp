// mixflowFoam: incompressible two-phase (liquid + air) VOF solver with a free surface, written
// in the volume-averaged form an unresolved CFD-DEM coupling needs (docs/model.md §3,
// formulation B of Zhou et al. 2010; cfd/README.md explains the choice).
//
// Unknowns: interstitial fluid velocity U, p_rgh = p - rho g.(x - x_ref), liquid fraction of the
// fluid alpha (alpha.<liquid>, bounded by MULES). Given (from the particles, or from files):
//   voidfraction  eps_f   fluid volume fraction of a cell (read if present, else 1)
//   Ksl           K       implicit drag coefficient [kg/m3/s]: drag on the fluid = K (Us - U)
//   Us            Us      particle (solid) velocity [m/s]
//   fSource       f       explicit force on the fluid per unit cell volume [N/m3]
// Equations, with rho = alpha rho_l + (1 - alpha) rho_a and phi = U_f . S_f the interstitial flux:
//   d(eps_f)/dt + div(eps_f U)                              = 0
//   d(eps_f alpha)/dt + div(eps_f U alpha) + compression    = 0
//   d(eps_f rho U)/dt + div(rho eps_f U U) - div(tau)       = -grad(p) + eps_f rho g
//                                                + sigma kappa grad(alpha) + K (Us - U) + f
// tau = rho nu_eff (grad U + grad U^T) from the mixture viscosity (per-phase Newtonian,
// HerschelBulkley, ...) and the turbulence model; constant/mixflowProperties may select
// div(eps_f tau) instead (viscousStress voidfractionWeighted). With eps_f = 1, K = 0 and f = 0
// the algorithm is interFoam's (Euler time scheme, static mesh), and so are the results.
//
// Body forces enter face by face (as interFoam does for gravity and surface tension), so that a
// fluid at rest under any balanced force distribution stays at rest to solver tolerance.
//
// Limitations (checked at start-up): Euler time scheme only, static mesh, no MRF/LTS, no
// isotropic/shear compression (icAlpha, scAlpha); alpha sub-cycling only while eps_f is steady.

#include <iostream>

#include "CMULES.H"
#include "EulerDdtScheme.H"
#include "Function1.H"
#include "MixflowProperties.h"
#include "Progress.h"
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
      "mixflowFoam: incompressible liquid/air VOF solver with fluid volume fraction "
      "(voidfraction), particle drag (Ksl, Us) and explicit particle force (fSource); "
      "volume-averaged formulation B");

  // clang-format off
#include "createStandaloneSolver.H"
  // clang-format on

  // The particle fields are those read at the start (or ramped by particleRamp); a coupled solver
  // sets them before each fluid step instead (apps/mixflowCoupled).
  const std::string progressName = "liquid";
  auto beforeFluidStep = [] {};
  auto afterFluidStep = [] {};
  // clang-format off
#include "standaloneTimeLoop.H"
  // clang-format on

  return 0;
}
