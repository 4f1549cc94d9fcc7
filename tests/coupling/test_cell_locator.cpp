// test_cell_locator -case DIR [-periodicZ]: the coupling's cell search (FoamCellLocator) against
// OpenFOAM's own meshSearch (octree, tetrahedral decomposition) on the case's mesh.
//
// Checks, for random points in the mesh's bounding box:
//   1. findCell(p, seed) equals meshSearch's cell for seeds near p (the centre's cell, as the
//      divided void fraction seeds a sphere's points), far from p (a random cell) and none (-1);
//   2. points outside the mesh give -1;
//   3. sphereInsideCell(centre, r, cell) true => every one of the 48 sphere points of the divided
//      model is found in `cell` (with -periodicZ: after wrapping z into the mesh's z range, and
//      a 2-D mesh's cells then hold the spheres that cross its front and back);
//   4. a sphere point behind all of crossedFaces(centre, r, cell) is found in `cell`, and at
//      least one point of a sphere that is not inside its cell is beyond one of them.
// Exit status 1 on the first kind of failure, with counts; prints how many spheres and points
// took the shortcuts (the locator's fast paths must be used, not only be correct).
#include <cmath>
#include <random>

#include "FoamCellLocator.H"
#include "SpherePoints.h"
#include "fvCFD.H"
#include "meshSearch.H"

using mixflow::coupling::FoamCellLocator;
using mixflow::coupling::SpherePoints;
using mixflow::coupling::Vec3;

int main(int argc, char* argv[]) {
  argList::addBoolOption("periodicZ", "treat the mesh's z range as the particles' periodic box");
  argList::addOption("points", "N", "random points (default 20000)");
  // clang-format off
#include "setRootCase.H"
#include "createTime.H"
#include "createMesh.H"
  // clang-format on

  const bool periodicZ = args.found("periodicZ");
  const label nPoints = args.lookupOrDefault<label>("points", 20000);
  const boundBox bb(mesh.points(), false);
  FoamCellLocator locator(mesh);
  if (periodicZ) locator.setPeriodicZ(bb.min().z(), bb.max().z());
  meshSearch reference(mesh, polyMesh::CELL_TETS);

  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> u01(0, 1);
  auto randomIn = [&](double margin) {
    const vector s = bb.span();
    return point(bb.min().x() - margin * s.x() + (1 + 2 * margin) * s.x() * u01(rng),
                 bb.min().y() - margin * s.y() + (1 + 2 * margin) * s.y() * u01(rng),
                 bb.min().z() + s.z() * u01(rng));
  };
  auto wrapZ = [&](point q) {
    if (!periodicZ) return q;
    const double lo = bb.min().z(), span = bb.max().z() - lo;
    q.z() = lo + std::fmod(q.z() - lo, span);
    if (q.z() < lo) q.z() += span;
    return q;
  };
  std::uniform_int_distribution<label> anyCell(0, mesh.nCells() - 1);

  // 1 and 2.
  label wrong = 0, outsideWrong = 0, inside = 0, outside = 0;
  for (label i = 0; i < nPoints; ++i) {
    const point q = randomIn(0.1);
    const label ref = reference.findCell(q, -1, true);
    const Vec3 p(q.x(), q.y(), q.z());
    const long seeds[3] = {ref >= 0 ? ref : -1, anyCell(rng), -1};
    for (const long seed : seeds) {
      const long got = locator.findCell(p, seed);
      if (ref < 0) {
        if (got != -1) ++outsideWrong;
      } else if (got != ref) {
        ++wrong;
      }
    }
    (ref < 0 ? outside : inside)++;
  }

  // 3. Spheres of diameter a third of the mean cell size, centred at random inside the mesh.
  const double cellSize = std::cbrt(gSum(mesh.V()) / mesh.nCells());
  const double r = cellSize / 6;
  const SpherePoints pts = SpherePoints::make(3, 16);
  label shortcut = 0, shortcutWrong = 0, pointWrong = 0, spheres = 0;
  label behind = 0, behindWrong = 0, crossedNone = 0;
  std::vector<mixflow::coupling::CellLocator::HalfSpace> crossed;
  for (label i = 0; i < nPoints / 10; ++i) {
    const point c = randomIn(0);
    const label cc = reference.findCell(c, -1, true);
    if (cc < 0) continue;
    ++spheres;
    const Vec3 centre(c.x(), c.y(), c.z());
    const bool in = locator.sphereInsideCell(centre, r, cc);
    shortcut += in;
    locator.crossedFaces(centre, r, cc, crossed);
    if (!in && crossed.empty()) ++crossedNone;
    for (const Vec3& o : pts.offsets) {
      const Vec3 p = centre + r * o;
      const point q = wrapZ(point(p.x, p.y, p.z));
      const label ref = reference.findCell(q, -1, true);
      if (locator.findCell(p, cc) != ref) ++pointWrong;
      if (in && ref != cc) ++shortcutWrong;
      bool behindAll = true;
      for (const auto& h : crossed) behindAll = behindAll && dot(h.n, p) - h.d <= 0;
      if (!in && behindAll) {
        ++behind;
        if (ref != cc) ++behindWrong;
      }
    }
  }

  Info << "points inside/outside the mesh: " << inside << " / " << outside << "; seeds per point: 3"
       << nl << "  findCell differing from meshSearch: " << wrong << nl
       << "  outside points given a cell: " << outsideWrong << nl << "spheres (r = " << r
       << " m): " << spheres << ", inside their centre's cell: " << shortcut << nl
       << "  sphere points differing from meshSearch: " << pointWrong << nl
       << "  shortcut spheres with a point elsewhere: " << shortcutWrong << nl
       << "points of the other spheres behind their centre cell's crossed faces: " << behind << nl
       << "  of these, elsewhere: " << behindWrong << nl
       << "  spheres not inside with no crossed face: " << crossedNone << endl;
  const bool ok = wrong == 0 && outsideWrong == 0 && pointWrong == 0 && shortcutWrong == 0 &&
                  behindWrong == 0 && crossedNone == 0 && shortcut > 0 && behind > 0 && inside > 0;
  Info << (ok ? "PASS" : "FAIL") << endl;
  return ok ? 0 : 1;
}
