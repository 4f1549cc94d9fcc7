#include "bulkMixtureViscosity.H"

#include "BulkMixtureCoeffs.h"
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
      phase_(viscosityProperties.dictName()),
      nu_(IOobject(name, U_.time().timeName(), U_.db(), IOobject::NO_READ, IOobject::AUTO_WRITE),
          U_.mesh(), dimensionedScalar("nu", dimViscosity, 0.0)) {
  readCoeffs();
  nu_ = calcNu();
}

void Foam::viscosityModels::bulkMixture::readCoeffs() {
  // The declared entries and ranges (common/BulkMixtureCoeffs.cpp), before anything is read.
  const fileName file =
      U_.time().rootPath() / U_.time().globalCaseName() / "constant" / "transportProperties";
  try {
    mixflow::BulkMixtureCoeffs::check(file, phase_);
  } catch (const std::exception& e) {
    FatalErrorInFunction << e.what() << exit(FatalError);
  }
  alphaS_ = coeffs_.get<scalar>("solidFraction");
  drifts_.lambdaU = coeffs_.get<scalar>("lambdaU");
  drifts_.lambdaW = coeffs_.get<scalar>("lambdaW");
  drifts_.lambdaP = coeffs_.get<scalar>("lambdaP");
  pore_.closure = coeffs_.lookupOrDefault<word>("pressureClosure", "porePressureRatio") == "lambdaP"
                      ? mixflow::bulk::PoreClosure::lambdaP
                      : mixflow::bulk::PoreClosure::ratio;
  drifts_.chi = coeffs_.lookupOrDefault<scalar>("porePressureRatio", 0);
  muI_ = coeffs_.lookupOrDefault<word>("solidRheology", "coulombViscoplastic") == "muI";
  if (muI_) {
    muIRheology_.muS = coeffs_.get<scalar>("muS");
    muIRheology_.mu2 = coeffs_.get<scalar>("mu2");
    muIRheology_.i0 = coeffs_.get<scalar>("I0");
    muIRheology_.diameter = coeffs_.get<scalar>("grainDiameter");
    muIRheology_.regularisation = coeffs_.get<scalar>("regularisation");
  } else {
    solid_.viscosity = coeffs_.get<scalar>("solidViscosity");
    solid_.tanPhi = coeffs_.get<scalar>("tanPhi");
    solid_.cohesion = coeffs_.get<scalar>("cohesion");
    solid_.regularisation = coeffs_.get<scalar>("regularisation");
  }
  pore_.buoyancyReduced = coeffs_.get<word>("yieldPressure") == "buoyancyReduced";
  fluid_.tau0 = coeffs_.get<scalar>("fluidTau0");
  fluid_.k = coeffs_.get<scalar>("fluidK");
  fluid_.n = coeffs_.get<scalar>("fluidN");
  fluid_.nu0 = coeffs_.get<scalar>("fluidNu0");
  rhoMix_ = coeffs_.get<scalar>("mixtureDensity");
  rhoSolid_ = coeffs_.get<scalar>("solidDensity");
  rhoFluid_ = coeffs_.get<scalar>("fluidDensity");
  rhoAir_ = coeffs_.get<scalar>("airDensity");
  pore_.rhoS = rhoSolid_;
  pore_.rhoF = rhoFluid_;
  relaxation_ = coeffs_.get<scalar>("relaxation");
  if (coeffs_.lookupOrDefault<Switch>("driftFields", false)) {
    readDriftFields();
  } else {
    driftSeries_.clear();
    lambdaU_.clear();
    lambdaW_.clear();
    lambdaP_.clear();
    solidFactors_.clear();
    fluidFactors_.clear();
  }
}

Foam::autoPtr<Foam::volScalarField> Foam::viscosityModels::bulkMixture::readDriftField(
    const word& name, const fileName& local) const {
  autoPtr<volScalarField> f(
      new volScalarField(IOobject(name, U_.time().constant(), local, U_.mesh(), IOobject::MUST_READ,
                                  IOobject::NO_WRITE, false),
                         U_.mesh()));
  f->correctBoundaryConditions();  // coupled patches: the face values of the cells read
  // The constants' range (prepare/BulkModel.cpp): Lambda = 1 / (alpha_s + lambda alpha_f) finite;
  // the pore-pressure ratio in [kPoreRatioMin, kPoreRatioMax) = [-10, 1).
  const bool ratio = name == poreFieldName() && pore_.closure == mixflow::bulk::PoreClosure::ratio;
  const scalar lo =
      ratio ? mixflow::bulk::kPoreRatioMin : mixflow::bulk::driftLowerBound(alphaS_, -1e3);
  const scalar hi = ratio ? mixflow::bulk::kPoreRatioMax : 1e3;
  auto bad = [&](scalar v) { return !(v >= lo && (ratio ? v < hi : v <= hi)); };
  label cells = 0, faces = 0;
  scalar vmin = GREAT, vmax = -GREAT;
  forAll(*f, celli) {
    const scalar v = (*f)[celli];
    vmin = min(vmin, v);
    vmax = max(vmax, v);
    if (bad(v)) ++cells;
  }
  // Coupled faces (processor, cyclic) only interpolate cells already counted.
  forAll(f->boundaryField(), patchi) {
    if (f->boundaryField()[patchi].coupled()) continue;
    forAll(f->boundaryField()[patchi], facei) {
      const scalar v = f->boundaryField()[patchi][facei];
      vmin = min(vmin, v);
      vmax = max(vmax, v);
      if (bad(v)) ++faces;
    }
  }
  // Counts and span over all ranks, so that a parallel run refuses (and reports) as a serial one.
  reduce(cells, sumOp<label>());
  reduce(faces, sumOp<label>());
  reduce(vmin, minOp<scalar>());
  reduce(vmax, maxOp<scalar>());
  const label nCells = returnReduce(f->size(), sumOp<label>());
  const fileName file =
      U_.time().rootPath() / U_.time().globalCaseName() / "constant" / local / name;
  if (cells || faces) {
    FatalErrorInFunction << file << ": field " << name << " has " << cells << " of " << nCells
                         << " cells and " << faces << " boundary faces outside the allowed range ["
                         << lo << ", " << hi << (ratio ? ")" : "]");
    if (!ratio) {
      FatalError << " (alpha_s + " << name << " alpha_f >= " << mixflow::bulk::kDriftDenominatorMin
                 << ", |" << name << "| <= 1000, alpha_s " << alphaS_ << ")";
    }
    FatalError << "; its values span [" << vmin << ", " << vmax << "]" << exit(FatalError);
  }
  Info << "bulkMixture: drift field " << file << ", range [" << vmin << ", " << vmax << "]" << endl;
  return f;
}

void Foam::viscosityModels::bulkMixture::readDriftFields() {
  if (coeffs_.lookupOrDefault<Switch>("driftTimeVarying", false)) {
    readDriftSeries();
  } else {
    driftSeries_.clear();
    lambdaU_ = readDriftField("lambdaU");
    lambdaW_ = readDriftField("lambdaW");
    lambdaP_ = readDriftField(poreFieldName());
  }
  auto factors = [&](const word& name) {
    return autoPtr<volVectorField>(
        new volVectorField(IOobject(name, U_.time().timeName(), U_.mesh(), IOobject::NO_READ,
                                    IOobject::NO_WRITE, false),
                           U_.mesh(), dimensionedVector("one", dimless, vector::one)));
  };
  solidFactors_ = factors("solidVelocityFactors");
  fluidFactors_ = factors("fluidVelocityFactors");
  // Fixed fields: the factors once, as alpha_s does not change in time; a series: at each step.
  driftTimeIndex_ = -1;
  if (driftSeries_.valid())
    syncDrifts();
  else
    setVelocityFactors();
}

void Foam::viscosityModels::bulkMixture::readDriftSeries() {
  const Time& time = U_.time();
  const fileName dir = time.path() / time.constant() / "drifts";
  const instantList times = Time::findTimes(dir);
  // Each rank reads its own decomposed windows (./Allrun RANKS decomposes them): the same ones.
  const label nMin = returnReduce(times.size(), minOp<label>());
  const label nMax = returnReduce(times.size(), maxOp<label>());
  if (nMin == 0 || nMin != nMax) {
    FatalErrorInFunction << dir << ": " << times.size()
                         << " windows (directories named by their time, each with lambdaU, "
                            "lambdaW, "
                         << poreFieldName() << "), " << nMin << " to " << nMax
                         << " over the ranks; allowed: at least 1, the same on every rank (in "
                            "parallel ./Allrun RANKS decomposes them)"
                         << exit(FatalError);
  }
  for (label i = 1; i < times.size(); ++i) {
    if (times[i].value() == times[i - 1].value()) {
      FatalErrorInFunction << dir << ": two windows at t = " << times[i].value() << ": "
                           << times[i - 1].name() << " and " << times[i].name() << exit(FatalError);
    }
  }
  const word how = coeffs_.get<word>("driftInterpolation");
  if (how != "linear" && how != "nearest") {
    FatalIOErrorInFunction(coeffs_)
        << "driftInterpolation " << how << ": allowed linear, nearest" << exit(FatalIOError);
  }
  // Every window is read and range-checked here, before the first step.
  const word names[3] = {"lambdaU", "lambdaW", poreFieldName()};
  PtrList<volScalarField> fields(3 * times.size());
  forAll(times, i) {
    for (label k = 0; k < 3; ++k) {
      fields.set(3 * i + k, readDriftField(names[k], fileName("drifts") / times[i].name()));
    }
  }
  driftSeries_.reset(new bulkDriftSeries(times, std::move(fields),
                                         how == "linear"
                                             ? bulkDriftSeries::Interpolation::linear
                                             : bulkDriftSeries::Interpolation::nearest));
  // The drifts in use start as copies of the first window (its boundary conditions included).
  auto current = [&](const label k) {
    return autoPtr<volScalarField>(
        new volScalarField(IOobject(names[k], time.timeName(), U_.mesh(), IOobject::NO_READ,
                                    IOobject::NO_WRITE, false),
                           driftSeries_->window(0, k)));
  };
  lambdaU_ = current(0);
  lambdaW_ = current(1);
  lambdaP_ = current(2);
}

void Foam::viscosityModels::bulkMixture::syncDrifts() const {
  if (!driftSeries_.valid() || driftTimeIndex_ == U_.time().timeIndex()) return;
  driftSeries_->set(U_.time().value(), *lambdaU_, *lambdaW_, *lambdaP_);
  setVelocityFactors();
  driftTimeIndex_ = U_.time().timeIndex();
}

void Foam::viscosityModels::bulkMixture::setVelocityFactors() const {
  // u_s = diag(Lambda_u, Lambda_w, Lambda_u) U and u_f = diag(lambda_u, lambda_w, lambda_u) u_s
  // with the drifts of each cell and face.
  auto set = [&](const mixflow::bulk::Drifts& d, vector& s, vector& f) {
    const mixflow::bulk::LambdaCoefficients c = mixflow::bulk::lambdaCoefficients(alphaS_, d);
    s = vector(c.u, c.w, c.u);
    f = vector(d.lambdaU * s.x(), d.lambdaW * s.y(), d.lambdaU * s.z());
  };
  volVectorField& sf = *solidFactors_;
  volVectorField& ff = *fluidFactors_;
  forAll(sf, celli) set(drifts(celli), sf[celli], ff[celli]);
  forAll(sf.boundaryField(), patchi) {
    forAll(sf.boundaryField()[patchi], facei) {
      set(drifts(patchi, facei), sf.boundaryFieldRef()[patchi][facei],
          ff.boundaryFieldRef()[patchi][facei]);
    }
  }
}

Foam::word Foam::viscosityModels::bulkMixture::poreFieldName() const {
  return pore_.closure == mixflow::bulk::PoreClosure::ratio ? "porePressureRatio" : "lambdaP";
}

mixflow::bulk::Drifts Foam::viscosityModels::bulkMixture::drifts(const scalar lu, const scalar lw,
                                                                 const scalar pore) const {
  // The third field is the pressure closure's: lambda_p, or chi (lambda_p then unused).
  return pore_.closure == mixflow::bulk::PoreClosure::ratio
             ? mixflow::bulk::Drifts{lu, lw, drifts_.lambdaP, pore}
             : mixflow::bulk::Drifts{lu, lw, pore, drifts_.chi};
}

mixflow::bulk::Drifts Foam::viscosityModels::bulkMixture::drifts(label celli) const {
  if (!driftFields()) return drifts_;
  return drifts((*lambdaU_)[celli], (*lambdaW_)[celli], (*lambdaP_)[celli]);
}

mixflow::bulk::Drifts Foam::viscosityModels::bulkMixture::drifts(label patchi, label facei) const {
  if (!driftFields()) return drifts_;
  return drifts(lambdaU_->boundaryField()[patchi][facei], lambdaW_->boundaryField()[patchi][facei],
                lambdaP_->boundaryField()[patchi][facei]);
}

Foam::scalar Foam::viscosityModels::bulkMixture::yieldFromMixturePressure(
    const mixflow::bulk::Drifts& d) const {
  return mixflow::bulk::yieldPressureFactor(alphaS_, d, pore_);
}

const Foam::volVectorField& Foam::viscosityModels::bulkMixture::solidVelocityFactorField() const {
  syncDrifts();
  return *solidFactors_;
}

const Foam::volVectorField& Foam::viscosityModels::bulkMixture::fluidVelocityFactorField() const {
  syncDrifts();
  return *fluidFactors_;
}

Foam::tmp<Foam::volVectorField> Foam::viscosityModels::bulkMixture::slipFactorField() const {
  syncDrifts();
  return *solidFactors_ - *fluidFactors_;
}

Foam::tmp<Foam::volScalarField> Foam::viscosityModels::bulkMixture::pressureFactorField(
    const bool fluid) const {
  syncDrifts();
  tmp<volScalarField> t(new volScalarField(
      IOobject(fluid ? "fluidPressureFactor" : "solidPressureFactor", U_.time().timeName(),
               U_.mesh(), IOobject::NO_READ, IOobject::NO_WRITE, false),
      U_.mesh(), dimensionedScalar("zero", dimDensity, 0.0)));
  auto factor = [&](const mixflow::bulk::Drifts& d) {
    return fluid ? mixflow::bulk::fluidPressureFactor(alphaS_, d, pore_)
                 : mixflow::bulk::solidPressureFactor(alphaS_, d, pore_);
  };
  volScalarField& f = t.ref();
  forAll(f, celli) f[celli] = factor(drifts(celli));
  forAll(f.boundaryField(), patchi) {
    forAll(f.boundaryField()[patchi], facei) {
      f.boundaryFieldRef()[patchi][facei] = factor(drifts(patchi, facei));
    }
  }
  return t;
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
  syncDrifts();
  const vector fs = solidVelocityFactors(), ff = fluidVelocityFactors();
  const bool fields = driftFields();
  const volScalarField srSolid(
      sqrt(2.0) *
      mag(symm(fvc::grad(fields ? cmptMultiply(U_, *solidFactors_) : cmptMultiply(U_, fs)))));
  // u_f = u_s without drifts: the second gradient is then the first.
  const tmp<volScalarField> tsrFluid =
      fields
          ? tmp<volScalarField>(sqrt(2.0) * mag(symm(fvc::grad(cmptMultiply(U_, *fluidFactors_)))))
      : ff == fs ? tmp<volScalarField>(srSolid)
                 : tmp<volScalarField>(sqrt(2.0) * mag(symm(fvc::grad(cmptMultiply(U_, ff)))));
  const volScalarField& srFluid = tsrFluid();
  const tmp<volScalarField> tpm = mixturePressure();

  tmp<volScalarField> tnu(new volScalarField(
      IOobject("nuBulk", U_.time().timeName(), U_.db(), IOobject::NO_READ, IOobject::NO_WRITE),
      U_.mesh(), dimensionedScalar("nu", dimViscosity, 0.0)));
  volScalarField& nu = tnu.ref();
  auto pointwise = [&](const mixflow::bulk::Drifts& d, scalar sS, scalar sF, scalar pm) {
    const scalar py = yieldFromMixturePressure(d) * pm;
    const scalar nuS = muI_ ? mixflow::bulk::solidViscosity(muIRheology_, sS, py)
                            : mixflow::bulk::solidViscosity(solid_, sS, py);
    const scalar nuF = mixflow::bulk::fluidViscosity(fluid_, sF);
    return mixflow::bulk::mixtureDiffusivity(alphaS_, d, nuS, nuF);
  };
  forAll(nu, celli) {
    nu[celli] = pointwise(drifts(celli), srSolid[celli], srFluid[celli], tpm()[celli]);
  }
  volScalarField::Boundary& nub = nu.boundaryFieldRef();
  forAll(nub, patchi) {
    forAll(nub[patchi], facei) {
      nub[patchi][facei] =
          pointwise(drifts(patchi, facei), srSolid.boundaryField()[patchi][facei],
                    srFluid.boundaryField()[patchi][facei], tpm().boundaryField()[patchi][facei]);
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
