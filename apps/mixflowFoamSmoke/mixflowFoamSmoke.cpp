// mixflowFoamSmoke: tool-chain smoke test for mixflow's OpenFOAM side.
//
// Solves transient diffusion of a passive scalar T,
//
//     dT/dt = div(DT grad T),
//
// with a constant diffusivity DT [m^2/s] read from constant/transportProperties, implicitly in
// time (the time scheme comes from system/fvSchemes). T is read from the start time directory
// and written by controlDict's rules.
//
// Optional controlDict entry `steadyStateTolerance` (default: off): the run stops and writes as
// soon as the largest change of T over one time step, over all processors, falls below it;
// without it the run goes to endTime.
//
// Runs serially or in parallel (`decomposePar`, then `mpirun -np N mixflowFoamSmoke -parallel`);
// the steady-state test reduces over processors, so every rank stops at the same step.

#include "fvCFD.H"

int main(int argc, char *argv[]) {
  argList::addNote(
      "mixflow smoke solver: transient diffusion of scalar T with "
      "constant diffusivity DT (constant/transportProperties)");

  // OpenFOAM's case-setup snippets; their order matters (args -> runTime -> mesh), so keep
  // clang-format's include sorting away from them.
  // clang-format off
#include "setRootCase.H"
#include "createTime.H"
#include "createMesh.H"
  // clang-format on

  Info << "Reading transportProperties" << nl << endl;
  IOdictionary transportProperties(IOobject("transportProperties", runTime.constant(), mesh,
                                            IOobject::MUST_READ_IF_MODIFIED, IOobject::NO_WRITE));

  dimensionedScalar DT("DT", dimArea / dimTime, transportProperties);
  if (DT.value() <= 0) {
    FatalIOErrorInFunction(transportProperties)
        << "Diffusivity DT must be positive, got " << DT.value() << exit(FatalIOError);
  }
  Info << "Diffusivity DT = " << DT.value() << " m^2/s" << nl << endl;

  Info << "Reading field T" << nl << endl;
  volScalarField T(
      IOobject("T", runTime.timeName(), mesh, IOobject::MUST_READ, IOobject::AUTO_WRITE), mesh);

  const scalar steadyTol =
      runTime.controlDict().lookupOrDefault<scalar>("steadyStateTolerance", -1);
  if (steadyTol > 0) {
    Info << "Stopping at steady state: max |T(n+1) - T(n)| < " << steadyTol << nl << endl;
  }

  Info << "Starting time loop" << nl << endl;
  while (runTime.loop()) {
    Info << "Time = " << runTime.timeName() << nl << endl;

    // Keep T^n explicitly: the change per step is the steady-state measure.
    const scalarField Tprev(T.primitiveField());

    fvScalarMatrix TEqn(fvm::ddt(T) - fvm::laplacian(DT, T));
    TEqn.solve();

    const scalar change = gMax(mag(T.primitiveField() - Tprev)());
    Info << "max |dT| over step = " << change << nl;

    if (steadyTol > 0 && change < steadyTol) {
      Info << "Steady state reached at time " << runTime.timeName() << nl;
      runTime.writeAndEnd();
    } else {
      runTime.write();
    }

    runTime.printExecutionTime(Info);
  }

  Info << "End" << nl << endl;
  return 0;
}
