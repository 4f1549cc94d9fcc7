"""results/bulk_model/: the bulk model of W&P, HB&P, B&P and the dry P against the CFD-DEM reference.

usage: mixflow bulk-model-results [--work runs/bulk] [--reference runs/reference]
                                                      [--out results/bulk_model] [--committed-only]
after `mixflow suite --tier bulk --scenes W+P,HB+P,B+P --work runs/bulk` and
`mixflow suite --tier reference --scenes W+P,HB+P,B+P,P --work runs/reference`.

Reads, per mixture, the tier bulk run (WORK/<scene>: postProcessing/liquid/timeSeries.csv, the
mixture's front) and the CFD-DEM run (REFERENCE/<scene>: the granular front of
postProcessing/dem/timeSeries.csv), and the committed
results: OUT/stages.json (mixflow bulk-stages: the front error per calibration stage at 0.075 m),
OUT/solid_calibration.json (mixflow calibrate-solid: the dry P against its DEM run) and
results/bench/bulk_vs_cfddem*.json (bench/bulk_vs_cfddem.py: solver CPU, bulk against CFD-DEM,
measured in one run). Writes OUT/summary.json, OUT/fronts.csv (fronts at 0.5, 1, 1.5, 2, 3 s) and
OUT/fronts.png (front against time, bulk and CFD-DEM, per scene), OUT/profiles.png (the bulk
mixture's surface against the CFD-DEM liquid's at 0.5, 1 and 3 s, with the CFD-DEM granular
deposit) and OUT/velocity.png (the bulk model's reconstructed u_s and u_f against the CFD-DEM grains'
u(y) at the section and time of the scene's demDict velocityProfile; the bulk cell centres from
OpenFOAM's `postProcess -func writeCellCentres`). The Froude number and the back-wall height
beside CFD-DEM's are in the reproduction report (mixflow report --bulk-work).
"""

import argparse
import glob
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

from mixflow import ROOT, foamcase, outputs

SCENES = {"W+P": "W&P", "HB+P": "HB&P", "B+P": "B&P"}
TIMES = (0.5, 1.0, 1.5, 2.0, 3.0)
PROFILE_TIMES = (0.5, 1.0, 3.0)


def profile(case, t):
    """(x, surface) of the liquid profiles.csv row set nearest to T."""
    sel = outputs.profile_at(case, t)
    return [r[outputs.PROFILE_X] for r in sel], [r[outputs.PROFILE_SURFACE] for r in sel]


def bulk_velocity(case, x, t):
    """(y, u_s, u_f, time) of the bulk cell column nearest X (the lower of two as near), at the
    field write nearest T, where the mixture fills at least half the cell."""
    tv, tn = min(foamcase.time_dirs(case), key=lambda d: abs(d[0] - t))
    d = os.path.join(case, tn)
    if not os.path.exists(os.path.join(d, "C")):
        foamcase.run(["postProcess", "-func", "writeCellCentres", "-time", tn], case,
                     "log.writeCellCentres", env_extra=foamcase.run_env())
    c = foamcase.read_internal_field(os.path.join(d, "C"))
    n = len(c)
    us = foamcase.read_internal_field(os.path.join(d, "U.solid"), n)
    uf = foamcase.read_internal_field(os.path.join(d, "U.fluid"), n)
    a = foamcase.read_internal_field(os.path.join(d, "alpha.liquid"), n)
    x0 = min((ci[0] for ci in c), key=lambda cx: (abs(cx - x), cx))  # one column: the nearest
    col = sorted((ci[1], usi[0], ufi[0]) for ci, usi, ufi, ai in zip(c, us, uf, a)
                 if abs(ci[0] - x0) < 1e-9 and ai >= 0.5)
    return [v[0] for v in col], [v[1] for v in col], [v[2] for v in col], tv


def load(path):
    with open(path) as f:
        return json.load(f)


def dem_front(dem, t):
    """The CFD-DEM granular front at T; its last write when T is past it by at most
    outputs.END_TOLERANCE_S, else nan."""
    end = dem[-1][outputs.TIME]
    return outputs.interpolated(dem, outputs.GRANULAR_FRONT,
                                end if end < t <= end + outputs.END_TOLERANCE_S else t)


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


def round_trip(out_dir):
    """The round trip's block (OUT/round_trip.json, tests/bulk/test_round_trip.py --json): per
    pore reference, the largest drift error over the sampled cells, the front and h(x, t) errors;
    `passes` and the headline numbers are the solver's own reference's (mixture); None without."""
    path = os.path.join(out_dir, "round_trip.json")
    if not os.path.isfile(path):
        return None
    d = load(path)
    runs = {r["pore_reference"]: {"drift_error": max(x["max_abs_error"] for x in r["drifts"].values()),
                                  "front_error": r["front_error"], "h_error_m": r["h_error_m"]}
            for r in d["runs"].values()}
    main_run = runs.get("mixture", {})
    return {"drift_error": main_run.get("drift_error"), "front_error": main_run.get("front_error"),
            "h_error_m": main_run.get("h_error_m"), "passes": d["passes"], "by_pore_reference": runs,
            "file": os.path.relpath(path, ROOT),
            "command": "python3 tests/bulk/test_round_trip.py build/bin runs/round_trip "
                       "--json results/bulk_model/round_trip.json"}


def truth_calibrations(out_dir):
    """Per mixture, `mixflow calibrate` on its truth-tier run (OUT/truth_<scene>/summary.json):
    the constant drifts with their 16-84 % interval and R^2, the mass-balance residual, the front
    error at the end and over time, the bulk solver's CPU time, and the command."""
    cal = {}
    for scene, name in SCENES.items():
        path = os.path.join(out_dir, f"truth_{scene}", "summary.json")
        if not os.path.exists(path):
            continue
        d = load(path)
        c, cmp = d["calibration"], d["comparison"]
        end = cmp["fronts"][-1]
        cal[name] = {
            "drifts": {q: c[q]["value"] for q in ("lambda_u", "lambda_w", "pore_pressure_ratio")},
            "interval": {q: c[q]["interval_16_84"]
                         for q in ("lambda_u", "lambda_w", "pore_pressure_ratio")},
            "r2": {q: c[q].get("r2") for q in ("lambda_u", "lambda_w")},
            "mass_residual": c["mass_balance"]["residual_over_scale"],
            "front_error": end["bulk_front_m"] / end["cfd_dem_front_m"] - 1,
            "front_rms_error": cmp["front_rms_error"],
            "bulk_solver_cpu_s": d["bulk_solver_cpu_s"], "command": d["command"]}
    return cal


def committed_blocks(out_dir):
    """The summary's blocks made from committed result files alone (no run directory)."""
    return {"round_trip": round_trip(out_dir), "speedup": speedups(),
            "calibration": truth_calibrations(out_dir),
            "speedup_baseline": "the CFD-DEM solver's CPU time (mixflowCoupled; for P mixflowDem's "
                                "collapse) measured in the same bench run as the bulk model's"}


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--work", default="runs/bulk")
    p.add_argument("--reference", default="runs/reference")
    p.add_argument("--out", default=os.path.join(ROOT, "results", "bulk_model"))
    p.add_argument("--committed-only", action="store_true",
                   help="refresh only the blocks made from committed result files (round_trip, "
                   "speedup, the truth-tier calibrations) in OUT/summary.json, keeping the rest: no run directory needed")
    a = p.parse_args()
    if a.committed_only:
        path = os.path.join(a.out, "summary.json")
        out = load(path)
        out.update(committed_blocks(a.out))
        outputs.write_json(path, out)
        return 0
    stages = load(os.path.join(a.out, "stages.json"))
    solid = load(os.path.join(a.out, "solid_calibration.json"))
    out = {"command": "mixflow bulk-model-results " + " ".join(sys.argv[1:]),
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
        out["front_error_by_stage"][name] = {k: st[k].get("front_error")
                                             for k in ("A0", "A", "B", "B_median", "C", "C_t")
                                             if k in st}
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
    out.update(committed_blocks(a.out))
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

    fig, axes = plt.subplots(1, 3, figsize=(15, 3.8), sharey=True)
    for ax, (scene, name) in zip(axes, SCENES.items()):
        bulk, ref = os.path.join(a.work, scene), os.path.join(a.reference, scene)
        for k, t in enumerate(PROFILE_TIMES):
            ax.plot(*profile(ref, t), "-", color=f"C{k}", label=f"CFD-DEM liquid, {t:g} s")
            ax.plot(*profile(bulk, t), "--", color=f"C{k}", label=f"bulk mixture, {t:g} s")
        dep = outputs.deposit(ref)
        ax.plot([r[outputs.PROFILE_X] for r in dep], [r[outputs.DEPOSIT_TOP] for r in dep], "k:",
                label="CFD-DEM grains at the end")
        ax.set_title(name)
        ax.set_xlim(0, 3.5)
        ax.set_xlabel("x (m)")
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("surface height (m)")
    axes[0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "profiles.png"), dpi=110)

    fig, axes = plt.subplots(1, 3, figsize=(15, 3.8), sharey=True)
    for ax, (scene, name) in zip(axes, SCENES.items()):
        ref = os.path.join(a.reference, scene)
        vp = outputs.read_rows(os.path.join(ref, outputs.VELOCITY_PROFILE))
        x, t = vp[0]["x_section_m"], vp[0][outputs.TIME]
        ax.plot([r["u_x_m_s"] for r in vp], [r["y_m"] for r in vp], "k-o", ms=3,
                label=f"CFD-DEM grains, {t:.2f} s")
        y, us, uf, tb = bulk_velocity(os.path.join(a.work, scene), x, t)
        ax.plot(us, y, "C0--", label=f"bulk u_s, {tb:g} s")
        ax.plot(uf, y, "C1:", label=f"bulk u_f, {tb:g} s")
        ax.set_title(f"{name}, x = {x:g} m")
        ax.set_xlabel("u (m/s)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    axes[0].set_ylabel("y (m)")
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "velocity.png"), dpi=110)
    for name, rec in out["scenes"].items():
        if name != "P":
            print(f"{name:5s} bulk front {rec['bulk_front_m']:.3f} m, CFD-DEM "
                  f"{rec['cfd_dem_front_m']:.3f} m ({100 * rec['front_error']:+.1f} %)")
    print(f"P     bulk front error at 3 s {100 * best['final_error']:+.1f} % "
          f"(rms {100 * best['rms_error']:.1f} %)")


if __name__ == "__main__":
    main()
