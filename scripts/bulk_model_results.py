#!/usr/bin/env python3
"""results/bulk_model/: the bulk model's runs of W&P, HB&P and B&P against the CFD-DEM reference.

Usage: python3 scripts/bulk_model_results.py [--work runs/bulk] [--out results/bulk_model]
after `python3 scripts/suite.py --tier bulk --scenes W+P,HB+P,B+P --work runs/bulk`.

Reads each run's postProcessing/liquid/timeSeries.csv (the mixture is the non-air phase, so its
front is the bulk front) and .done (wall time), and the CFD-DEM reference-tier numbers committed in
results/mixtures/summary.json (granular front at the end) and
results/mixtures/pressure_coupling/drag_viscosity_max_reference/tier_trade.json (the wall time of
the reference-tier HB&P run on this machine kind). Writes summary.json and fronts.csv.
"""

import argparse
import csv
import json
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "python"))
from mixflow.outputs import nearest as at  # noqa: E402
from mixflow.outputs import series  # noqa: E402  (series(case): the liquid time series)
SCENES = {"W&P": "W+P", "HB&P": "HB+P", "B&P": "B+P"}
L = 0.9  # sample length (m): fronts are reported as positions x from the back wall
TIMES = (0.5, 1.0, 1.5, 2.0, 3.0)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--work", default="runs/bulk")
    p.add_argument("--out", default="results/bulk_model")
    a = p.parse_args()
    ref = json.load(open(os.path.join(ROOT, "results/mixtures/summary.json")))["scenes"]
    cost = json.load(open(os.path.join(
        ROOT, "results/mixtures/pressure_coupling/drag_viscosity_max_reference/tier_trade.json")))
    ref_wall = cost["tiers"]["default"]["wall_s"]
    ref_sim = cost["tiers"]["default"]["simulated_s"]
    out = {"command": "python3 scripts/suite.py --tier bulk --scenes W+P,HB+P,B+P --work "
                      f"{a.work} && python3 scripts/bulk_model_results.py --work {a.work} --out {a.out}",
           "stage": "A: lambda = 1, constant alpha_s, default solid rheology (uncalibrated)",
           "reference": "CFD-DEM reference tier, results/mixtures/summary.json",
           "front_error": {}, "front_m": {}, "speedup": {}, "wall_s": {}}
    rows = []
    for name, case_name in SCENES.items():
        case = os.path.join(a.work, case_name)
        s = series(case)
        done = json.load(open(os.path.join(case, ".done")))
        end = s[-1]["time_s"]
        front = s[-1]["front_bed_m"]
        cfd_dem = ref[name]["granular_front_end_m"]
        out["front_m"][name] = {"bulk": front, "cfd_dem": cfd_dem, "time_s": end}
        out["front_error"][name] = (front - cfd_dem) / cfd_dem
        out["wall_s"][name] = done["wall_s"]
        # Wall seconds per simulated second, against the reference-tier CFD-DEM HB&P run's.
        out["speedup"][name] = (ref_wall / ref_sim) / (done["wall_s"] / done["simulated_s"])
        for t in TIMES:
            rows.append({"scene": name, "time_s": t, "bulk_front_m": at(s, "front_bed_m", t),
                         "bulk_back_wall_depth_m": at(s, "back_wall_depth_m", t)})
    out["speedup_baseline"] = (f"reference-tier CFD-DEM HB&P, {ref_wall} s wall for {ref_sim:.3f} s "
                               "simulated (committed, not measured in the same run)")
    os.makedirs(a.out, exist_ok=True)
    with open(os.path.join(a.out, "summary.json"), "w") as f:
        json.dump(out, f, indent=2)
        f.write("\n")
    with open(os.path.join(a.out, "fronts.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    for name in SCENES:
        fm = out["front_m"][name]
        print(f"{name:5s} front {fm['bulk']:.3f} m (CFD-DEM {fm['cfd_dem']:.3f} m, "
              f"{100 * out['front_error'][name]:+.0f} %), wall {out['wall_s'][name]:.0f} s, "
              f"speedup {out['speedup'][name]:.1f}")


if __name__ == "__main__":
    main()
