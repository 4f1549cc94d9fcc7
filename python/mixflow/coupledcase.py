"""Case writer for mixflowCoupled tests: a closed 3-D box (one blockMesh block, uniform cells,
all faces no-slip walls, y up, g = (0, -9.81, 0)) filled with liquid or part liquid/part air,
plus constant/couplingProperties and the particle scene as LIGGGHTS commands (system/in.liggghts).

Standard library only; OpenFOAM file helpers come from python/mixflow/foamcase.py.
"""

import csv
import os
import shutil
import sys

from mixflow import foamcase as fc
from mixflow import outputs

G = 9.81


class Box:
    """[0, Lx] x [0, Ly] x [0, Lz] with nx x ny x nz cells; cell (i, j, k) = i + nx (j + ny k)."""

    def __init__(self, L, n):
        self.L, self.n = tuple(L), tuple(n)
        self.h = tuple(L[a] / n[a] for a in range(3))

    @property
    def ncells(self):
        return self.n[0] * self.n[1] * self.n[2]

    @property
    def cell_volume(self):
        return self.h[0] * self.h[1] * self.h[2]

    def centres(self):
        nx, ny, nz = self.n
        for k in range(nz):
            for j in range(ny):
                for i in range(nx):
                    yield ((i + 0.5) * self.h[0], (j + 0.5) * self.h[1], (k + 0.5) * self.h[2])


def block_mesh_dict(box, open_top=False):
    Lx, Ly, Lz = box.L
    nx, ny, nz = box.n
    top = "patch" if open_top else "wall"
    return f"""convertToMeters 1;
vertices
(
    (0 0 0) ({Lx} 0 0) ({Lx} {Ly} 0) (0 {Ly} 0)
    (0 0 {Lz}) ({Lx} 0 {Lz}) ({Lx} {Ly} {Lz}) (0 {Ly} {Lz})
);
blocks ( hex (0 1 2 3 4 5 6 7) ({nx} {ny} {nz}) simpleGrading (1 1 1) );
edges ();
boundary
(
    walls {{ type wall; faces ( (0 4 7 3) (1 2 6 5) (0 1 5 4) (0 3 2 1) (4 5 6 7) ); }}
    top {{ type {top}; faces ( (3 7 6 2) ); }}
);
mergePatchPairs ();
"""


CONTROL = """application     mixflowCoupled;
startFrom       startTime;
startTime       0;
stopAt          endTime;
endTime         {end};
deltaT          {dt};
writeControl    timeStep;
writeInterval   {wsteps};
purgeWrite      0;
writeFormat     ascii;
writePrecision  17;
writeCompression off;
timeFormat      general;
timePrecision   8;
runTimeModifiable no;
adjustTimeStep  no;
maxCo           1;
maxAlphaCo      1;
maxDeltaT       1;
"""

SCHEMES = fc.VOF_SCHEMES

SOLUTION = """solvers
{
    "alpha.water.*"
    {
        nAlphaCorr      2;
        nAlphaSubCycles 1;
        cAlpha          1;
        MULESCorr       yes;
        nLimiterIter    5;
        solver          smoothSolver;
        smoother        symGaussSeidel;
        tolerance       1e-10;
        relTol          0;
    }
    "pcorr.*" { solver PCG; preconditioner DIC; tolerance 1e-10; relTol 0; }
    p_rgh { solver PCG; preconditioner DIC; tolerance {ptol}; relTol 0; }
    p_rghFinal { $p_rgh; relTol 0; }
    "U.*" { solver smoothSolver; smoother symGaussSeidel; tolerance 1e-10; relTol 0; }
}
PIMPLE
{
    momentumPredictor   no;
    nOuterCorrectors    1;
    nCorrectors         3;
    nNonOrthogonalCorrectors 0;
    pRefCell 0;
    pRefValue 0;
}
relaxationFactors { equations { ".*" 1; } }
"""


def transport(rho_l, nu_l):
    return (f"phases (water air);\nwater\n{{\n    transportModel Newtonian; nu {nu_l!r}; "
            f"rho {rho_l!r};\n}}\n"
            "air\n{\n    transportModel Newtonian; nu 1.48e-05; rho 1;\n}\nsigma 0.07;\n")


def liggghts_header(box, dt, skin, young=5e6, restitution=0.5, friction=0.5):
    """Box = the fluid mesh's bounding box; one particle type; Hertz contacts; gravity as constant/g."""
    Lx, Ly, Lz = box.L
    return f"""units si
atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
region domain block 0 {Lx!r} 0 {Ly!r} 0 {Lz!r} units box
create_box 1 domain
neighbor {skin!r} bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype {young!r}
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 {restitution!r}
fix m4 all property/global coefficientFriction peratomtypepair 1 {friction!r}
pair_style gran model hertz tangential history
pair_coeff * *
timestep {dt!r}
fix gravi all gravity {G!r} vector 0 -1 0
"""


def transport_herschel_bulkley(rho_l, tau_y, k, n, cap):
    """transportProperties of a Herschel-Bulkley (n = 1: Bingham) liquid, SI dynamic input."""
    return (f"phases (water air);\nwater\n{{\n    transportModel HerschelBulkley;\n"
            f"    HerschelBulkleyCoeffs {{ k {k / rho_l!r}; n {n!r}; tau0 {tau_y / rho_l!r}; "
            f"nu0 {cap / rho_l!r}; }}\n    rho {rho_l!r};\n}}\n"
            "air\n{\n    transportModel Newtonian; nu 1.48e-05; rho 1;\n}\nsigma 0.07;\n")


def write_case(case, box, end, dt_cfd, dem_script, coupling, rho_l=1000.0, nu_l=1e-6,
               liquid_height=None, ptol="1e-10", write_steps=None, mixflow_properties=None,
               open_top=False, transport_text=None):
    """open_top: the lid y = Ly is open to the atmosphere (total pressure 0, air in/outflow),
    else a no-slip wall like the other faces. transport_text: constant/transportProperties'
    body (default: a Newtonian liquid of rho_l, nu_l)."""
    shutil.rmtree(case, ignore_errors=True)
    os.makedirs(case)
    fc.write_foam_file(case, "system/blockMeshDict", "dictionary", "blockMeshDict",
                       block_mesh_dict(box, open_top))
    nsteps = int(round(end / dt_cfd))
    fc.write_foam_file(case, "system/controlDict", "dictionary", "controlDict",
                       CONTROL.format(end=repr(end), dt=repr(dt_cfd),
                                      wsteps=write_steps or nsteps))
    fc.write_foam_file(case, "system/fvSchemes", "dictionary", "fvSchemes", SCHEMES)
    fc.write_foam_file(case, "system/fvSolution", "dictionary", "fvSolution",
                       SOLUTION.replace("{ptol}", ptol))
    fc.write_foam_file(case, "constant/transportProperties", "dictionary", "transportProperties",
                       transport_text or transport(rho_l, nu_l))
    fc.write_foam_file(case, "constant/turbulenceProperties", "dictionary",
                       "turbulenceProperties", "simulationType laminar;\n")
    fc.write_foam_file(case, "constant/g", "uniformDimensionedVectorField", "g",
                       f"dimensions [0 1 -2 0 0 0 0];\nvalue (0 {-G!r} 0);\n")
    fc.write_foam_file(case, "constant/couplingProperties", "dictionary", "couplingProperties",
                       coupling)
    if mixflow_properties:
        fc.write_foam_file(case, "constant/mixflowProperties", "dictionary", "mixflowProperties",
                           mixflow_properties)
    with open(os.path.join(case, "system", "in.liggghts"), "w") as f:
        f.write(dem_script)

    def wall(e, top=None):
        top = top if (open_top and top) else e
        return f"boundaryField\n{{\n    walls {{ {e} }}\n    top {{ {top} }}\n}}\n"
    if liquid_height is None:
        alpha = "uniform 1"
    else:
        alpha = fc.format_scalar_list([
            min(max((liquid_height - (c[1] - 0.5 * box.h[1])) / box.h[1], 0.0), 1.0)
            for c in box.centres()])
    fc.write_foam_file(case, "0/alpha.water", "volScalarField", "alpha.water",
                       f"dimensions [0 0 0 0 0 0 0];\ninternalField {alpha};\n" +
                       wall("type zeroGradient;",
                            "type inletOutlet; inletValue uniform 0; value uniform 0;"))
    fc.write_foam_file(case, "0/U", "volVectorField", "U",
                       "dimensions [0 1 -1 0 0 0 0];\ninternalField uniform (0 0 0);\n" +
                       wall("type noSlip;",
                            "type pressureInletOutletVelocity; value uniform (0 0 0);"))
    fc.write_foam_file(case, "0/p_rgh", "volScalarField", "p_rgh",
                       "dimensions [1 -1 -2 0 0 0 0];\ninternalField uniform 0;\n" +
                       wall("type fixedFluxPressure; value uniform 0;",
                            "type totalPressure; p0 uniform 0;"))


def run(case, solver, blockmesh, np=1, mpiexec=None, decomposepar=None, reconstructpar=None,
        log="log.mixflowCoupled"):
    """blockMesh, then the solver serially or on np ranks (simple decomposition in np slabs along
    x; the coupling gives LIGGGHTS the matching processor grid); reconstructPar if given."""
    fc.run([blockmesh], case, "log.blockMesh")
    if np <= 1:
        return fc.run([solver], case, log)
    fc.set_decomposition(case, np)
    fc.run([decomposepar or "decomposePar", "-force"], case, "log.decomposePar")
    text = fc.run(fc.launcher_tokens(mpiexec or "mpirun --allow-run-as-root --oversubscribe") +
                  ["-x", "WM_PROJECT_DIR", "-np", str(np), solver, "-parallel"], case, log)
    if reconstructpar:
        fc.run([reconstructpar], case, "log.reconstructPar")
    return text


def add_parallel_args(ap):
    ap.add_argument("--np", type=int, default=1, help="MPI ranks (simple decomposition along x)")
    ap.add_argument("--mpiexec", default="mpirun --allow-run-as-root --oversubscribe")
    ap.add_argument("--decomposepar", default="decomposePar")
    ap.add_argument("--reconstructpar", default="reconstructPar")


def add_fluid_response_arg(ap):
    ap.add_argument("--drag-fluid-response", default="none", choices=("none", "share", "continuity"),
                    help="couplingProperties dragFluidResponse (implicit drag)")
    ap.add_argument("--drag-coefficient-update", choices=("slip", "exchange"),
                    help="couplingProperties dragCoefficientUpdate (default: the solver's)")
    ap.add_argument("--pressure-coupling", choices=("fluid", "mixture"),
                    help="couplingProperties pressureCoupling (default: the code's, mixture for "
                         "the implicit drag without dragFluidResponse, fluid otherwise)")
    ap.add_argument("--void-smoothing", type=float,
                    help="couplingProperties dividedCoeffs smoothing (default: the code's, 0); "
                         "coupling/README.md, 'Void fraction jumps'")


def fluid_response_entry(a):
    """The couplingProperties lines for --drag-fluid-response, --drag-coefficient-update,
    --pressure-coupling and --void-smoothing."""
    text = f"dragFluidResponse {a.drag_fluid_response};\n"
    if a.drag_coefficient_update:
        text += f"dragCoefficientUpdate {a.drag_coefficient_update};\n"
    if a.pressure_coupling:
        text += f"pressureCoupling {a.pressure_coupling};\n"
    if a.void_smoothing is not None:
        text += f"dividedCoeffs {{ smoothing {a.void_smoothing!r}; }}\n"
    return text


def read_exchange_log(case):
    """postProcessing/coupling/exchange.csv as a list of dicts of floats."""
    path = os.path.join(case, outputs.EXCHANGE)
    rows = outputs.read_series(path, comments=True)
    if not rows:
        fc.fail(f"{path} has no rows")
    return rows


def read_reference(path, key_col, key):
    """Row of a tests/reference CSV ('#' comments, header, "..." quoting) whose key_col == key."""
    with open(path) as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    for r in rows:
        if r[key_col] == key:
            return r
    fc.fail(f"{path}: no row with {key_col} = {key}")


def powerlaw_sphere_factor(reference_dir, n):
    """X(n) of tests/reference/powerlaw_sphere_drag_correction.csv, linear in n; 1 for n >= 1
    (coupling/models/dragViscosity/DragViscosity.h powerLawSphereFactor)."""
    if n >= 1:
        return 1.0
    path = os.path.join(reference_dir, "powerlaw_sphere_drag_correction.csv")
    with open(path) as f:
        rows = sorted((float(r["n"]), float(r["X_numerical"])) for r in
                      csv.DictReader(line for line in f if not line.startswith("#")))
    for (n0, x0), (n1, x1) in zip(rows, rows[1:]):
        if n0 <= n <= n1:
            return x0 + (x1 - x0) * (n - n0) / (n1 - n0)
    sys.exit(f"{path}: n = {n} outside the table")


def powerlaw_shape_factor(reference_dir, n, eps, shear_rate_factor=1.0):
    """The slip closure's power-law shape factor X(n)^(1-w) ((3n + 1) / 4n)^(n w), w = pore /
    (pore + factor), pore = 12 (1 - eps) / eps (coupling/models/dragViscosity/DragViscosity.h powerLawShapeFactor)."""
    if n >= 1:
        return 1.0
    pore = 12 * (1 - eps) / eps
    w = pore / (pore + shear_rate_factor)
    return powerlaw_sphere_factor(reference_dir, n) ** (1 - w) * \
        ((3 * n + 1) / (4 * n)) ** (n * w)


def check(ok, what):
    print(("  PASS " if ok else "  FAIL ") + what, flush=True)
    return ok
