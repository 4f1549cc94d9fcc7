"""Fit (l_inf - L)/L = lambda * a**alpha to finished dry-column scenes (Li & Zhao 2018 Eq. 12).

usage: mixflow runout-fit WORKDIR OUTDIR COMMAND
Reads WORKDIR/P-I-*/postProcessing/dem/{summary.json,depositProfile.csv}, writes OUTDIR/runout.csv,
summary.json, runout.png. The aspect ratio is the settled one (settled height / L), which is what the
collapse actually starts from. Two runout rules are fitted (docs/parameters.md, frontGapDiameters):
  cluster:   front of the largest connected cluster (a sparse one-grain tail counts);
  thickness: end of the deposit at least one grain thick (the first x > L where the width-averaged
             column top falls below d); computed here from depositProfile.csv, as mixflowDem does.
"""
import argparse
import csv
import glob
import json
import os
import shutil
import sys

from mixflow.outputs import read_rows
from mixflow.paper import D_P
from mixflow.runout import fit_power_law, power_law_slope_error, thickness_front


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("work", metavar="WORKDIR", help="the suite's work directory of the P-I-* scenes")
    p.add_argument("out", metavar="OUTDIR", help="where runout.csv, summary.json, runout.png go")
    p.add_argument("command", metavar="COMMAND", help="the command recorded in summary.json")
    a = p.parse_args(argv)
    work, out, command = a.work, a.out, a.command
    rows = []
    for path in sorted(glob.glob(os.path.join(work, "P-I-*", "postProcessing", "dem", "summary.json"))):
        s = json.load(open(path))
        L = s["sample"]["length_m"]
        a = s["settled"]["height_m"] / L
        thick = thickness_front(read_rows(os.path.join(os.path.dirname(path), "depositProfile.csv")),
                                L, D_P)
        rows.append({"case": s["case"], "H_m": s["sample"]["height_m"], "settled_height_m": s["settled"]["height_m"],
                     "a": a, "runout_m": s["runout_m"], "normalised_runout": s["runout_m"] / L,
                     "runout_thickness_m": thick - L, "normalised_runout_thickness": (thick - L) / L,
                     "end_time_s": s["end_time_s"], "stop_reason": s["stop_reason"],
                     "particles": s["settled"]["particles"], "young_modulus_pa": s["young_modulus_pa"],
                     "time_step_s": s["time_step_s"]})
    if len(rows) < 2:
        sys.exit("mixflow runout-fit: need at least two finished scenes in " + work)
    os.makedirs(out, exist_ok=True)
    # Keep each scene's own outputs beside the fit (small CSV/JSON files).
    for path in sorted(glob.glob(os.path.join(work, "P-I-*", "postProcessing", "dem", "summary.json"))):
        src = os.path.dirname(path)
        dst = os.path.join(out, "scenes", os.path.basename(os.path.dirname(os.path.dirname(src))))
        os.makedirs(dst, exist_ok=True)
        for name in ("summary.json", "timeSeries.csv", "depositProfile.csv", "velocityProfile.csv"):
            if os.path.exists(os.path.join(src, name)):
                shutil.copy(os.path.join(src, name), dst)
    with open(os.path.join(out, "runout.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    a_list = [r["a"] for r in rows]
    alpha, lam = fit_power_law(a_list, [r["normalised_runout"] for r in rows])
    alpha_t, lam_t = fit_power_law(a_list, [r["normalised_runout_thickness"] for r in rows])
    summary = {"alpha": alpha, "lambda": lam,
               "alpha_standard_error": power_law_slope_error(
                   a_list, [r["normalised_runout"] for r in rows]), "front_rule": "cluster (largest connected cluster, gap 0.5 d)",
               "alpha_thickness_front": alpha_t, "lambda_thickness_front": lam_t,
               "paper_alpha": 0.9884, "experiment_alpha_wide": [0.8, 1.0], "lube2005_lambda": 1.2,
               "young_modulus_pa": rows[0]["young_modulus_pa"], "time_step_s": rows[0]["time_step_s"],
               "particles": [r["particles"] for r in rows], "scenes": [r["case"] for r in rows],
               "command": command}
    json.dump(summary, open(os.path.join(out, "summary.json"), "w"), indent=2)
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        a = [r["a"] for r in rows]
        fig, ax = plt.subplots(figsize=(5, 4))
        grid = [min(a) * 0.95 + i * (max(a) * 1.05 - min(a) * 0.95) / 50 for i in range(51)]
        ax.loglog(a, [r["normalised_runout"] for r in rows], "o", label="cluster front")
        ax.loglog(grid, [lam * g ** alpha for g in grid], "-", label=f"fit λ={lam:.3f}, α={alpha:.3f}")
        ax.loglog(a, [r["normalised_runout_thickness"] for r in rows], "s", label="one-grain-thick front")
        ax.loglog(grid, [lam_t * g ** alpha_t for g in grid], "-", label=f"fit λ={lam_t:.3f}, α={alpha_t:.3f}")
        ax.loglog(grid, [1.2 * g for g in grid], "--", label="Lube et al. 2005: 1.2 a")
        ax.set_xlabel("aspect ratio a = H/L (settled)")
        ax.set_ylabel("(l∞ − L)/L")
        ax.legend()
        fig.tight_layout()
        fig.savefig(os.path.join(out, "runout.png"), dpi=120)
    except ImportError:
        pass
    print(json.dumps(summary, indent=2))


if __name__ == "__main__":
    main()
