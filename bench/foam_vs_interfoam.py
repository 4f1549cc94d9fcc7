#!/usr/bin/env python3
"""Benchmark: mixflowFoam in pure-liquid mode (voidfraction 1, no particle source) against Debian's
/usr/bin/interFoam on the same damBreak mesh (OpenFOAM's laminar tutorial, 2268 cells, taken from the
OpenFOAM source tree that scripts/install-deps.sh extracts). Prints cell-steps per CPU second for
each and their ratio. Target: mixflowFoam within 10 % of interFoam.

CPU time (user + sys of the solver process) is measured rather than wall time: on a shared machine
wall time also counts waiting for a core. Both runs take the same time steps (the tests assert
bit-identical fields), so the ratio is the solver's own overhead.

usage: foam_vs_interfoam.py [--end-time T] [--repeat K] [--json OUT] [--bin build/bin]"""
import argparse
import json
import os
import re
import resource
import shutil
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
from mixflow import foamcase as fc  # noqa: E402  (shared case helpers of the CFD tests)

TUTORIAL = "tutorials/multiphase/interFoam/laminar/damBreak/damBreak"


def run_timed(solver, case):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    fc.run([solver], case, "log." + os.path.basename(solver))
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    log = open(os.path.join(case, "log." + os.path.basename(solver))).read()
    steps = len(re.findall(r"^Time = ", log, re.M))
    return wall, cpu, steps


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--end-time", default="0.5")
    ap.add_argument("--repeat", type=int, default=2)
    ap.add_argument("--json")
    ap.add_argument("--bin", default=os.path.join(ROOT, "build", "bin"))
    ap.add_argument("--foam-src", default=os.environ.get("MIXFLOW_OPENFOAM_SRC", "/opt/mixflow-deps/openfoam-src"))
    a = ap.parse_args()
    os.environ.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")
    solvers = {"interFoam": shutil.which("interFoam") or "/usr/bin/interFoam",
               "mixflowFoam": os.path.join(a.bin, "mixflowFoam")}
    work = tempfile.mkdtemp(prefix="mixflow-foambench-")
    results = {}
    for name, exe in solvers.items():
        runs = []
        for k in range(a.repeat):
            case = os.path.join(work, f"{name}{k}")
            fc.prepare_dam_break(os.path.join(a.foam_src, TUTORIAL), case, a.end_time, "setFields", "blockMesh")
            runs.append(run_timed(exe, case))
        results[name] = runs
    cells = 2268
    out = {"case": "damBreak (laminar tutorial), endTime " + a.end_time, "cells": cells}
    for name, runs in results.items():
        cpu = min(r[1] for r in runs)
        steps = runs[0][2]
        out[name] = {"steps": steps, "cpu_s": [r[1] for r in runs], "wall_s": [r[0] for r in runs],
                     "cell_steps_per_cpu_s": cells * steps / cpu}
        print(f"  {name:12s} steps {steps:5d}  cpu {cpu:7.2f} s  {cells * steps / cpu:.3e} cell-steps per cpu-s")
    ratio = (out["mixflowFoam"]["cell_steps_per_cpu_s"] / out["interFoam"]["cell_steps_per_cpu_s"])
    out["throughput_ratio_mixflowFoam_over_interFoam"] = ratio
    out["target_ratio_min"] = 0.9
    out["command"] = "bench/foam_vs_interfoam.py " + " ".join(sys.argv[1:])
    print(f"  throughput ratio mixflowFoam / interFoam = {ratio:.3f} (target >= 0.90)")
    if a.json:
        os.makedirs(os.path.dirname(os.path.abspath(a.json)), exist_ok=True)
        json.dump(out, open(a.json, "w"), indent=2)
    shutil.rmtree(work)


if __name__ == "__main__":
    main()
