"""Liquid cases as a user writes them (constant/sceneProperties, system/cfdDict,
system/controlDict only), run through mixflowPrepare, blockMesh and a solver, serial or decomposed,
and their liquidObservables outputs read back: the liquid tests' case writer
(tests/cfd/run_liquid_cases.py, run_bulk_model.py), `mixflow martin-moyce-interfoam` and
bench/piso_correctors.py. The Martin & Moyce (1952) column (n^2 = 1) is the scene they share.

`run_case` takes the programs from an argparse namespace A: A.prepare, A.blockmesh, A.solver,
and for a decomposed run A.decomposepar, A.mpiexec, A.reconstructpar.
"""

import os
import re
import shutil

from . import foamcase as fc
from . import outputs


def write_case(case, scene, cfd, end, write_interval):
    shutil.rmtree(case, ignore_errors=True)
    os.makedirs(os.path.join(case, "constant"))
    os.makedirs(os.path.join(case, "system"))
    hdr = "FoamFile { version 2.0; format ascii; class dictionary; object %s; }\n"
    with open(os.path.join(case, "constant/sceneProperties"), "w") as f:
        f.write(hdr % "sceneProperties" + scene)
    with open(os.path.join(case, "system/cfdDict"), "w") as f:
        f.write(hdr % "cfdDict" + cfd)
    with open(os.path.join(case, "system/controlDict"), "w") as f:
        f.write(hdr % "controlDict" + f"endTime {end};\nwriteInterval {write_interval};\n")


def add_program_arguments(parser, root):
    """--prepare, --solver and --blockmesh, the programs run_case takes from its namespace (the
    build's under ROOT, Debian's blockMesh); a serial run's WM_PROJECT_DIR as CTest exports it."""
    parser.add_argument("--prepare", default=os.path.join(root, "build/bin/mixflowPrepare"))
    parser.add_argument("--solver", default=os.path.join(root, "build/bin/mixflowFoam"))
    parser.add_argument("--blockmesh", default="/usr/bin/blockMesh")
    os.environ.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")


def run_case(a, case, np=1, solver=None):
    """mixflowPrepare, blockMesh, the solver (a.solver, mixflowFoam, unless given; serial or np
    ranks). Returns the time series."""
    solver = solver or a.solver
    log_name = "log." + os.path.basename(solver)
    fc.run([a.prepare, "-case", case, "-np", str(np)], case, "log.mixflowPrepare")
    fc.run([a.blockmesh], case, "log.blockMesh")
    if np > 1:
        fc.run([a.decomposepar, "-force"], case, "log.decomposePar")
        log = fc.run(fc.launcher_tokens(a.mpiexec) + ["-x", "WM_PROJECT_DIR", "-np", str(np),
                                                      solver, "-parallel"], case, log_name)
        if not re.search(rf"^nProcs\s*:\s*{np}\s*$", log, re.M):
            fc.fail(f"{case}: not a parallel run on {np} ranks")
        fc.run([a.reconstructpar, "-latestTime"], case, "log.reconstructPar")
    else:
        log = fc.run([solver], case, log_name)
    if "while loading function object" in log or "liquidObservables liquid:" not in log:
        fc.fail(f"{case}: the liquidObservables function object did not run (see the log)")
    return read_series(case)


def read_series(case):
    path = os.path.join(case, outputs.LIQUID_SERIES)
    if not os.path.exists(path):
        fc.fail(f"{path} was not written")
    return outputs.read_series(path)


def read_profiles(case):
    rows = outputs.read_series(os.path.join(case, outputs.LIQUID_PROFILES))
    out = {}
    for r in rows:
        out.setdefault(r["time_s"], []).append((r["x_m"], r["depth_m"]))
    return out


def interp(series, key, t):
    """Linear interpolation of series[key] at time t."""
    for r0, r1 in zip(series, series[1:]):
        if r0["time_s"] <= t <= r1["time_s"]:
            w = (t - r0["time_s"]) / (r1["time_s"] - r0["time_s"])
            return (1 - w) * r0[key] + w * r1[key]
    fc.fail(f"time {t} outside the series")


# ------------------------------------------------------------------------------- Martin & Moyce
# The scene (tests/cfd/run_liquid_cases.py; on interFoam too: mixflow martin-moyce-interfoam).
MM_SIDE = 0.05715
MM_SCENE = (f"content liquid;\nsample {{ length {MM_SIDE}; height {MM_SIDE}; width {MM_SIDE}; }}\n"
            f"channel {{ length {6 * MM_SIDE}; height {1.5 * MM_SIDE}; }}\n"
            "liquid { rheology Newtonian; density 1000; viscosity 0.001; surfaceTension 0.07; }\n")


def write_martin_moyce_case(case, cells, gate=""):
    """The column on a/CELLS, 2-D, to t = 0.26 s (T = 3.4); GATE: the sceneProperties gate
    block's entries (default: none, the instant removal)."""
    scene = MM_SCENE + (f"gate {{ {gate} }}\n" if gate else "")
    write_case(case, scene, f"dimensions 2;\ncellSize {MM_SIDE / cells:.10g};\n", 0.26, 0.13)


def read_martin_moyce(path):
    """{"front_Z": [(T, Z)], "height_eta": [(tau, eta)]} of the reference file."""
    ref = {"front_Z": [], "height_eta": []}
    with open(path) as f:
        for line in f:
            if line.startswith("#") or line.startswith("quantity"):
                continue
            q, t, v = line.strip().split(",")
            ref[q].append((float(t), float(v)))
    return ref
