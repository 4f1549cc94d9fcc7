"""The bulk model at its calibration stages against the CFD-DEM reference, per mixture scene.

usage: mixflow bulk-stages [--scenes W+P,HB+P,B+P] [--cell-size 0.075]
          [--estimators wls,median] [--field-mean wls] [--window-span 5]
          [--pressure porePressureRatio|lambdaP] [--vertical auto|fit|isotropic]
          [--pressure-bins all|flowing]
          [--reference runs/reference]
          [--solid-from cases/P-bulk] [--work runs/bulk-stages]
          [--out results/bulk_model/stages.json]

For each scene: the tier `bulk` case at --cell-size (`suite.py --tier bulk --set
cfdDict.cellSize=...`) with the uncalibrated solid estimate (stage A0: lambda = 1, tanPhi = tan 25 deg,
nu_s 0.03 m2/s); the same case with the solid block of --solid-from's constant/bulkProperties
(stage A: lambda = 1, the solid rheology calibrated on the dry scene P by mixflow calibrate-solid,
the bulk model's default); then stage A's case with the constant drifts calibrated from the
CFD-DEM reference run's extraction, once per --estimators entry (stage B: `mixflow calibrate-drifts
REFERENCE/<scene> --target CASE --flowing-factor F --pressure P --vertical V --pressure-bins B
--estimator E`, the pore-pressure closure P, the vertical drift's rule V and the pressure's bins B
as `mixflow calibrate`'s, E wls (key B) or median (key
B_median); the reference run needs postProcessing/mixture/mixture.h5, e.g. from
mixflow mixture-lambdas) and run again (`./Allrun`); stage C: stage A's case with the drift
fields lambda(x, y) on its mesh (`calibrate_drifts.py ... --fields --field-mean M`,
docs/calibration.md "Stage C"); stage C_t: the same with the drift fields of every extraction
window, lambda(x, y, t), linear in time (`--fields --per-window --window-span K --field-mean M`:
each window's fields pooled over the K windows centred on it, default 5). Against the
reference's granular front at the end (its postProcessing/dem/timeSeries.csv): the bulk front
(postProcessing/liquid front_bed_m), its error, and the bulk solver's CPU time
(log.mixflowBulkFoam). Writes OUT.
"""

import argparse
import csv
import json
import os
import shutil
import sys

from mixflow.cli import command
ESTIMATE = {"tanPhi": "0.4663", "viscosity": "0.03"}  # stage A0's solid: tan 25 deg, nu_s estimated
from mixflow import ROOT, bulkprops, foamcase, outputs


def last(path, column):
    with open(path) as f:
        rows = list(csv.DictReader(ln for ln in f if ln.strip() and not ln.startswith("#")))
    return float(rows[-1]["time_s"]), float(rows[-1][column])


def run(cmd, cwd=None, fatal=True):
    return foamcase.run_tool(cmd, "bulk_stages", cwd, fatal)


def result(case, ref_front):
    t, front = last(os.path.join(case, "postProcessing", "liquid", "timeSeries.csv"), "front_bed_m")
    return {"time_s": t, "front_m": front, "front_error": front / ref_front - 1,
            "solver_cpu_s": foamcase.execution_time(
                os.path.join(case, "log.mixflowBulkFoam"))}


STAGE_B = {"wls": "B", "median": "B_median"}  # the stage's key in OUT per estimator


def drift_stage(rec, key, options, case_a, ref, ref_front, a):
    """Stage KEY: stage A's case with the drifts calibrate_drifts.py writes with OPTIONS, run.
    REC[KEY] (its result, or why it did not run), REC[KEY + '_calibration'] (the calibration's
    printout) and REC[KEY + '_drifts'] (its JSON)."""
    case = fresh_copy(case_a, os.path.join(a.work, key, os.path.basename(case_a)))
    cal = run(command("calibrate-drifts") + [ref, "--target", case, "--flowing-factor",
               a.flowing_factor, "--pressure", a.pressure, "--vertical", a.vertical,
               "--pressure-bins", a.pressure_bins] + options,
              fatal=False)
    if cal is None:  # e.g. a drift outside the bulk model's range: recorded, not run
        rec[key] = {"error": "calibrate_drifts.py refused the drifts (its message above)"}
        return
    rec[key + "_calibration"] = cal.strip().splitlines()[-12:]
    with open(os.path.join(case, "constant", "bulkProperties.calibration.json")) as f:
        rec[key + "_drifts"] = json.load(f)
    if run(["./Allrun", "1"], cwd=case, fatal=False) is None:  # recorded with its last time
        t, front = last(os.path.join(case, "postProcessing", "liquid", "timeSeries.csv"),
                        "front_bed_m")
        rec[key] = {"error": f"mixflowBulkFoam failed at t = {t:g} s (front {front:.3f} m; "
                             f"{os.path.join(case, 'log.mixflowBulkFoam')})"}
        return
    rec[key] = result(case, ref_front)


def stage_line(rec, key):
    r = rec[key]
    return f"{r['front_m']:.3f} m ({100 * r['front_error']:+.0f} %)" if "front_m" in r else "not run"


def fresh_copy(src, dst):
    """DST (removed first) with the inputs of the case SRC."""
    shutil.rmtree(dst, ignore_errors=True)
    os.makedirs(os.path.dirname(dst), exist_ok=True)
    outputs.copy_inputs(src, dst)
    return dst


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scenes", default="W+P,HB+P,B+P")
    ap.add_argument("--cell-size", default="0.075")
    ap.add_argument("--flowing-factor", default="0.02",
                    help="calibrate_drifts.py --flowing-factor: 0.02 sqrt(g H) = 0.049 m/s, the "
                    "flowing rule of results/yield_stress/lambdas.json (|u_s| >= 0.05 m/s)")
    ap.add_argument("--estimators", default="wls,median",
                    help="calibrate_drifts.py --estimator of stage B, one run each (wls: key B, "
                    "median: key B_median)")
    ap.add_argument("--field-mean", default="wls",
                    help="stages C and C_t: calibrate_drifts.py --field-mean (wls or ratio; ratio "
                    "lets W&P's lambda_w reach the range limit and the run diverge)")
    ap.add_argument("--pressure", default="porePressureRatio",
                    help="calibrate_drifts.py --pressure of stages B, C and C_t (default "
                    "porePressureRatio, chi without the pole of Lambda_p, as mixflow calibrate; "
                    "lambdaP for the pressure drift of Pokhrel et al.)")
    ap.add_argument("--vertical", default="auto",
                    help="calibrate_drifts.py --vertical of stages B, C and C_t (default auto, as "
                    "mixflow calibrate: lambda_w's fit where well-posed, else the isotropic drift)")
    ap.add_argument("--pressure-bins", default="all",
                    help="calibrate_drifts.py --pressure-bins of stages B, C and C_t (default all: "
                    "the pressure closure over every mixture bin, the column at rest too)")
    ap.add_argument("--reference", default=os.path.join(ROOT, "runs", "reference"))
    ap.add_argument("--solid-from", default=os.path.join(ROOT, "cases", "P-bulk"))
    ap.add_argument("--window-span", type=int, default=5,
                    help="stage C_t: calibrate_drifts.py --window-span (each window's fields from "
                    "the K windows centred on it; 1, a window's own samples alone, lets W&P's "
                    "lambda_w reach 40 in a bin and the run diverge at 0.75 s)")
    ap.add_argument("--work", default=os.path.join(ROOT, "runs", "bulk-stages"))
    ap.add_argument("--out", default=os.path.join(ROOT, "results", "bulk_model", "stages.json"))
    a = ap.parse_args()
    try:
        solid = bulkprops.read(a.solid_from).get("solid")
    except bulkprops.DictError as e:
        sys.exit(f"bulk_stages: {bulkprops.path(a.solid_from)}: {e}")
    if not isinstance(solid, dict) or not solid:
        sys.exit(f"bulk_stages: --solid-from {a.solid_from}: {bulkprops.path(a.solid_from)} has no "
                 "solid { ... } block (mixflow calibrate-solid --target writes one)")
    out = {"command": "mixflow bulk-stages " + " ".join(sys.argv[1:]),
           "cell_size_m": float(a.cell_size), "pressure": a.pressure, "vertical": a.vertical,
           "pressure_bins": a.pressure_bins,
           "solid": solid, "solid_A0": ESTIMATE,
           "solid_from": os.path.relpath(os.path.abspath(a.solid_from), ROOT), "scenes": {}}
    for scene in a.scenes.split(","):
        ref = os.path.join(a.reference, scene)
        t_ref, ref_front = last(os.path.join(ref, "postProcessing", "dem", "timeSeries.csv"),
                                "front_x_m")
        work = os.path.join(a.work, "A0")
        shutil.rmtree(os.path.join(work, scene), ignore_errors=True)
        run(command("suite") + ["--tier", "bulk",
             "--scenes", scene, "--work", work, "--set", f"cfdDict.cellSize={a.cell_size}"]
            + [x for k, v in ESTIMATE.items() for x in ("--set", f"bulkProperties.solid.{k}={v}")])
        case_a0 = os.path.join(work, scene)
        rec = {"cfd_dem_front_m": ref_front, "cfd_dem_time_s": t_ref,
               "A0": result(case_a0, ref_front)}
        case_a = fresh_copy(case_a0, os.path.join(a.work, "A", scene))
        p = bulkprops.path(case_a)
        bulkprops.write_text(p, bulkprops.block_text(p, "solid", solid))
        run(["./Allrun", "1"], cwd=case_a)
        rec["A"] = result(case_a, ref_front)
        out["scenes"][scene] = rec
        for est in a.estimators.split(","):
            drift_stage(rec, STAGE_B[est], ["--estimator", est], case_a, ref, ref_front, a)
        # Stage C: the drift fields on stage A's mesh (copied along with its inputs), fixed and
        # per window.
        fields = ["--fields", "--field-mean", a.field_mean]
        drift_stage(rec, "C", fields, case_a, ref, ref_front, a)
        drift_stage(rec, "C_t", fields + ["--per-window", "--window-span", str(a.window_span)],
                    case_a, ref, ref_front, a)
        print(f"{scene}: CFD-DEM front {ref_front:.3f} m; stage A0 {stage_line(rec, 'A0')}, "
              f"A {stage_line(rec, 'A')}; stage B "
              + ", ".join(f"{est} {stage_line(rec, k)}" for est, k in STAGE_B.items() if k in rec)
              + f"; stage C {stage_line(rec, 'C')}, in time {stage_line(rec, 'C_t')}", flush=True)
    outputs.write_json(a.out, out)
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
