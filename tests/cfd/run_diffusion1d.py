#!/usr/bin/env python3
"""Run the 1-D diffusion case with mixflowFoamSmoke and check it against the analytic solution.

Steps: copy the case template to a fresh work directory, blockMesh, then either run the solver
serially or decomposePar + `mpirun -np N mixflowFoamSmoke -parallel` + reconstructPar, write the
cell centres with `postProcess -func writeCellCentres`, and compare T in every cell with the
steady analytic profile T(x) = T_left + (T_right - T_left) (x - x_left) / (x_right - x_left).

Pass criteria (all must hold):
  * every program exits with status 0;
  * the solver log says "Steady state reached" (the run stopped on its steadyStateTolerance,
    not on endTime);
  * in parallel: every processor directory holds T at the final time;
  * the number of cells equals --ncells;
  * max |T - T_exact| over all cells <= --tol (absolute).

With --expect-deviation the solver is stopped after --end-time (before steady state) and the
test passes only if the profile check FAILS, i.e. max |T - T_exact| > --tol: this proves the
check can fail.

Exit status 0 = pass, 1 = fail. Uses only the standard library.
"""

import argparse
import math
import os
import re
import shutil

from mixflow.foamcase import (fail, launcher_tokens, read_internal_field, require_foam_env, run,
                      set_decomposition, set_entry, time_dirs)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--solver", required=True, help="path of mixflowFoamSmoke")
    ap.add_argument("--template", required=True, help="case template (system/, constant/, 0/)")
    ap.add_argument("--workdir", required=True, help="case directory to create (wiped first)")
    ap.add_argument("--blockmesh", default="blockMesh")
    ap.add_argument("--decomposepar", default="decomposePar")
    ap.add_argument("--reconstructpar", default="reconstructPar")
    ap.add_argument("--postprocess", default="postProcess")
    ap.add_argument("--np", type=int, default=1, help="MPI ranks (1 = serial run, no mpirun)")
    ap.add_argument("--mpiexec", default="mpirun --allow-run-as-root --oversubscribe",
                    help="MPI launcher command line (split on spaces or ';')")
    ap.add_argument("--ncells", type=int, required=True, help="expected number of cells")
    ap.add_argument("--x-left", type=float, required=True)
    ap.add_argument("--x-right", type=float, required=True)
    ap.add_argument("--t-left", type=float, required=True)
    ap.add_argument("--t-right", type=float, required=True)
    ap.add_argument("--tol", type=float, default=1e-6, help="max absolute deviation allowed")
    ap.add_argument("--expect-deviation", action="store_true",
                    help="negative test: stop early and require the profile check to fail")
    ap.add_argument("--end-time", type=float, default=1.0, help="endTime for --expect-deviation")
    a = ap.parse_args()

    require_foam_env()

    case = os.path.abspath(a.workdir)
    shutil.rmtree(case, ignore_errors=True)
    shutil.copytree(a.template, case)
    if a.expect_deviation:
        control = os.path.join(case, "system", "controlDict")
        set_entry(control, "endTime", a.end_time)
        set_entry(control, "writeInterval", a.end_time)

    run([a.blockmesh], case, "log.blockMesh")

    if a.np > 1:
        set_decomposition(case, a.np)
        run([a.decomposepar], case, "log.decomposePar")
        launcher = launcher_tokens(a.mpiexec)
        # -x: pass OpenFOAM's environment to the ranks explicitly.
        solver_log = run(launcher + ["-x", "WM_PROJECT_DIR", "-np", str(a.np), a.solver, "-parallel"],
                         case, "log.mixflowFoamSmoke")
        final = None
        for p in range(a.np):
            pdir = os.path.join(case, f"processor{p}")
            if not os.path.isdir(pdir):
                fail(f"{pdir} missing after decomposePar")
            times = [t for t in time_dirs(pdir) if t[0] > 0]
            if not times:
                fail(f"{pdir} holds no written time after the parallel run")
            if final is None:
                final = times[-1]
            elif times[-1] != final:
                fail(f"processors disagree on the final time ({final[1]} vs {times[-1][1]})")
            if not os.path.isfile(os.path.join(pdir, final[1], "T")):
                fail(f"{pdir}/{final[1]}/T missing")
        run([a.reconstructpar, "-latestTime"], case, "log.reconstructPar")
    else:
        solver_log = run([a.solver], case, "log.mixflowFoamSmoke")

    steady = "Steady state reached" in solver_log
    if not a.expect_deviation and not steady:
        fail("solver stopped at endTime without reaching steadyStateTolerance")
    if a.np > 1 and not re.search(rf"^nProcs\s*:\s*{a.np}\s*$", solver_log, re.M):
        fail(f"solver log does not show a parallel run on {a.np} ranks (no 'nProcs : {a.np}')")

    times = [t for t in time_dirs(case) if t[0] > 0]
    if not times:
        fail("no time directory written by the solver")
    tname = times[-1][1]
    run([a.postprocess, "-func", "writeCellCentres", "-time", tname], case, "log.postProcess")

    x = read_internal_field(os.path.join(case, tname, "Cx"), a.ncells)
    T = read_internal_field(os.path.join(case, tname, "T"), len(x))
    if len(x) != a.ncells or len(T) != a.ncells:
        fail(f"expected {a.ncells} cells, got {len(x)} centres and {len(T)} values")

    slope = (a.t_right - a.t_left) / (a.x_right - a.x_left)
    worst, worst_x = -1.0, None
    for xi, ti in zip(x, T):
        if not (a.x_left < xi < a.x_right):
            fail(f"cell centre x={xi} outside ({a.x_left}, {a.x_right})")
        dev = abs(ti - (a.t_left + slope * (xi - a.x_left)))
        if not math.isfinite(dev):
            fail(f"non-finite T at x={xi}")
        if dev > worst:
            worst, worst_x = dev, xi

    mode = f"{a.np} MPI ranks" if a.np > 1 else "serial"
    print(f"time {tname} ({mode}): {len(x)} cells, max |T - T_exact| = {worst:.3e} at x = {worst_x:.4f}"
          f" (tolerance {a.tol:g}); steady state reached: {steady}")

    if a.expect_deviation:
        if worst <= a.tol:
            fail(f"negative test: an unconverged run (endTime {a.end_time}) passed the profile check;"
                 f" the check cannot detect a wrong profile")
        print("PASS: profile check rejects the unconverged field, as it must")
        return
    if worst > a.tol:
        fail(f"profile is not the analytic linear one: max deviation {worst:.3e} > {a.tol:g}")
    print("PASS")


if __name__ == "__main__":
    main()
