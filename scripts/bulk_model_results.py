#!/usr/bin/python3
"""results/bulk_model/: the bulk model of W&P, HB&P, B&P and the dry P against the CFD-DEM reference.

usage: /usr/bin/python3 scripts/bulk_model_results.py [--work runs/bulk] [--reference runs/reference]
                                                      [--out results/bulk_model]
after `python3 scripts/suite.py --tier bulk --scenes W+P,HB+P,B+P --work runs/bulk` and
`python3 scripts/suite.py --tier reference --scenes W+P,HB+P,B+P,P --work runs/reference`.

Reads, per mixture, the tier bulk run (WORK/<scene>: postProcessing/liquid/timeSeries.csv, the
mixture's front) and the CFD-DEM run (REFERENCE/<scene>: the granular front of
postProcessing/dem/timeSeries.csv), and the committed
results: OUT/stages.json (scripts/bulk_stages.py: the front error per calibration stage at 0.075 m),
OUT/solid_calibration.json (scripts/calibrate_solid.py: the dry P against its DEM run) and
results/bench/bulk_vs_cfddem*.json (bench/bulk_vs_cfddem.py: solver CPU, bulk against CFD-DEM,
measured in one run). Writes OUT/summary.json, OUT/fronts.csv (fronts at 0.5, 1, 1.5, 2, 3 s) and
OUT/fronts.png (front against time, bulk and CFD-DEM, per scene). The Froude number and the
back-wall height beside CFD-DEM's are in the reproduction report (scripts/report.py --bulk-work).
"""

import argparse
import glob
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "python"))
from mixflow import outputs  # noqa: E402

SCENES = {"W+P": "W&P", "HB+P": "HB&P", "B+P": "B&P"}
TIMES = (0.5, 1.0, 1.5, 2.0, 3.0)


def load(path):
    with open(path) as f:
        return json.load(f)


def dem_front(dem, t):
    """The CFD-DEM granular front at T; its last write when T is past it (a run ends a DEM step
    short of endTime)."""
    return outputs.interpolated(dem, outputs.GRANULAR_FRONT, min(t, dem[-1][outputs.TIME]))


def mixture(scene, work, reference):
    bulk = outputs.series(os.path.join(work, scene))
    dem = outputs.series(os.path.join(reference, scene), "dem")
    end = bulk[-1][outputs.TIME]
    ref_front = dem_front(dem, end)
    front = bulk[-1][outputs.LIQUID_FRONT]
    return {
        "time_s": end, "bulk_front_m": front, "cfd_dem_front_m": ref_front,
        "front_error": front / ref_front - 1,
        "fronts": [{"time_s": t,
                    "bulk_front_m": outputs.interpolated(bulk, outputs.LIQUID_FRONT, t),
                    "cfd_dem_front_m": dem_front(dem, t)}
                   for t in TIMES if t <= end],
    }, (bulk, dem)


def speedups():
    """Per scene, the same-run bench rows: {cell size label: ratio, front error}."""
    out = {}
    for path in sorted(glob.glob(os.path.join(ROOT, "results", "bench", "bulk_vs_cfddem*.json"))):
        d = load(path)
        for scene, rec in d["scenes"].items():
            out[SCENES.get(scene, scene)] = {
                "file": os.path.relpath(path, ROOT), "command": d["command"],
                "cfd_dem_solver": rec["cfddem"]["solver"],
                "cfd_dem_solver_cpu_s": rec["cfddem"]["solver_cpu_s"],
                "bulk": {b["label"]: {"cell_size": (b["set"] or ["tier bulk (0.02 m)"])[0],
                                      "solver_cpu_s": b["solver_cpu_s"],
                                      "ratio_solver_cpu": b["ratio_solver_cpu"],
                                      "ratio_with_settling": b["ratio_with_settling"],
                                      "front_error": b["front_error"]} for b in rec["bulk"]}}
    return out


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--work", default="runs/bulk")
    p.add_argument("--reference", default="runs/reference")
    p.add_argument("--out", default=os.path.join(ROOT, "results", "bulk_model"))
    a = p.parse_args()
    stages = load(os.path.join(a.out, "stages.json"))
    solid = load(os.path.join(a.out, "solid_calibration.json"))
    out = {"command": "/usr/bin/python3 scripts/bulk_model_results.py " + " ".join(sys.argv[1:]),
           "stage": "A: lambda = 1, alpha_s constant, the solid rheology calibrated on the dry P "
                    "(the bulk model's defaults)",
           "reference": f"CFD-DEM tier reference ({a.reference})",
           "front_error": {}, "front_error_by_stage": {}, "scenes": {}}
    rows, curves = [], {}
    for scene, name in SCENES.items():
        rec, curves[name] = mixture(scene, a.work, a.reference)
        out["scenes"][name] = rec
        out["front_error"][name] = rec["front_error"]
        st = stages["scenes"].get(scene, {})
        out["front_error_by_stage"][name] = {
            k: st[k].get("front_error") for k in ("A0", "A", "B") if k in st}
        rows += [{"scene": name, **r} for r in rec["fronts"]]
    best = solid["best"]
    p_times = solid["times_s"]
    p_best = next(g for g in solid["grid"] if g["tan_phi"] == best["tan_phi"]
                  and g["viscosity_m2_s"] == best["viscosity_m2_s"])
    out["front_error"]["P"] = best["final_error"]
    out["front_error_by_stage"]["P"] = {"A": best["final_error"], "A_rms": best["rms_error"]}
    out["scenes"]["P"] = {"source": "solid_calibration.json (P-bulk at 0.075 m, tanPhi "
                                    f"{best['tan_phi']}, nu_s {best['viscosity_m2_s']})",
                          "fronts": [{"time_s": t, "bulk_front_m": b, "cfd_dem_front_m": r}
                                     for t, b, r in zip(p_times, p_best["fronts_m"],
                                                        solid["reference_front_m"])]}
    out["speedup"] = speedups()
    out["speedup_baseline"] = ("the CFD-DEM solver's CPU time (mixflowCoupled; for P mixflowDem's "
                               "collapse) measured in the same bench run as the bulk model's")
    outputs.write_json(os.path.join(a.out, "summary.json"), out)
    outputs.write_csv(os.path.join(a.out, "fronts.csv"), rows)

    fig, axes = plt.subplots(1, 4, figsize=(16, 3.6), sharey=True)
    for ax, name in zip(axes, ["P"] + list(SCENES.values())):
        if name == "P":
            ax.plot(p_times, solid["reference_front_m"], "k-", label="DEM")
            ax.plot(p_times, p_best["fronts_m"], "C0--", label="bulk (0.075 m)")
        else:
            bulk, dem = curves[name]
            ax.plot([r[outputs.TIME] for r in dem], [r[outputs.GRANULAR_FRONT] for r in dem], "k-",
                    label="CFD-DEM granular")
            ax.plot([r[outputs.TIME] for r in bulk], [r[outputs.LIQUID_FRONT] for r in bulk],
                    "C0--", label="bulk, stage A (0.02 m)")
        ax.set_title(name)
        ax.set_xlabel("t (s)")
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("front x (m)")
    axes[0].legend(loc="lower right")
    axes[1].legend(loc="lower right")
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "fronts.png"), dpi=110)
    for name, rec in out["scenes"].items():
        if name != "P":
            print(f"{name:5s} bulk front {rec['bulk_front_m']:.3f} m, CFD-DEM "
                  f"{rec['cfd_dem_front_m']:.3f} m ({100 * rec['front_error']:+.1f} %)")
    print(f"P     bulk front error at 3 s {100 * best['final_error']:+.1f} % "
          f"(rms {100 * best['rms_error']:.1f} %)")


if __name__ == "__main__":
    main()
