"""bulk_stages.py's stage C_t end to end on small inputs: the drift fields of every window of the
synthetic extraction of drift_data.py (6 windows of 0.02 s) calibrated onto a copy of cases/P-bulk
at 0.075 m cells by `calibrate_drifts.py --fields --per-window`, then its ./Allrun 1 to 0.3 s:
the JSON holds the 6 windows, the solver takes them, the run reaches its end time and the stage's
record is the run's front against the reference front.

usage: test_stage_series.py BINDIR WORKDIR"""
import argparse
import os
import shutil
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
from mixflow.commands import bulk_stages  # noqa: E402
import drift_data as dd  # noqa: E402
from mixflow import foamcase, outputs  # noqa: E402
from mixflow.synthcase import checker  # noqa: E402

END = 0.3  # s: the windows end at 0.12 s, so the last one holds for most of the run
REF_FRONT = 1.0  # m, the stage's reference front (the synthetic case has no DEM front)


def main():
    bindir, work = sys.argv[1], os.path.abspath(sys.argv[2])
    os.environ["MIXFLOW_BUILD"] = os.path.dirname(os.path.abspath(bindir))
    failures = []
    check = checker(failures)
    shutil.rmtree(work, ignore_errors=True)
    dem = os.path.join(work, "dem_case")
    dd.make(dem, os.path.join(bindir, "mixflowExtract"))
    # Stage A's case: P-bulk, coarse and short, with its mesh (bulk_stages runs it first).
    case_a = outputs.copy_inputs(os.path.join(ROOT, "cases", "P-bulk"), os.path.join(work, "A"))
    foamcase.set_entry(os.path.join(case_a, "system", "cfdDict"), "cellSize", "0.075")
    foamcase.set_entry(os.path.join(case_a, "system", "controlDict"), "endTime", str(END))
    foamcase.set_entry(os.path.join(case_a, "system", "controlDict"), "writeInterval", "0.1")
    foamcase.run_tool(["mixflowPrepare", "-case", case_a], "test_stage_series")
    foamcase.run_tool(["blockMesh", "-case", case_a], "test_stage_series")
    rec = {}
    a = argparse.Namespace(work=work, flowing_factor="0.1", pressure="porePressureRatio",
                           vertical="auto", pressure_bins="all")
    bulk_stages.drift_stage(rec, "C_t", ["--fields", "--field-mean", "wls", "--per-window"],
                            case_a, dem, REF_FRONT, a)
    r = rec.get("C_t", {})
    check("front_m" in r, f"stage C_t ran: {r}")
    if "front_m" not in r:
        return 1
    windows = rec["C_t_drifts"]["fields"]["lambdaU"]["windows"]
    check(len(windows) == dd.SHAPE[0], f"calibration: {len(windows)} windows "
          f"({dd.SHAPE[0]} in the extraction)")
    case = os.path.join(work, "C_t", "A")
    with open(os.path.join(case, "log.mixflowBulkFoam")) as f:
        log = f.read()
    check(f"the fields of the {dd.SHAPE[0]} windows constant/drifts/<t>/" in log,
          "the solver takes the windows")
    check(abs(r["time_s"] - END) <= 1e-9, f"the run reaches {r['time_s']:g} s ({END:g})")
    check(abs(r["front_error"] - (r["front_m"] / REF_FRONT - 1)) <= 1e-12,
          f"record: front {r['front_m']:.4f} m, error {r['front_error']:+.4f} against "
          f"{REF_FRONT:g} m (1e-12)")
    print("PASS" if not failures else f"FAIL: {len(failures)} checks")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
