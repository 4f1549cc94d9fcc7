// mixflowCoupled: two-way CFD-DEM coupling in one process -- mixflowFoam's fluid (OpenFOAM VOF,
// formulation B; cfd/README.md) and LIGGGHTS particles driven as a library, exchanging every
// exchangeEvery DEM steps (one CFD step). The fluid algorithm is mixflowFoam's own: this file is
// the standalone solvers' time loop (cfd/vofSolver/standaloneTimeLoop.H) with the coupling
// inserted where updateCouplingFields.H expects it, and it includes mixflowFoam's step files
// unchanged (cfd/vofSolver/*.H); its own start-up steps are the step files beside it
// (createCoupling.H, writeStartFields.H, keepRestartState.H).
//
// Case: an interFoam/mixflowFoam case plus constant/couplingProperties (coupling/README.md) and
// the particle scene as LIGGGHTS commands (its demScript, e.g. system/in.liggghts).
//
// Order of one step (t -> t + dt, dt = exchangeEvery x DEM dt):
//   1. DEM runs exchangeEvery steps with the fluid forces of the last exchange held constant;
//   2. exchange at the particles' new positions: eps_f(t + dt), forces from the fluid at t
//      (the particles' forces for the next interval, the fluid's Ksl/Us/fSource for this step);
//   3. the fluid step (PIMPLE) with those fields;
//   4. pressureCoupling mixture (the implicit drag's default): the fluid velocity the next
//      interval's drag holds is sampled again from the fluid at t + dt, whose pressure equation
//      counted on the grains following it (coupling/README.md, "Pressure coupling").
// Before the loop one exchange sets eps_f(0) and the first interval's forces.
//
// MPI: LIGGGHTS needs MPI; OpenFOAM initialises it only with -parallel, so a serial run calls
// MPI_Init here (v1912's Pstream accepts an MPI that is already initialised).

#include <mpi.h>

#include <cstring>

// clang-format off
#include "CMULES.H"
#include "EulerDdtScheme.H"
#include "Function1.H"
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
#include "FoamCoupling.H"
#include "MixtureMonitor.h"
#include "MixflowProperties.h"
// clang-format on

namespace {

int runCoupled(int argc, char* argv[]) {
  argList::addNote(
      "mixflowCoupled: mixflowFoam (VOF, formulation B) two-way coupled with LIGGGHTS particles "
      "(constant/couplingProperties)");
  argList::addBoolOption("resume",
                         "continue a mixture scene from its last field write "
                         "(dem/coupled.resume.state; scripts/ResumeFunctions resumeMixtureCase "
                         "sets startFrom and cuts the outputs' later rows first)");

  // clang-format off
#include "setRootCase.H"
#include "createRunTime.H"
#include "createMesh.H"
#include "createPimpleControl.H"
#include "createTimeControls.H"
#include "initContinuityErrs.H"
#include "createFields.H"
#include "checkSchemes.H"
#include "createAlphaFluxes.H"
#include "createFvOptions.H"
  // clang-format on

  // clang-format off
#include "createCoupling.H"
#include "initCorrectPhi.H"
#include "writeStartFields.H"
  // clang-format on

  turbulence->validate();

  // clang-format off
#include "keepRestartState.H"
  // clang-format on

  {
    // clang-format off
#include "CourantNo.H"
    // clang-format on
  }

  Info << "\nStarting time loop\n" << endl;

  // A write's resume state waits for the next runTime.run(): the function objects write their
  // state into that write's uniform/ only then, and a resume from a write without it restarts
  // their series (postProcessing/liquid) instead of appending.
  word writeToRecord;
  while (runTime.run()) {
    if (monitor && !writeToRecord.empty()) monitor->afterWrite(writeToRecord);
    writeToRecord.clear();
    // clang-format off
#include "readTimeControls.H"
#include "courantNumbers.H"
    // clang-format on

    ++runTime;

    Info << "Time = " << runTime.timeName() << nl << endl;

    coupling.evolve();  // DEM interval, then exchange at the new positions

    // clang-format off
#include "fluidStep.H"
    // clang-format on
    coupling.checkFluid();
    coupling.recordDragDefect();
    coupling.resampleFluidVelocity();  // pressureCoupling mixture: the next interval's U

    runTime.write();
    if (monitor) {
      monitor->afterStep();
      // After the step's granular row, so that a resumed run finds its counters up to date.
      if (runTime.writeTime()) writeToRecord = runTime.timeName();
    }

    runTime.printExecutionTime(Info);
  }
  if (monitor && !writeToRecord.empty()) monitor->afterWrite(writeToRecord);
  if (monitor) monitor->finish();

  Info << "End\n" << endl;
  return 0;
}

}  // namespace

int main(int argc, char* argv[]) {
  bool parallel = false;
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "-parallel") == 0) parallel = true;
  // With -parallel OpenFOAM initialises (and finalises) MPI itself.
  if (!parallel) MPI_Init(&argc, &argv);
  const int status = runCoupled(argc, argv);
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!parallel && !finalized) MPI_Finalize();
  return status;
}
