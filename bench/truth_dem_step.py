#!/usr/bin/env python3
"""The truth tier's cost at two DEM steps: a mixture (default W+P) at the tier's 0.1 T_R with its
exchange every 27 DEM steps against 0.2 T_R with every 13 (the same exchange interval in time
within 4 %; results/convergence/dem_step.sh measures the answers), both from the shipped sample,
to END s. The arms alternate, REPEAT runs each, so both see the same machine; the figure is the
solver's CPU (its ExecutionTime, the collapse alone: the copy, mesh and start-up are the same
for both), with the median of each arm and their ratio, and where the solver's wall time went
(postProcessing/coupling/stageTimes.csv).

usage: truth_dem_step.py [--scene W+P] [--end 0.03] [--repeat 2] [--work DIR] [--json OUT]"""
import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys

from mixflow import observables as obs

ARMS = {"0.1 T_R, every 27": ["demDict.rayleighFraction=0.1", "couplingProperties.exchangeEvery=27"],
        "0.2 T_R, every 13": ["demDict.rayleighFraction=0.2", "couplingProperties.exchangeEvery=13"]}


def run(scene, end, sets, work):
    shutil.rmtree(work, ignore_errors=True)
    cmd = [sys.executable, "-m", "mixflow", "suite", "--tier", "truth", "--scenes", scene,
           "--work", work, "--set", f"controlDict.endTime={end!r}"]
    for s in sets:
        cmd += ["--set", s]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    s = obs.Scene(work, scene)
    return {"solver_cpu_s": obs.solver_cpu(s), "stage_wall_s": obs.stage_times(s)}


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scene", default="W+P")
    ap.add_argument("--end", type=float, default=0.03)
    ap.add_argument("--repeat", type=int, default=2)
    ap.add_argument("--work", default="runs/bench_truth_dem_step")
    ap.add_argument("--json")
    a = ap.parse_args()
    runs = {arm: [] for arm in ARMS}
    for k in range(a.repeat):
        for n, (arm, sets) in enumerate(ARMS.items()):
            r = run(a.scene, a.end, sets, os.path.join(os.path.abspath(a.work), f"arm{n}_{k}"))
            runs[arm].append(r)
            print(f"{arm} #{k + 1}: solver CPU {r['solver_cpu_s']} s", flush=True)
    med = {arm: statistics.median(r["solver_cpu_s"] for r in rs) for arm, rs in runs.items()}
    base, fast = list(ARMS)
    out = {"scene": a.scene, "end_s": a.end, "arms": {arm: {"sets": ARMS[arm], "runs": runs[arm],
                                                             "median_solver_cpu_s": med[arm]}
                                                       for arm in ARMS},
           "speedup": med[base] / med[fast],
           "command": " ".join(["mixflow bench truth_dem_step"] + sys.argv[1:])}
    print(json.dumps({"median_solver_cpu_s": med, "speedup": out["speedup"]}))
    if a.json:
        with open(a.json, "w") as f:
            json.dump(out, f, indent=1)


if __name__ == "__main__":
    main()
