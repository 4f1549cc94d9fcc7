"""`mixflow calibrate` end to end on a short CFD-DEM run of cases/W+P-quick (0.6 s, about
30 s in all): refusals before anything runs, then extraction (the shipped docs/extractDict fitted to
the case), calibration, the bulk run and the comparison.

Asserted (each against what it is recomputed from, with why the tolerance):
  - refusals exit 2, name the missing file or option, and create no work directory;
  - the summary's drifts are the ones written into the bulk case's bulkProperties (6 significant
    digits, the writer's format), each inside its 16-84 % bootstrap interval, R^2 <= 1, and
    inside the bulk model's admissible range (alpha_s + lambda alpha_f >= 0.01 and |lambda| <=
    1000 for lambda_u, lambda_w; chi in [-10, 1); docs/bulk_model.md), recomputed here;
  - the bulk run reached the end time (1e-3 s, a solver step) and the summary's front at the end
    equals its time series' last row and the CFD-DEM front interpolated there, or its last row
    within 1e-3 s past it (1e-12: the same numbers, read back);
  - the three overlay plots are PNG files, u(y) at demDict velocityProfile's section is compared;
  - --skip-existing reruns nothing: the bulk solver's log unchanged, the same summary numbers;
  - a flowing threshold that refuses the flow exits 2 naming --flowing-factor and the
    extractDict's thresholds.minVelocity.
The bulk front is not asserted against CFD-DEM's: constant drifts do not carry a 0.6 s collapse
over within a stated tolerance (docs/calibration.md gives the measured gap).
usage: test_calibrate_pipeline.py BINDIR WORKDIR"""
import json
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
from mixflow import foamcase, foamdict, outputs  # noqa: E402
from mixflow.cli import command  # noqa: E402
from mixflow.synthcase import checker  # noqa: E402

END = 0.6  # s: past demDict velocityProfile.time 0.5 of W+P-quick, so u(y) is compared
DENOMINATOR_MIN, DRIFT_MAX = 0.01, 1000.0  # the bulk model's range (prepare/BulkModel.cpp)
RATIO_MIN, RATIO_MAX = -10.0, 1.0  # chi's range (common/DriftAlgebra.h), the upper end open


def calibrate(*args):
    r = subprocess.run(command("calibrate", *args), capture_output=True, text=True,
                       env=foamcase.run_env())
    print(r.stdout[-3000:], r.stderr[-3000:])
    return r


def main():
    bindir, work = sys.argv[1], os.path.abspath(sys.argv[2])
    os.environ["MIXFLOW_BUILD"] = os.path.dirname(os.path.abspath(bindir))
    failures = []
    check = checker(failures)
    shutil.rmtree(work, ignore_errors=True)
    case = outputs.copy_inputs(os.path.join(ROOT, "cases", "W+P-quick"), os.path.join(work, "WPq"))
    foamcase.set_entry(os.path.join(case, "system", "controlDict"), "endTime", repr(END))
    out = os.path.join(work, "out")

    # Refusals before the run exists: nothing is made.
    r = calibrate(case, "--work", out)
    check(r.returncode == 2 and outputs.DEM_SERIES in r.stderr and not os.path.exists(out),
          "an unrun case: exit 2 naming postProcessing/dem/timeSeries.csv, no work directory")
    r = calibrate(os.path.join(ROOT, "cases", "P-bulk"), "--work", out)
    check(r.returncode == 2 and "mixtureModel bulk" in r.stderr and not os.path.exists(out),
          "a bulk-model case: exit 2 naming cfdDict mixtureModel")

    foamcase.run_tool(["nice", "-n", "10", "./Allrun", "1"], "test_calibrate_pipeline", cwd=case)
    r = calibrate(case, "--work", out, "--end", "5")
    check(r.returncode == 2 and "--end 5" in r.stderr and not os.path.exists(out),
          "--end past the last field write: exit 2 naming --end")

    r = calibrate(case, "--work", out)
    check(r.returncode == 0, f"the pipeline exits 0 (got {r.returncode})")
    if r.returncode != 0:
        print(f"FAIL: {len(failures) or 1} checks")
        return 1
    with open(os.path.join(out, "summary.json")) as f:
        s = json.load(f)
    bulk = s["bulk_case"]
    drifts = foamdict.read_dict(os.path.join(bulk, "constant", "bulkProperties"))["drifts"]
    check(drifts["pressure"] == "porePressureRatio", "the default closure porePressureRatio")
    alpha = s["solid_fraction"]
    lo = (DENOMINATOR_MIN - alpha) / (1 - alpha)
    for q, key in (("lambda_u", "lambdaU"), ("lambda_w", "lambdaW"),
                   ("pore_pressure_ratio", "porePressureRatio")):
        c = s["calibration"][q]
        v, (p16, p84) = c["value"], c["interval_16_84"]
        check(abs(float(drifts[key]) - v) <= 5e-6 * abs(v),
              f"{q} {v:.6g}: written as {drifts[key]} (6 digits)")
        check(p16 <= v <= p84, f"{q} inside its 16-84 % interval [{p16:.4g}, {p84:.4g}]")
        check(c["r2"] is not None and c["r2"] <= 1, f"{q} R^2 {c['r2']} <= 1")
        ok = RATIO_MIN <= v < RATIO_MAX if q == "pore_pressure_ratio" else lo <= v <= DRIFT_MAX
        check(ok, f"{q} {v:.4g} admissible (alpha_s {alpha:g}: lambda >= {lo:.4g}, chi in [-10, 1))")
    blk = outputs.read_rows(os.path.join(bulk, outputs.LIQUID_SERIES))
    dem = outputs.read_rows(os.path.join(case, outputs.DEM_SERIES))
    fe = s["comparison"]["front_at_end"]
    check(abs(blk[-1]["time_s"] - END) <= 1e-3, f"the bulk run ends at {blk[-1]['time_s']:g} s")
    # The CFD-DEM front at the bulk run's last time, its last row when that time is past it by
    # at most a DEM step (bulk_model_results.dem_front's rule).
    ref = outputs.interpolated(dem, outputs.GRANULAR_FRONT, min(fe["time_s"], dem[-1]["time_s"]))
    check(fe["bulk_front_m"] == blk[-1][outputs.LIQUID_FRONT] and abs(fe["cfd_dem_front_m"] - ref)
          <= 1e-12 and abs(fe["front_error"] - (fe["bulk_front_m"] / ref - 1)) <= 1e-12,
          f"front at the end: bulk {fe['bulk_front_m']:.4f} m, CFD-DEM {ref:.4f} m "
          f"({100 * fe['front_error']:+.1f} %), as read back")
    for name in ("fronts.png", "profiles.png", "velocity.png"):
        with open(os.path.join(out, name), "rb") as f:
            check(f.read(8) == b"\x89PNG\r\n\x1a\n", f"{name} is a PNG")
    check(s["comparison"]["u_y"].get("rms_difference_m_s") is not None,
          f"u(y) compared at x = {s['comparison']['u_y'].get('x_m')} m")

    log = os.path.join(bulk, "log.mixflowBulkFoam")
    stamp = os.path.getmtime(log)
    r = calibrate(case, "--work", out, "--skip-existing")
    with open(os.path.join(out, "summary.json")) as f:
        s2 = json.load(f)
    check(r.returncode == 0 and os.path.getmtime(log) == stamp
          and s2["comparison"]["front_at_end"] == fe and s2["calibration"] == s["calibration"],
          "--skip-existing: no new bulk run, the same summary")
    r = calibrate(case, "--work", out, "--skip-existing", "--flowing-factor", "100")
    check(r.returncode == 2 and "--flowing-factor" in r.stderr and "minVelocity" in r.stderr,
          "a threshold that refuses the flow: exit 2 naming --flowing-factor and minVelocity")
    print("PASS" if not failures else f"FAIL: {len(failures)} checks")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
