// FoamCellLocator: see FoamCellLocator.H.
#include "FoamCellLocator.H"

#include <algorithm>
#include <cmath>

namespace mixflow::coupling {

namespace {
// A hop walk longer than this falls back to meshSearch (a seed far from the point, or a cycle
// between cells of a badly skewed mesh).
constexpr int kMaxHops = 16;
}  // namespace

FoamCellLocator::FoamCellLocator(const Foam::fvMesh& mesh)
    : mesh_(mesh),
      search_(mesh, Foam::polyMesh::CELL_TETS),
      bounds_(mesh.points(), false) {  // this rank's (sub)mesh, not reduced over ranks
  // Inflate by a relative 1e-9 so that points on the outer boundary faces are not lost to the
  // box test (the cell test decides them).
  const Foam::vector span = bounds_.span();
  const Foam::scalar tol = 1e-9 * Foam::mag(span);
  bounds_.min() -= Foam::vector(tol, tol, tol);
  bounds_.max() += Foam::vector(tol, tol, tol);

  const Foam::label nCells = mesh.nCells();
  firstPlane_.assign(nCells + 1, 0);
  forAll(mesh.cells(), c) { firstPlane_[c + 1] = firstPlane_[c] + mesh.cells()[c].size(); }
  planes_.resize(firstPlane_[nCells]);
  spansZ_.assign(nCells, 0);
  forAll(mesh.cells(), c) {
    long k = firstPlane_[c];
    for (const Foam::label f : mesh.cells()[c]) {
      const bool owner = mesh.faceOwner()[f] == c;
      Plane& pl = planes_[k++];
      pl.n = mesh.faceAreas()[f] / Foam::mag(mesh.faceAreas()[f]);
      if (!owner) pl.n = -pl.n;
      pl.d = pl.n & mesh.faceCentres()[f];
      if (mesh.isInternalFace(f)) pl.across = owner ? mesh.faceNeighbour()[f] : mesh.faceOwner()[f];
    }
  }
}

void FoamCellLocator::setPeriodicZ(double lo, double hi) {
  periodicZ_ = true;
  zLo_ = lo;
  zSpan_ = hi - lo;
  const double tol = 1e-9 * zSpan_;
  for (size_t c = 0; c + 1 < firstPlane_.size(); ++c) {
    bool atLo = false, atHi = false;
    for (long k = firstPlane_[c]; k < firstPlane_[c + 1]; ++k) {
      Plane& pl = planes_[k];
      if (pl.across >= 0 || std::abs(std::abs(pl.n.z()) - 1) > 1e-9) continue;
      // Outward +z: the face is z = d; outward -z: z = -d.
      if (pl.n.z() > 0 && std::abs(pl.d - hi) < tol) pl.wrapZ = atHi = true;
      if (pl.n.z() < 0 && std::abs(-pl.d - lo) < tol) pl.wrapZ = atLo = true;
    }
    spansZ_[c] = atLo && atHi;
  }
}

// From the seed, cross the face the point is furthest beyond until a cell holds it; -1 if that
// would leave the local mesh or take more than kMaxHops.
long FoamCellLocator::hop(const Foam::point& q, long seed) const {
  long c = seed;
  for (int step = 0; step <= kMaxHops; ++step) {
    double worst = 0;
    long next = -1;
    bool outside = false;
    for (long k = firstPlane_[c]; k < firstPlane_[c + 1]; ++k) {
      const double s = (planes_[k].n & q) - planes_[k].d;
      if (s > worst) {
        worst = s;
        next = planes_[k].across;
        outside = true;
      }
    }
    if (!outside) return c;
    if (next < 0) return -1;
    c = next;
  }
  return -1;
}

Foam::point FoamCellLocator::wrapped(const Vec3& p) const {
  double z = p.z;
  if (periodicZ_ && (z < zLo_ || z >= zLo_ + zSpan_)) {
    z = zLo_ + std::fmod(z - zLo_, zSpan_);
    if (z < zLo_) z += zSpan_;
  }
  return Foam::point(p.x, p.y, z);
}

long FoamCellLocator::findCell(const Vec3& p, long seed) const {
  const Foam::point q = wrapped(p);
  if (!bounds_.contains(q)) return -1;
  if (seed >= 0 && seed < mesh_.nCells()) {
    const long c = hop(q, seed);
    if (c >= 0) return c;
    const Foam::label w = search_.findCell(q, seed, false);  // meshSearch's walk
    if (w >= 0) return w;
  }
  return search_.findCell(q, -1, true);  // octree
}

// The sphere is inside a convex cell if it is at least r behind every face plane; with a
// z-periodic box, a cell spanning the whole z range also holds the wrapped parts.
bool FoamCellLocator::sphereInsideCell(const Vec3& centre, double r, long cell) const {
  const Foam::point c(centre.x, centre.y, centre.z);
  const bool wrapped = periodicZ_ && spansZ_[cell];
  for (long k = firstPlane_[cell]; k < firstPlane_[cell + 1]; ++k) {
    if (wrapped && planes_[k].wrapZ) continue;
    if (planes_[k].d - (planes_[k].n & c) < r) return false;
  }
  return true;
}

// The planes sphereInsideCell finds closer than r. A point of the sphere behind all of them is
// behind every plane of the cell, so the hop walk would return the cell itself; a wrapped point
// of a z-spanning cell keeps its x and y, which the remaining planes (normals in x-y) test.
bool FoamCellLocator::crossedFaces(const Vec3& centre, double r, long cell,
                                   std::vector<HalfSpace>& out) const {
  out.clear();
  const Foam::point c(centre.x, centre.y, centre.z);
  const bool wrapped = periodicZ_ && spansZ_[cell];
  for (long k = firstPlane_[cell]; k < firstPlane_[cell + 1]; ++k) {
    const Plane& pl = planes_[k];
    if (wrapped && pl.wrapZ) continue;
    if (pl.d - (pl.n & c) < r) out.push_back({Vec3(pl.n.x(), pl.n.y(), pl.n.z()), pl.d});
  }
  return true;
}

void FoamCellLocator::facesNear(const Vec3& p, long cell, double band,
                                std::vector<NearFace>& out) const {
  out.clear();
  const Foam::point q = wrapped(p);
  for (long k = firstPlane_[cell]; k < firstPlane_[cell + 1]; ++k) {
    const Plane& pl = planes_[k];
    if (pl.across < 0) continue;
    const double d = std::max(0.0, pl.d - (pl.n & q));  // >= 0 inside (round-off clamped)
    if (d < band) out.push_back({pl.across, d, Vec3(pl.n.x(), pl.n.y(), pl.n.z())});
  }
}

}  // namespace mixflow::coupling
