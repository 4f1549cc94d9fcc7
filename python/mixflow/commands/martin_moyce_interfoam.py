"""Martin & Moyce (1952) column collapse (n^2 = 1): mixflowFoam vs Debian's interFoam vs experiment.

    mixflow martin-moyce-interfoam [--work /tmp/mm_interfoam] [--cells 40]

Question: is the lead of the simulated front over the experiment (dZ/dT on 1 <= T <= 3: 1.64 vs
1.41) ours or the VOF model's? Answer at a/40: interFoam's time series is byte-identical to ours.
Both solvers run the very same case, written by mixflowPrepare from the scene of
tests/cfd/run_liquid_cases.py::martin_moyce (a = 0.05715 m, a/40 cells, water/air, sigma 0.07,
t <= 0.26 s); every generated dictionary (schemes, fvSolution, maxCo/maxAlphaCo, PIMPLE, 0/,
constant/) is shared, the only added entry for interFoam is `libs (...)`. The front and residual
height come from the same code for both: cfd/functionObjects/liquidObservables.cpp, compiled into
mixflowFoam and, here, into a shared library (with the build's own compile flags) that interFoam
loads; so the rule (bed row, alpha >= 0.5, interpolated between cell centres) is identical.
T = t sqrt(g/a) as in the test and the reference file (MM's T = n t sqrt(g/a), n = 1).

Output: results/pure_liquids/martin_moyce_interfoam.csv, one row per reference time (front T and
height tau share the scale): T, Z_exp, Z_mixflow, Z_interFoam, eta_exp, eta_mixflow,
eta_interFoam (blank where there is no datum). Prints max |Z_mixflow - Z_interFoam| (per step),
both against the experiment and the slopes dZ/dT fitted on 1 <= T <= 3. Runs serially.
"""

import argparse
import csv
import filecmp
import json
import math
import os
import shlex
import subprocess
import time

import numpy as np

from mixflow import liquidcase as rlc
from mixflow import ROOT, outputs
from mixflow.paper import G

SIDE = rlc.MM_SIDE


def build_observables_lib(build, out):
    """liquidObservables.cpp as a shared library, with the flags mixflowFoam was compiled with."""
    with open(os.path.join(build, "compile_commands.json")) as f:
        entry = next(e for e in json.load(f) if e["file"].endswith("liquidObservables.cpp")
                     and "mixflowFoam.dir" in e["command"])
    tok, flags, skip = shlex.split(entry["command"]), [], False
    for t in tok[1:]:  # drop "-o object" and "-c source"
        if not skip and t not in ("-o", "-c"):
            flags.append(t)
        skip = t in ("-o", "-c")
    subprocess.check_call([tok[0], *flags, "-shared", "-o", out, entry["file"],
                           "-lfiniteVolume", "-lmeshTools", "-lOpenFOAM"])


def run(a, name, solver, lib=None):
    """The test's case on a/CELLS through run_case (prepare, blockMesh, SOLVER, the front rule's
    check), with LIB loaded by SOLVER if given: (case, time series, wall time)."""
    case = os.path.join(a.work, name)
    rlc.write_martin_moyce_case(case, a.cells)
    if lib:  # controlDict's own entries follow the generated include and win
        with open(os.path.join(case, "system/controlDict"), "a") as f:
            f.write(f'libs ("{lib}");\n')
    t0 = time.time()
    series = rlc.run_case(argparse.Namespace(prepare=a.prepare, blockmesh=a.blockmesh,
                                             solver=solver), case)
    return case, series, time.time() - t0


def differing_inputs(c1, c2):
    """Input files (0/, constant/, system/) that differ between the two cases."""
    out = []
    for d in ("0", "constant", "constant/polyMesh", "system"):
        cmp = filecmp.dircmp(os.path.join(c1, d), os.path.join(c2, d))
        out += [f"{d}/{n}" for n in cmp.diff_files + cmp.left_only + cmp.right_only]
    return out


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--work", default="/tmp/mm_interfoam")
    p.add_argument("--cells", type=int, default=40, help="cells per column side (test: 40)")
    p.add_argument("--build", default=os.path.join(ROOT, "build"))
    rlc.add_program_arguments(p, ROOT)
    p.add_argument("--interfoam", default="/usr/bin/interFoam")
    p.add_argument("--reference", default=os.path.join(
        ROOT, "tests", "reference", "martin_moyce_1952_n2eq1_front_height.csv"))
    p.add_argument("--out", default=os.path.join(ROOT, "results/pure_liquids/"
                                                        "martin_moyce_interfoam.csv"))
    a = p.parse_args()
    a.work = os.path.abspath(a.work)
    os.makedirs(a.work, exist_ok=True)

    lib = os.path.join(a.work, "libliquidObservables.so")
    build_observables_lib(a.build, lib)
    mix_case, mix, t_mix = run(a, "mixflowFoam", a.solver)
    if_case, itf, t_if = run(a, "interFoam", a.interfoam, lib)

    ts = math.sqrt(SIDE / G)
    t_end = min(mix[-1]["time_s"], itf[-1]["time_s"]) / ts
    ref = {q: dict(pts) for q, pts in rlc.read_martin_moyce(a.reference).items()}

    def sim(series, key, T):
        return rlc.interp(series, key, T * ts) / SIDE

    rows = []
    for T in sorted(set(ref["front_Z"]) | set(ref["height_eta"])):
        if T > t_end:
            continue
        rows.append([T, ref["front_Z"].get(T), sim(mix, "front_bed_m", T),
                     sim(itf, "front_bed_m", T), ref["height_eta"].get(T),
                     sim(mix, "back_wall_depth_m", T), sim(itf, "back_wall_depth_m", T)])
    os.makedirs(os.path.dirname(a.out), exist_ok=True)
    with open(a.out, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["T", "Z_exp", "Z_mixflow", "Z_interFoam", "eta_exp", "eta_mixflow",
                    "eta_interFoam"])
        w.writerows([["" if v is None else f"{v:.5g}" for v in r] for r in rows])

    print(f"\nmesh a/{a.cells}; wall time mixflowFoam {t_mix:.1f} s ({len(mix) - 1} steps), "
          f"interFoam {t_if:.1f} s ({len(itf) - 1} steps)")
    print(f"inputs differing between the cases: {differing_inputs(mix_case, if_case)} "
          "(system/controlDict: the libs entry)")
    same = filecmp.cmp(*(os.path.join(c, outputs.LIQUID_SERIES)
                         for c in (mix_case, if_case)), shallow=False)
    print(f"timeSeries.csv byte-identical: {same}")
    # Per step where the step times coincide (they do when the runs agree), else on a 0.01 grid.
    if [r["time_s"] for r in mix] == [r["time_s"] for r in itf]:
        pairs = list(zip(mix, itf))
        dz = max(abs(m["front_bed_m"] - i["front_bed_m"]) for m, i in pairs) / SIDE
        de = max(abs(m["back_wall_depth_m"] - i["back_wall_depth_m"]) for m, i in pairs) / SIDE
    else:
        grid = np.arange(0, t_end, 0.01)
        dz = max(abs(sim(mix, "front_bed_m", T) - sim(itf, "front_bed_m", T)) for T in grid)
        de = max(abs(sim(mix, "back_wall_depth_m", T) - sim(itf, "back_wall_depth_m", T))
                 for T in grid)
    print(f"max |Z_mixflow - Z_interFoam| = {dz:.3e}, max |eta_mixflow - eta_interFoam| = "
          f"{de:.3e} (0 <= T <= {t_end:.2f})")
    # Against the experiment over the test's ranges (front T <= 3, eta tau <= 3.08).
    for name, k in (("mixflowFoam", 2), ("interFoam", 3)):
        fz = [(abs(r[k] - r[1]), r[0]) for r in rows if r[1] is not None and r[0] <= 3.0]
        fe = [(abs(r[k + 3] - r[4]), r[0]) for r in rows if r[4] is not None and r[0] <= 3.08]
        print(f"{name:12s} vs experiment: max |dZ| = {max(fz)[0]:.3f} (T = {max(fz)[1]}), "
              f"max |d eta| = {max(fe)[0]:.3f} (tau = {max(fe)[1]})")

    def slope(series):
        pts = [(r["time_s"] / ts, r["front_bed_m"] / SIDE) for r in series
               if 1.0 <= r["time_s"] / ts <= 3.0]
        return np.polyfit(*zip(*pts), 1)[0]

    exp = [(T, z) for T, z in ref["front_Z"].items() if 1.0 <= T <= 3.0]
    print(f"dZ/dT on 1 <= T <= 3: experiment {np.polyfit(*zip(*exp), 1)[0]:.3f} "
          f"({len(exp)} points), mixflowFoam {slope(mix):.3f}, interFoam {slope(itf):.3f}")
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
