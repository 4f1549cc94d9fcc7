#include "bulkCoulombSlipFvPatchVectorField.H"

#include "addToRunTimeSelectionTable.H"
#include "incompressibleTwoPhaseMixture.H"
#include "turbulenceModel.H"
#include "volFields.H"

Foam::bulkCoulombSlipFvPatchVectorField::bulkCoulombSlipFvPatchVectorField(
    const fvPatch& p, const DimensionedField<vector, volMesh>& iF)
    : partialSlipFvPatchVectorField(p, iF) {}

Foam::bulkCoulombSlipFvPatchVectorField::bulkCoulombSlipFvPatchVectorField(
    const fvPatch& p, const DimensionedField<vector, volMesh>& iF, const dictionary& dict)
    : partialSlipFvPatchVectorField(p, iF), tanDelta_(dict.get<scalar>("tanDelta")) {
  if (tanDelta_ < 0) {
    FatalIOErrorInFunction(dict) << "tanDelta " << tanDelta_ << " is negative"
                                 << exit(FatalIOError);
  }
  // No-slip until the first updateCoeffs (a restart re-derives f from the fields).
  valueFraction() = 1;
  refValue() = Zero;
  evaluate();
}

Foam::bulkCoulombSlipFvPatchVectorField::bulkCoulombSlipFvPatchVectorField(
    const bulkCoulombSlipFvPatchVectorField& ptf, const fvPatch& p,
    const DimensionedField<vector, volMesh>& iF, const fvPatchFieldMapper& mapper)
    : partialSlipFvPatchVectorField(ptf, p, iF, mapper), tanDelta_(ptf.tanDelta_) {}

Foam::bulkCoulombSlipFvPatchVectorField::bulkCoulombSlipFvPatchVectorField(
    const bulkCoulombSlipFvPatchVectorField& ptf)
    : partialSlipFvPatchVectorField(ptf), tanDelta_(ptf.tanDelta_) {}

Foam::bulkCoulombSlipFvPatchVectorField::bulkCoulombSlipFvPatchVectorField(
    const bulkCoulombSlipFvPatchVectorField& ptf, const DimensionedField<vector, volMesh>& iF)
    : partialSlipFvPatchVectorField(ptf, iF), tanDelta_(ptf.tanDelta_) {}

void Foam::bulkCoulombSlipFvPatchVectorField::updateCoeffs() {
  if (updated()) return;
  const objectRegistry& db = this->db();
  // Before the solver has built the mixture, turbulence and p (field construction): no-slip.
  if (!db.foundObject<turbulenceModel>(turbulenceModel::propertiesName) ||
      !db.foundObject<volScalarField>("p") || !db.foundObject<volScalarField>("gh")) {
    valueFraction() = 1;
    partialSlipFvPatchVectorField::updateCoeffs();
    return;
  }
  const label patchi = patch().index();
  const incompressibleTwoPhaseMixture& mixture =
      db.lookupObject<incompressibleTwoPhaseMixture>("transportProperties");
  const turbulenceModel& turbulence =
      db.lookupObject<turbulenceModel>(turbulenceModel::propertiesName);
  const scalarField& rho = db.lookupObject<volScalarField>("rho").boundaryField()[patchi];
  const scalarField& p = db.lookupObject<volScalarField>("p").boundaryField()[patchi];
  const scalarField& gh = db.lookupObject<volScalarField>("gh").boundaryField()[patchi];
  const scalarField c(min(max(mixture.alpha1().boundaryField()[patchi], scalar(0)), scalar(1)));

  // The stress coefficient of the discretised wall flux: (rho nuEff)_face deltaCoeffs.
  const scalarField muDelta(rho * turbulence.nuEff(patchi) * patch().deltaCoeffs());
  const vectorField nHat(patch().nf());
  const scalarField ut(mag(transform(I - sqr(nHat), patchInternalField())));
  const scalarField sigmaN(max(p - mixture.rho2().value() * gh, scalar(0)));

  scalarField& f = valueFraction();
  forAll(f, facei) {
    const scalar tauNoSlip = muDelta[facei] * ut[facei];
    const scalar tauCoulomb = tanDelta_ * sigmaN[facei];
    const scalar fMixture = tauNoSlip > tauCoulomb ? tauCoulomb / tauNoSlip : 1;
    f[facei] = c[facei] * fMixture + (1 - c[facei]);
  }
  partialSlipFvPatchVectorField::updateCoeffs();
}

Foam::tmp<Foam::vectorField> Foam::bulkCoulombSlipFvPatchVectorField::snGradTransformDiag() const {
  return tmp<vectorField>(new vectorField(valueFraction() * vector::one));
}

void Foam::bulkCoulombSlipFvPatchVectorField::write(Ostream& os) const {
  fvPatchVectorField::write(os);
  os.writeEntry("tanDelta", tanDelta_);
  writeEntry("value", os);
}

namespace Foam {
makePatchTypeField(fvPatchVectorField, bulkCoulombSlipFvPatchVectorField);
}
