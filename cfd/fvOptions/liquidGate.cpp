#include "liquidGate.H"

#include "addToRunTimeSelectionTable.H"
#include "fvMatrices.H"
#include "fvmSup.H"

namespace Foam {
namespace fv {

defineTypeNameAndDebug(liquidGate, 0);
addToRunTimeSelectionTable(option, liquidGate, dictionary);

liquidGate::liquidGate(const word& name, const word& modelType, const dictionary& dict,
                       const fvMesh& mesh)
    : option(name, modelType, dict, mesh) {
  read(dict);
  // Only the momentum equation: the plate holds the mixture (liquid and air) at rest.
  fieldNames_ = wordList(1, "U");
  applied_.setSize(1, false);

  const volVectorField& C = mesh_.C();
  DynamicList<label> cells;
  forAll(C, celli) {
    if (C[celli].x() >= xMin_ && C[celli].x() < xMax_) cells.append(celli);
  }
  plateCells_.transfer(cells);
  const label nPlate = returnReduce(plateCells_.size(), sumOp<label>());
  if (nPlate == 0)
    FatalIOErrorInFunction(dict) << type() << " " << name_ << ": no cell centre lies in " << xMin_
                                 << " <= x < " << xMax_ << exit(FatalIOError);
  Info << type() << " " << name_ << ": plate " << xMin_ << " <= x < " << xMax_ << " m, " << nPlate
       << " cells, lower edge " << lowerEdge_->type() << ", holdFactor " << holdFactor_ << endl;
}

bool liquidGate::read(const dictionary& dict) {
  if (!option::read(dict)) return false;
  coeffs_.readEntry("xMin", xMin_);
  coeffs_.readEntry("xMax", xMax_);
  coeffs_.readEntry("holdFactor", holdFactor_);
  if (!(xMax_ > xMin_) || !(holdFactor_ > 0 && holdFactor_ < 1))
    FatalIOErrorInFunction(dict) << type() << " " << name_
                                 << ": need xMax > xMin and 0 < holdFactor < 1"
                                 << exit(FatalIOError);
  lowerEdge_ = Function1<scalar>::New("lowerEdge", coeffs_);
  return true;
}

scalar liquidGate::lowerEdge() const { return lowerEdge_->value(mesh_.time().value()); }

void liquidGate::addSup(const volScalarField& rho, fvMatrix<vector>& eqn, const label) {
  // Assembled at the new time level, as the implicit step it is part of.
  const scalar h = lowerEdge();
  const scalar K = (1.0 / holdFactor_ - 1.0) / mesh_.time().deltaTValue();
  // The densest phase's density for every held cell: the pressure across the plate is the
  // liquid's, and air held with its own density (1e-3 of it) would seep up the plate.
  const scalar rhoHeld = gMax(rho.primitiveField());
  volScalarField::Internal sink(IOobject(name_ + ":sink", mesh_.time().timeName(), mesh_,
                                         IOobject::NO_READ, IOobject::NO_WRITE, false),
                                mesh_, dimensionedScalar(dimDensity / dimTime, Zero));
  const volVectorField& C = mesh_.C();
  label held = 0;
  for (const label celli : plateCells_) {
    if (C[celli].y() > h) {
      sink[celli] = rhoHeld * K;
      ++held;
    }
  }
  reduce(held, sumOp<label>());
  if (held != lastHeld_)
    Info << type() << " " << name_ << ": lower edge " << h << " m, " << held << " cells held"
         << endl;
  lastHeld_ = held;
  eqn -= fvm::Sp(sink, eqn.psi());
}

}  // namespace fv
}  // namespace Foam
