#!/usr/bin/env python3
"""The bulk model's speed against CFD-DEM on the same scene, both measured in this run.

usage: bench/bulk_vs_cfddem.py [--scenes HB+P,P] [--work /tmp/mixflow-bench-bulk]
                               [--bulk-cell-sizes tier,0.075] [--json results/bench/bulk_vs_cfddem.json]

For each scene: the CFD-DEM run at the tier `reference` (settling, then mixflowCoupled; for the dry
scene P the DEM alone, mixflowDem), then the bulk model (mixflowBulkFoam; P as its bulk twin
cases/P-bulk) at the tier `bulk`, once per --bulk-cell-sizes entry (`tier`: the
tier's own cell size; a number: `--set cfdDict.cellSize=` it), each through mixflow suite into
WORK/<label>, one after the other. Measured per run: the solver's CPU time (its log's last
ExecutionTime; mixflowDem: its collapse phase's CPU), the settling's wall time (CFD-DEM only), the suite's wall time, the simulated end
time and the granular front at the end. Ratios: CFD-DEM solver CPU / bulk solver CPU, and the
same with the settling added to the CFD-DEM side (what a user waits for). Target (issue of the bulk
model): 100. The runs are kept in WORK (delete it to rerun from scratch; a finished run is not
run again by the suite, so delete WORK before timing again).
"""

import argparse
import csv
import json
import os
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
from mixflow import foamcase, outputs  # noqa: E402
from mixflow.cli import command  # noqa: E402


def settle_wall(log):
    """The settling's wall time (s) from mixflowDem's last '[settle] ... wall hh:mm:ss' line."""
    m = foamcase.last_match(log, r"\[settle\].*wall (\d+):(\d+):(\d+)")
    if not m:
        return None
    h, mi, s = (int(g) for g in m.groups())
    return 3600 * h + 60 * mi + s


BULK_TWIN = {"P": "P-bulk"}  # a dry scene's bulk model is its own case (air as the pore fluid)


def collapse_cpu(log):
    """mixflowDem's collapse-phase CPU time (s): its '[mixflowDem] collapse phase: ... CPU X s'."""
    m = foamcase.last_match(log, r"\[mixflowDem\] collapse phase: .*CPU ([0-9.eE+-]+) s")
    return float(m.group(1)) if m else None


def end_state(case):
    """(simulated end time, granular front x) at the last output row: CFD-DEM's grains
    (postProcessing/dem/timeSeries.csv front_x_m), the bulk model's mixture on the bed
    (postProcessing/liquid/timeSeries.csv front_bed_m)."""
    dem = os.path.join(case, outputs.DEM_SERIES)
    path, key = (dem, "front_x_m") if os.path.isfile(dem) else \
        (os.path.join(case, outputs.LIQUID_SERIES), "front_bed_m")
    with open(path) as f:
        rows = list(csv.DictReader(ln for ln in f if ln.strip() and not ln.startswith("#")))
    return float(rows[-1]["time_s"]), float(rows[-1][key])


def run(label, scene, tier, work, sets):
    cmd = command("suite") + ["--tier", tier, "--scenes",
           scene, "--work", os.path.join(work, label)]
    for s in sets:
        cmd += ["--set", s]
    print("+ " + " ".join(cmd), flush=True)
    # The bench measures: a run the suite finds finished would not be timed.
    if os.path.exists(os.path.join(work, label, scene, ".done")):
        sys.exit(f"bench: {os.path.join(work, label)} holds a finished run; delete {work} first")
    t0 = time.time()
    subprocess.run(cmd, check=True)
    wall = time.time() - t0
    case = os.path.join(work, label, scene)
    solver = next(s for s in ("mixflowCoupled", "mixflowBulkFoam", "mixflowDem")
                  if os.path.isfile(os.path.join(case, f"log.{s}")))
    dem_log = os.path.join(case, "log.mixflowDem")
    rec = {"label": label, "scene": scene, "tier": tier, "set": sets, "solver": solver,
           "suite_wall_s": wall,
           "solver_cpu_s": collapse_cpu(dem_log) if solver == "mixflowDem" else
           foamcase.execution_time(os.path.join(case, f"log.{solver}"))}
    rec["settle_wall_s"] = settle_wall(dem_log) if os.path.isfile(dem_log) else None
    rec["simulated_s"], rec["granular_front_m"] = end_state(case)
    print(json.dumps(rec), flush=True)
    return rec


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scenes", default="HB+P")
    ap.add_argument("--work", default="/tmp/mixflow-bench-bulk")
    ap.add_argument("--bulk-cell-sizes", default="tier,0.075")
    ap.add_argument("--json")
    a = ap.parse_args()
    out = {"command": "mixflow bench bulk_vs_cfddem " + " ".join(sys.argv[1:]), "scenes": {}}
    for scene in a.scenes.split(","):
        ref = run(f"{scene}-cfddem", scene, "reference", a.work, [])
        bulks = []
        for size in a.bulk_cell_sizes.split(","):
            sets = [] if size == "tier" else [f"cfdDict.cellSize={size}"]
            b = run(f"{scene}-bulk-{size}", BULK_TWIN.get(scene, scene), "bulk", a.work, sets)
            b["ratio_solver_cpu"] = ref["solver_cpu_s"] / b["solver_cpu_s"]
            b["ratio_with_settling"] = (ref["solver_cpu_s"] + (ref["settle_wall_s"] or 0)) / \
                b["solver_cpu_s"]
            if ref["granular_front_m"] and b["granular_front_m"]:
                b["front_error"] = b["granular_front_m"] / ref["granular_front_m"] - 1
            bulks.append(b)
            print(f"{scene} bulk ({size}): solver CPU {b['solver_cpu_s']:.1f} s against CFD-DEM "
                  f"{ref['solver_cpu_s']:.1f} s (+ settling {ref['settle_wall_s']} s): ratio "
                  f"{b['ratio_solver_cpu']:.2f} ({b['ratio_with_settling']:.2f} with settling); "
                  f"front {b['granular_front_m']} m against {ref['granular_front_m']} m", flush=True)
        out["scenes"][scene] = {"cfddem": ref, "bulk": bulks}
    if a.json:
        outputs.write_json(a.json, out)
        print(f"wrote {a.json}")


if __name__ == "__main__":
    main()
