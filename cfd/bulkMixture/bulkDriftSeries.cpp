#include "bulkDriftSeries.H"

Foam::bulkDriftSeries::bulkDriftSeries(const instantList& times, PtrList<volScalarField>&& fields,
                                       const Interpolation how)
    : times_(times), fields_(std::move(fields)), how_(how) {}

void Foam::bulkDriftSeries::bracket(const scalar t, label& a, label& b, scalar& w) const {
  const label n = times_.size();
  w = 0;
  if (t <= times_[0].value()) {
    a = b = 0;
    return;
  }
  if (t >= times_[n - 1].value()) {
    a = b = n - 1;
    return;
  }
  a = 0;
  while (times_[a + 1].value() <= t) ++a;
  b = a + 1;
  w = (t - times_[a].value()) / (times_[b].value() - times_[a].value());
  if (how_ == Interpolation::nearest) {
    a = b = w < 0.5 ? a : b;  // the midpoint belongs to the later window
    w = 0;
  }
}

void Foam::bulkDriftSeries::set(const scalar t, volScalarField& lambdaU, volScalarField& lambdaW,
                                volScalarField& lambdaP) const {
  label a = 0, b = 0;
  scalar w = 0;
  bracket(t, a, b, w);
  // x + w (y - x): exactly x at w = 0 and where the two windows agree (a series of equal
  // windows is the fixed fields bit for bit).
  auto mix = [w](scalarField& f, const scalarField& x, const scalarField& y) {
    forAll(f, i) f[i] = x[i] + w * (y[i] - x[i]);
  };
  volScalarField* lambda[3] = {&lambdaU, &lambdaW, &lambdaP};
  for (label k = 0; k < 3; ++k) {
    volScalarField& f = *lambda[k];
    const volScalarField& x = window(a, k);
    const volScalarField& y = window(b, k);
    mix(f.primitiveFieldRef(), x, y);
    forAll(f.boundaryField(), patchi) {
      mix(f.boundaryFieldRef()[patchi], x.boundaryField()[patchi], y.boundaryField()[patchi]);
    }
  }
}
