"""The gate studies' table (results/runout_scaling/gate.sh, results/mixtures/gate.sh): per gate
run WORK/<name>/<SCENE>, the fronts, released energy and back-wall height at TIMES
(mixflow.commands.tier_trade.observables, the ladders' observables), the stop time and reason.
Usage: gate_table.py WORK OUT.csv SCENE NAME..."""
import csv
import json
import os
import sys

from mixflow.commands.tier_trade import observables
from mixflow.observables import Scene

TIMES = (0.25, 0.5, 1.0, 1.5, 2.0, 3.0)
KEYS = ("granular_front_m", "liquid_front_m", "liquid_depth_front_m",
        "particle_pe_released_J_per_m", "back_wall_height_over_H")


def main(work, out, scene, *names):
    rows = []
    for name in names:
        s = Scene(os.path.join(work, name), scene)
        if not s.done:
            sys.exit(f"{work}/{name}/{scene} has not finished")
        obs = observables(s, TIMES)
        with open(os.path.join(s.dir, "postProcessing", "dem", "summary.json")) as f:
            summary = json.load(f)
        for t in TIMES:
            o = obs.get(f"{t:g}s")
            if o:
                rows.append({"gate": name, "time_s": t,
                             **{k: round(o[k], 4) if isinstance(o.get(k), float) else ""
                                for k in KEYS}})
        rows.append({"gate": name, "time_s": "end",
                     "granular_front_m": round(summary["front_x_m"], 4),
                     **{k: "" for k in KEYS[1:]}})
    with open(out, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=["gate", "time_s", *KEYS])
        w.writeheader()
        w.writerows(rows)
    print(out, len(rows), "rows")


if __name__ == "__main__":
    main(*sys.argv[1:])
