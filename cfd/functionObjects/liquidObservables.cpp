#include "liquidObservables.H"

#include <cmath>
#include <limits>

#include "addToRunTimeSelectionTable.H"
#include "boundBox.H"
#include "gravityMeshObject.H"
#include "surfaceFields.H"
#include "volFields.H"

namespace Foam {
namespace functionObjects {

defineTypeNameAndDebug(liquidObservables, 0);
addToRunTimeSelectionTable(functionObject, liquidObservables, dictionary);

namespace {
const scalar kNaN = std::numeric_limits<scalar>::quiet_NaN();

// A face counts as normal to x when its unit normal's x component exceeds this.
const scalar kXNormal = 0.9;

// Position of the alpha = thr crossing between an upstream (xu, au >= thr) and a downstream
// (xd, ad < thr) cell centre.
scalar crossing(scalar xu, scalar au, scalar xd, scalar ad, scalar thr) {
  return xu + (xd - xu) * (au - thr) / max(au - ad, VSMALL);
}
}  // namespace

liquidObservables::liquidObservables(const word& name, const Time& runTime, const dictionary& dict)
    : fvMeshFunctionObject(name, runTime, dict) {
  read(dict);
  setGeometry();

  initialVolume_ = getProperty<scalar>("initialVolume", -1);
  outletVolume_ = getProperty<scalar>("outletVolume", 0);
  topVolume_ = getProperty<scalar>("topVolume", 0);
  lastTimeIndex_ = mesh_.time().timeIndex();

  const Row r = measure();
  const bool restart = initialVolume_ >= 0;
  if (!restart) initialVolume_ = r.volume;

  if (Pstream::master()) {
    const fileName dir = mesh_.time().globalPath() / "postProcessing" / this->name();
    mkDir(dir);
    const auto mode = restart ? std::ios::app : std::ios::trunc;
    series_.open(dir / "timeSeries.csv", std::ios::out | mode);
    profiles_.open(dir / "profiles.csv", std::ios::out | mode);
    if (!series_ || !profiles_) {
      FatalErrorInFunction << "cannot write " << dir << "/timeSeries.csv, profiles.csv"
                           << exit(FatalError);
    }
    series_.precision(12);
    profiles_.precision(10);
    if (!restart) {
      series_ << "time_s,deltaT_s,front_bed_m,front_any_m,volume_domain_m3,volume_outlet_m3,"
                 "volume_top_m3,volume_balance,kinetic_energy_J,potential_energy_J,mean_ux_m_s,"
                 "mean_uy_m_s,back_wall_depth_m,section_x_m,section_depth_m,"
                 "section_velocity_m_s,section_froude,back_wall_surface_m,section_surface_m\n";
      profiles_ << "time_s,x_m,depth_m,discharge_m2_s,surface_m\n";
    }
  }
  if (!restart) {
    writeRow(r);
    writeProfiles();
  }
  Info << type() << " " << this->name() << ": initial liquid volume " << r.volume << " m3, "
       << nColumns_ << " columns of " << columnLength_ << " m, channel width " << width_
       << " m, section x = " << sectionX_ << " m" << (restart ? " (continuing)" : "") << nl << endl;
}

bool liquidObservables::read(const dictionary& dict) {
  fvMeshFunctionObject::read(dict);
  // The outflow is integrated step by step: every step must be seen.
  if (dict.lookupOrDefault<word>("executeControl", "timeStep") != "timeStep" ||
      dict.lookupOrDefault<label>("executeInterval", 1) != 1) {
    FatalIOErrorInFunction(dict) << type() << " needs executeControl timeStep and "
                                 << "executeInterval 1 (it integrates the outflow per step)"
                                 << exit(FatalIOError);
  }
  alphaName_ = dict.get<word>("alpha");
  rhoLiquid_ = dict.get<scalar>("rhoLiquid");
  outletPatch_ = dict.lookupOrDefault<word>("outletPatch", "outlet");
  topPatch_ = dict.lookupOrDefault<word>("topPatch", "atmosphere");
  threshold_ = dict.lookupOrDefault<scalar>("frontThreshold", 0.5);
  sectionX_ = dict.lookupOrDefault<scalar>("sectionX", -1);
  minDepth_ = dict.get<scalar>("minDepth");
  froudeDepth_ = dict.lookupOrDefault<word>("froudeDepth", "surface");
  nColumns_ = dict.get<label>("nColumns");
  if (rhoLiquid_ <= 0 || threshold_ <= 0 || threshold_ >= 1 || minDepth_ <= 0 || nColumns_ < 1) {
    FatalIOErrorInFunction(dict) << type() << ": need rhoLiquid > 0, 0 < frontThreshold < 1, "
                                 << "minDepth > 0, nColumns >= 1" << exit(FatalIOError);
  }
  if (froudeDepth_ != "surface" && froudeDepth_ != "volume") {
    FatalIOErrorInFunction(dict) << type() << ": froudeDepth '" << froudeDepth_
                                 << "' is not allowed; choose surface or volume"
                                 << exit(FatalIOError);
  }
  const dictionary& alphaControls = mesh_.solverDict(alphaName_);
  if (alphaControls.lookupOrDefault<label>("nAlphaSubCycles", 1) != 1) {
    FatalIOErrorInFunction(alphaControls)
        << type() << " needs nAlphaSubCycles 1: the stored "
        << "liquid flux is then the flux of the whole step" << exit(FatalIOError);
  }
  return true;
}

void liquidObservables::setGeometry() {
  const boundBox bb(mesh_.points(), true);
  origin_ = bb.min();
  columnLength_ = bb.span().x() / nColumns_;
  width_ = bb.span().z();

  const volVectorField& C = mesh_.C();
  // Bed row: cells whose centre lies below one cell height, i.e. below twice the lowest centre.
  const scalar lowest = returnReduce(min(C.primitiveField().component(vector::Y)), minOp<scalar>());
  const scalar bedTop = origin_.y() + 2 * (lowest - origin_.y());
  isBed_.setSize(mesh_.nCells());
  column_.setSize(mesh_.nCells());
  forAll(C, celli) {
    isBed_[celli] = C[celli].y() < bedTop;
    column_[celli] =
        min(nColumns_ - 1, max(label(0), label((C[celli].x() - origin_.x()) / columnLength_)));
  }

  outletID_ = mesh_.boundaryMesh().findPatchID(outletPatch_);
  topID_ = mesh_.boundaryMesh().findPatchID(topPatch_);
  if (outletID_ < 0 || topID_ < 0) {
    FatalErrorInFunction << type() << ": patch " << outletPatch_ << " or " << topPatch_
                         << " not found" << exit(FatalError);
  }

  if (sectionX_ >= 0) {
    const scalar s = (sectionX_ - origin_.x()) / columnLength_ - 0.5;
    sectionI0_ = min(nColumns_ - 2, max(label(0), label(std::floor(s))));
    sectionW_ = min(scalar(1), max(scalar(0), s - sectionI0_));
    if (nColumns_ < 2) sectionI0_ = -1;
  }
}

scalar liquidObservables::patchLiquidFlux(const label patchi) const {
  const word name = IOobject::groupName("alphaPhi0", IOobject::group(alphaName_));
  const surfaceScalarField& alphaPhi = mesh_.lookupObject<surfaceScalarField>(name);
  return gSum(alphaPhi.boundaryField()[patchi]);
}

liquidObservables::Row liquidObservables::measure() {
  const volScalarField& alpha = mesh_.lookupObject<volScalarField>(alphaName_);
  const volVectorField& U = mesh_.lookupObject<volVectorField>("U");
  const volScalarField* eps = mesh_.findObject<volScalarField>("voidfraction");
  const meshObjects::gravity& g = meshObjects::gravity::New(mesh_.time());
  const scalarField& V = mesh_.V();
  const volVectorField& C = mesh_.C();

  Row r;
  depth_ = scalarField(nColumns_, 0.0);
  surface_ = scalarField(nColumns_, 0.0);
  discharge_ = scalarField(nColumns_, 0.0);
  scalar frontBed = -GREAT, frontAny = -GREAT;
  vector momentum = Zero;
  forAll(alpha, celli) {
    const scalar vl = (eps ? (*eps)[celli] : 1.0) * alpha[celli] * V[celli];  // liquid volume
    r.volume += vl;
    r.kinetic += 0.5 * rhoLiquid_ * vl * magSqr(U[celli]);
    r.potential += -rhoLiquid_ * vl * (g.value() & (C[celli] - origin_));
    momentum += vl * U[celli];
    depth_[column_[celli]] += vl;
    surface_[column_[celli]] += alpha[celli] * V[celli];  // pores counted full
    discharge_[column_[celli]] += vl * U[celli].x();
    if (alpha[celli] >= threshold_) {
      frontAny = max(frontAny, C[celli].x());
      if (isBed_[celli]) frontBed = max(frontBed, C[celli].x());
    }
  }

  // Sub-cell front: the alpha = threshold crossing between x-neighbours.
  const vectorField& Sf = mesh_.Sf();
  const labelUList& own = mesh_.owner();
  const labelUList& nei = mesh_.neighbour();
  forAll(nei, facei) {
    if (mag(Sf[facei].x()) < kXNormal * mag(Sf[facei])) continue;
    label u = own[facei], d = nei[facei];
    if (C[u].x() > C[d].x()) std::swap(u, d);
    if (alpha[u] >= threshold_ && alpha[d] < threshold_) {
      const scalar x = crossing(C[u].x(), alpha[u], C[d].x(), alpha[d], threshold_);
      frontAny = max(frontAny, x);
      if (isBed_[u] && isBed_[d]) frontBed = max(frontBed, x);
    }
  }
  forAll(alpha.boundaryField(), patchi) {
    const fvPatchScalarField& ap = alpha.boundaryField()[patchi];
    const fvPatch& p = ap.patch();
    const labelUList& cells = p.faceCells();
    if (ap.coupled()) {
      // Processor (or cyclic) neighbour across the patch; on a uniform mesh its centre is the
      // owner's mirrored through the face.
      const scalarField an(ap.patchNeighbourField());
      forAll(cells, i) {
        const vector& s = p.Sf()[i];
        if (mag(s.x()) < kXNormal * mag(s)) continue;
        const label o = cells[i];
        const scalar xo = C[o].x(), xn = 2 * p.Cf()[i].x() - xo;
        if (xn > xo && alpha[o] >= threshold_ && an[i] < threshold_) {
          const scalar x = crossing(xo, alpha[o], xn, an[i], threshold_);
          frontAny = max(frontAny, x);
          if (isBed_[o]) frontBed = max(frontBed, x);
        }
      }
    } else if (patchi == outletID_) {
      // Liquid at the outlet: the front has reached the channel end.
      forAll(cells, i) {
        if (alpha[cells[i]] >= threshold_) {
          const scalar x = p.Cf()[i].x();
          frontAny = max(frontAny, x);
          if (isBed_[cells[i]]) frontBed = max(frontBed, x);
        }
      }
    }
  }
  reduce(frontBed, maxOp<scalar>());
  reduce(frontAny, maxOp<scalar>());
  r.frontBed = frontBed > -GREAT ? frontBed : kNaN;
  r.frontAny = frontAny > -GREAT ? frontAny : kNaN;

  reduce(r.volume, sumOp<scalar>());
  reduce(r.kinetic, sumOp<scalar>());
  reduce(r.potential, sumOp<scalar>());
  reduce(momentum, sumOp<vector>());
  r.meanU = r.volume > VSMALL ? momentum / r.volume : vector::zero;

  Pstream::listCombineGather(depth_, plusEqOp<scalar>());
  Pstream::listCombineScatter(depth_);
  Pstream::listCombineGather(surface_, plusEqOp<scalar>());
  Pstream::listCombineScatter(surface_);
  Pstream::listCombineGather(discharge_, plusEqOp<scalar>());
  Pstream::listCombineScatter(discharge_);
  const scalar area = columnLength_ * width_;  // plan area of a column
  depth_ /= area;
  surface_ /= area;
  discharge_ /= area;

  r.backDepth = depth_[0];
  r.backSurface = surface_[0];
  r.sectionDepth = r.sectionSurface = r.sectionVelocity = r.froude = kNaN;
  if (sectionI0_ >= 0) {
    const scalar w = sectionW_;
    const auto atSection = [&](const scalarField& f) {
      return (1 - w) * f[sectionI0_] + w * f[sectionI0_ + 1];
    };
    const scalar h = atSection(depth_);
    r.sectionDepth = h;
    r.sectionSurface = atSection(surface_);
    // Fr = v / sqrt(g h): v the mean liquid velocity q / (liquid volume depth); h the flow depth
    // froudeDepth says (the liquid surface, or the liquid volume depth).
    const scalar hFr = froudeDepth_ == "surface" ? r.sectionSurface : h;
    if (h >= minDepth_ && hFr >= minDepth_) {
      r.sectionVelocity = atSection(discharge_) / h;
      r.froude = r.sectionVelocity / std::sqrt(mag(g.value()) * hFr);
    }
  }
  return r;
}

void liquidObservables::writeRow(const Row& r) {
  if (!Pstream::master()) return;
  const scalar balance =
      (initialVolume_ - r.volume - outletVolume_ - topVolume_) / max(initialVolume_, VSMALL);
  const Time& t = mesh_.time();
  const scalar dt = t.timeIndex() == 0 ? 0 : t.deltaTValue();
  series_ << t.value() << ',' << dt << ',' << r.frontBed << ',' << r.frontAny << ',' << r.volume
          << ',' << outletVolume_ << ',' << topVolume_ << ',' << balance << ',' << r.kinetic << ','
          << r.potential << ',' << r.meanU.x() << ',' << r.meanU.y() << ',' << r.backDepth << ','
          << (sectionI0_ >= 0 ? sectionX_ : kNaN) << ',' << r.sectionDepth << ','
          << r.sectionVelocity << ',' << r.froude << ',' << r.backSurface << ',' << r.sectionSurface
          << '\n';
  series_.flush();
}

void liquidObservables::writeProfiles() {
  if (!Pstream::master()) return;
  const scalar t = mesh_.time().value();
  forAll(depth_, i) {
    profiles_ << t << ',' << origin_.x() + (i + 0.5) * columnLength_ << ',' << depth_[i] << ','
              << discharge_[i] << ',' << surface_[i] << '\n';
  }
  profiles_.flush();
}

bool liquidObservables::execute() {
  const Time& t = mesh_.time();
  if (t.timeIndex() == lastTimeIndex_) return true;  // already counted this step
  lastTimeIndex_ = t.timeIndex();
  // The liquid flux alphaPhi0 of this step, positive out of the domain.
  const scalar dt = t.deltaTValue();
  outletVolume_ += dt * patchLiquidFlux(outletID_);
  topVolume_ += dt * patchLiquidFlux(topID_);
  writeRow(measure());
  setProperty("initialVolume", initialVolume_);
  setProperty("outletVolume", outletVolume_);
  setProperty("topVolume", topVolume_);
  return true;
}

bool liquidObservables::write() {
  writeProfiles();
  return true;
}

}  // namespace functionObjects
}  // namespace Foam
