#include "bulkMixtureViscosity.H"

#include "addToRunTimeSelectionTable.H"
#include "fvcGrad.H"
#include "surfaceFields.H"

namespace Foam {
namespace viscosityModels {
defineTypeNameAndDebug(bulkMixture, 0);
addToRunTimeSelectionTable(viscosityModel, bulkMixture, dictionary);
}  // namespace viscosityModels
}  // namespace Foam

Foam::viscosityModels::bulkMixture::bulkMixture(const word& name,
                                                const dictionary& viscosityProperties,
                                                const volVectorField& U,
                                                const surfaceScalarField& phi)
    : viscosityModel(name, viscosityProperties, U, phi),
      coeffs_(viscosityProperties.optionalSubDict(typeName + "Coeffs")),
      nu_(IOobject(name, U_.time().timeName(), U_.db(), IOobject::NO_READ, IOobject::AUTO_WRITE),
          U_.mesh(), dimensionedScalar("nu", dimViscosity, 0.0)) {
  readCoeffs();
  nu_ = calcNu();
}

void Foam::viscosityModels::bulkMixture::readCoeffs() {
  alphaS_ = coeffs_.get<scalar>("solidFraction");
  drifts_.lambdaU = coeffs_.get<scalar>("lambdaU");
  drifts_.lambdaW = coeffs_.get<scalar>("lambdaW");
  drifts_.lambdaP = coeffs_.get<scalar>("lambdaP");
  solid_.viscosity = coeffs_.get<scalar>("solidViscosity");
  solid_.tanPhi = coeffs_.get<scalar>("tanPhi");
  solid_.cohesion = coeffs_.get<scalar>("cohesion");
  solid_.regularisation = coeffs_.get<scalar>("regularisation");
  yieldPressureFactor_ = coeffs_.get<scalar>("yieldPressureFactor");
  fluid_.tau0 = coeffs_.get<scalar>("fluidTau0");
  fluid_.k = coeffs_.get<scalar>("fluidK");
  fluid_.n = coeffs_.get<scalar>("fluidN");
  fluid_.nu0 = coeffs_.get<scalar>("fluidNu0");
  rhoMix_ = coeffs_.get<scalar>("mixtureDensity");
  rhoSolid_ = coeffs_.get<scalar>("solidDensity");
  rhoFluid_ = coeffs_.get<scalar>("fluidDensity");
  rhoAir_ = coeffs_.get<scalar>("airDensity");
  relaxation_ = coeffs_.get<scalar>("relaxation");
}

Foam::vector Foam::viscosityModels::bulkMixture::solidVelocityFactors() const {
  const mixflow::bulk::LambdaCoefficients c = mixflow::bulk::lambdaCoefficients(alphaS_, drifts_);
  return vector(c.u, c.w, c.u);  // the spanwise drift (3-D) is the along-channel one
}

Foam::vector Foam::viscosityModels::bulkMixture::fluidVelocityFactors() const {
  const vector s = solidVelocityFactors();
  return vector(drifts_.lambdaU * s.x(), drifts_.lambdaW * s.y(), drifts_.lambdaU * s.z());
}

Foam::tmp<Foam::volScalarField> Foam::viscosityModels::bulkMixture::mixturePressure() const {
  tmp<volScalarField> tpm(new volScalarField(
      IOobject("pMixture", U_.time().timeName(), U_.db(), IOobject::NO_READ, IOobject::NO_WRITE),
      U_.mesh(), dimensionedScalar("zero", sqr(dimVelocity), 0.0)));
  const volScalarField* p = U_.db().findObject<volScalarField>("p");
  const volScalarField* gh = U_.db().findObject<volScalarField>("gh");
  if (p && gh) {
    // The atmosphere's hydrostatic pressure is removed so that p_m = 0 at the free surface.
    tpm.ref() = (*p - dimensionedScalar("rhoAir", dimDensity, rhoAir_) * (*gh)) /
                dimensionedScalar("rhoMix", dimDensity, rhoMix_);
  }
  return tpm;
}

Foam::tmp<Foam::volScalarField> Foam::viscosityModels::bulkMixture::calcNu() const {
  const vector fs = solidVelocityFactors(), ff = fluidVelocityFactors();
  const volScalarField srSolid(sqrt(2.0) * mag(symm(fvc::grad(cmptMultiply(U_, fs)))));
  // u_f = u_s without drifts: the second gradient is then the first.
  const tmp<volScalarField> tsrFluid =
      ff == fs ? tmp<volScalarField>(srSolid)
               : tmp<volScalarField>(sqrt(2.0) * mag(symm(fvc::grad(cmptMultiply(U_, ff)))));
  const volScalarField& srFluid = tsrFluid();
  const tmp<volScalarField> tpm = mixturePressure();
  const scalar ps2yield =
      yieldPressureFactor_ / mixflow::bulk::lambdaCoefficients(alphaS_, drifts_).p;

  tmp<volScalarField> tnu(new volScalarField(
      IOobject("nuBulk", U_.time().timeName(), U_.db(), IOobject::NO_READ, IOobject::NO_WRITE),
      U_.mesh(), dimensionedScalar("nu", dimViscosity, 0.0)));
  volScalarField& nu = tnu.ref();
  auto pointwise = [&](scalar sS, scalar sF, scalar pm) {
    const scalar nuS = mixflow::bulk::solidViscosity(solid_, sS, ps2yield * pm);
    const scalar nuF = mixflow::bulk::fluidViscosity(fluid_, sF);
    return mixflow::bulk::mixtureDiffusivity(alphaS_, drifts_, nuS, nuF);
  };
  forAll(nu, celli) nu[celli] = pointwise(srSolid[celli], srFluid[celli], tpm()[celli]);
  volScalarField::Boundary& nub = nu.boundaryFieldRef();
  forAll(nub, patchi) {
    forAll(nub[patchi], facei) {
      nub[patchi][facei] =
          pointwise(srSolid.boundaryField()[patchi][facei], srFluid.boundaryField()[patchi][facei],
                    tpm().boundaryField()[patchi][facei]);
    }
  }
  return tnu;
}

void Foam::viscosityModels::bulkMixture::correct() {
  // Under-relaxation of the pressure- and rate-dependent viscosity (1: none).
  if (relaxation_ < 1)
    nu_ = relaxation_ * calcNu() + (1 - relaxation_) * nu_;
  else
    nu_ = calcNu();
}

bool Foam::viscosityModels::bulkMixture::read(const dictionary& viscosityProperties) {
  viscosityModel::read(viscosityProperties);
  coeffs_ = viscosityProperties.optionalSubDict(typeName + "Coeffs");
  readCoeffs();
  return true;
}
