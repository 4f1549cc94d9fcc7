"""gate.sh's table: per gate run WORK/<name>/P, the granular front (cluster) at TIMES, the final
runout and the time and reason the run stopped (postProcessing/dem/timeSeries.csv, summary.json).
Usage: gate_table.py WORK OUT.csv NAME..."""
import csv
import json
import os
import sys

from mixflow.observables import Scene

TIMES = (0.25, 0.5, 0.75, 1.0, 1.5, 2.0)


def main(work, out, *names):
    rows = []
    for name in names:
        s = Scene(os.path.join(work, name), "P")
        if not s.done:
            sys.exit(f"{work}/{name}/P has not finished")
        with open(os.path.join(s.dir, "postProcessing", "dem", "summary.json")) as f:
            summary = json.load(f)
        row = {"gate": name}
        for t in TIMES:
            r = min(s.dem, key=lambda r: abs(r["time_s"] - t))
            row[f"front_{t:g}s_m"] = round(r["front_x_m"], 4) if r["time_s"] > t - 0.01 else ""
        row["runout_final_m"] = round(summary["runout_final_m"], 4)
        row["stop_s"] = round(summary["end_time_s"], 3)
        row["stop_reason"] = summary["stop_reason"]
        rows.append(row)
    with open(out, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    print(out, len(rows), "rows")


if __name__ == "__main__":
    main(*sys.argv[1:])
