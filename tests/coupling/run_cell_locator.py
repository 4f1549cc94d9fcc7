"""coupling.cell_locator: the coupling's cell search against OpenFOAM's meshSearch.

Two meshes, written with blockMesh:
  l_shape  3-D, two graded blocks in an L (points in the bounding box but outside the mesh), the
           upper block's top inclined (planar, non-parallel faces), 5 cells in z;
  slab     the mixture cases' 2-D layout, one cell in z, searched with the particle box periodic
           in z (sphere parts beyond the front and back wrap into the same cell column).
test_cell_locator (tests/coupling/test_cell_locator.cpp) then compares every answer with
meshSearch's (exactly: random points are never on a face) and checks the inside-cell shortcut.
"""

import argparse
import os
import shutil
import sys

sys.dont_write_bytecode = True
from mixflow import foamcase as fc  # noqa: E402

CONTROL = """application test_cell_locator;
startFrom startTime; startTime 0; stopAt endTime; endTime 1; deltaT 1;
writeControl timeStep; writeInterval 1;
"""

# fvMesh reads these; the checker solves nothing.
SCHEMES = """ddtSchemes { default Euler; } gradSchemes { default Gauss linear; }
divSchemes { default none; } laplacianSchemes { default Gauss linear corrected; }
interpolationSchemes { default linear; } snGradSchemes { default corrected; }
"""

L_SHAPE = """convertToMeters 1;
vertices
(
    (0 0 0) (1 0 0) (1 0.3 0) (0 0.3 0)
    (0 0 0.2) (1 0 0.2) (1 0.3 0.2) (0 0.3 0.2)
    (0 0.8 0) (0.4 0.7 0) (0.4 0.7 0.2) (0 0.8 0.2)
    (0.4 0.3 0) (0.4 0.3 0.2) (0.4 0 0) (0.4 0 0.2)
);
blocks
(
    hex (0 14 12 3 4 15 13 7) (7 6 5) simpleGrading (1 0.5 1)
    hex (14 1 2 12 15 5 6 13) (10 6 5) simpleGrading (3 0.5 1)
    hex (3 12 9 8 7 13 10 11) (7 9 5) simpleGrading (1 2 1)
);
edges ();
defaultPatch { name walls; type wall; }
boundary ();
mergePatchPairs ();
"""

SLAB = """convertToMeters 1;
vertices
(
    (0 0 0) (2 0 0) (2 0.6 0) (0 0.6 0)
    (0 0 0.072) (2 0 0.072) (2 0.6 0.072) (0 0.6 0.072)
);
blocks ( hex (0 1 2 3 4 5 6 7) (33 10 1) simpleGrading (1 1 1) );
edges ();
boundary
(
    walls { type wall; faces ((0 1 5 4) (0 4 7 3) (1 2 6 5) (3 7 6 2)); }
    frontAndBack { type empty; faces ((0 3 2 1) (4 5 6 7)); }
);
mergePatchPairs ();
"""


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--checker", required=True, help="test_cell_locator executable")
    ap.add_argument("--blockmesh", required=True)
    ap.add_argument("--workdir", required=True)
    a = ap.parse_args()
    fc.require_foam_env()
    shutil.rmtree(a.workdir, ignore_errors=True)
    for name, mesh, extra in (("l_shape", L_SHAPE, []), ("slab", SLAB, ["-periodicZ"])):
        case = os.path.join(a.workdir, name)
        fc.write_foam_file(case, "system/controlDict", "dictionary", "controlDict", CONTROL)
        fc.write_foam_file(case, "system/blockMeshDict", "dictionary", "blockMeshDict", mesh)
        fc.write_foam_file(case, "system/fvSchemes", "dictionary", "fvSchemes", SCHEMES)
        fc.write_foam_file(case, "system/fvSolution", "dictionary", "fvSolution", "")
        fc.run([a.blockmesh, "-case", case], case, "log.blockMesh")
        out = fc.run([a.checker, "-case", case] + extra, case, "log.test_cell_locator")
        print(f"--- {name}\n" + "\n".join(ln for ln in out.splitlines()
                                        if ln.startswith(("points", "spheres", "  ", "PASS"))))
        if "PASS" not in out:
            fc.fail(f"{name}: the cell search differs from meshSearch (log in {case})")
    print("PASS")


if __name__ == "__main__":
    main()
