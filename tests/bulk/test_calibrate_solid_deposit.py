"""calibrate_solid.py's deposit error and --score on a grid whose two points are already run (their
.done, time series and h(x) profiles written here, so nothing runs): the deposit error against a
hand-computed value, the DEM bins averaged over cell columns that straddle them, the profile at
the write nearest the last of --times, the best point by `front` and by `front+deposit`, the
target written; and the refusals of --score (exit 2 naming the option, the file, the entry and
what is allowed), with nothing written.

usage: test_calibrate_solid_deposit.py WORKDIR"""
import json
import os
import shutil
import subprocess
import sys

from mixflow.cli import command  # noqa: E402
from mixflow import outputs  # noqa: E402
from mixflow.commands.calibrate_solid import SCENE  # noqa: E402
from mixflow.synthcase import checker, write  # noqa: E402

CMD = command("calibrate-solid")
HEADER = "FoamFile { version 2.0; format ascii; class dictionary; object bulkProperties; }\n"
REF_FRONT = {0: 0.9, 1: 1.5, 2: 2.0, 3: 2.0}
# The DEM deposit on bins of 0.1 m; the bulk model's cell columns are 0.15 m wide, so the DEM
# columns by hand (overlaps x h / 0.15): 0.09/0.15, 0.07/0.15, 0.025/0.15, 0.005/0.15.
DEM_X = [0.05, 0.15, 0.25, 0.35, 0.45, 0.55]
DEM_H = [0.6, 0.6, 0.4, 0.2, 0.1, 0.0]
COLS = [0.075, 0.225, 0.375, 0.525]
DEM_COLS = [0.6, 0.07 / 0.15, 0.025 / 0.15, 0.005 / 0.15]
# Point A: the DEM's front at every time, a deposit off by 0.1, 1/30, 1/30 and 1/15 m:
# error (0.1 + 2/30 + 1/15) / (0.19 / 0.15) = 0.23333 / 1.26667 = 0.184211.
A, A_H = (0.4, 0.01), [0.5, 0.5, 0.2, 0.1]
A_ERROR = (0.1 + 1 / 30 + 1 / 30 + 1 / 15) / (0.19 / 0.15)
# Point B: fronts 2 % long at every time (rms 0.02), the DEM's deposit on its columns (error 0).
B, B_H = (0.6, 0.01), DEM_COLS


def grid_point(work, point, scale, h):
    """A finished grid point: its .done, fronts REF_FRONT x SCALE, profiles at 2.5 s (zero
    heights, which the deposit must not take) and 3 s (H)."""
    case = os.path.join(work, f"tanPhi{point[0]:g}_nu{point[1]:g}")
    write(os.path.join(case, outputs.DONE), "")
    write(os.path.join(case, outputs.LIQUID_SERIES),
          "time_s,front_bed_m\n" + "".join(f"{t},{f * scale!r}\n" for t, f in REF_FRONT.items()))
    write(os.path.join(case, outputs.LIQUID_PROFILES),
          "time_s,x_m,depth_m,discharge_m2_s,surface_m\n"
          + "".join(f"2.5,{x},0,0,0\n" for x in COLS)
          + "".join(f"3,{x},{v!r},0,{v!r}\n" for x, v in zip(COLS, h)))


def main():
    work = sys.argv[1]
    failures = []
    check = checker(failures)
    shutil.rmtree(work, ignore_errors=True)
    ref = os.path.join(work, "dem")
    write(os.path.join(ref, outputs.DEM_SERIES),
          "time_s,front_x_m\n" + "".join(f"{t},{f}\n" for t, f in REF_FRONT.items()))
    write(os.path.join(ref, outputs.DEPOSIT), "x_m,h_top_m,h_volume_m,time_s\n"
          + "".join(f"{x},{h + 0.02},{h},2.9\n" for x, h in zip(DEM_X, DEM_H)))
    fronts = open(os.path.join(ref, outputs.DEM_SERIES)).read()
    nodeposit = os.path.join(work, "nodeposit")
    write(os.path.join(nodeposit, outputs.DEM_SERIES), fronts)
    emptydeposit = os.path.join(work, "emptydeposit")
    write(os.path.join(emptydeposit, outputs.DEM_SERIES), fronts)
    write(os.path.join(emptydeposit, outputs.DEPOSIT), "x_m,h_top_m\n0.05,0.6\n0.15,0.6\n")
    grid = os.path.join(work, "grid")
    write(os.path.join(grid, "base", SCENE, outputs.DONE), "")
    grid_point(grid, A, 1.0, A_H)
    grid_point(grid, B, 1.02, B_H)
    target = os.path.join(work, "target")
    bp = os.path.join(target, "constant", "bulkProperties")
    write(bp, HEADER + "solid { tanPhi 0.45; viscosity 0.02; }\n")
    points = ["--tan-phi", f"{A[0]},{B[0]}", "--viscosity", f"{A[1]}", "--times", "1:3:1",
              "--work", grid]

    def run(reference, *extra, out="calibration.json"):
        out = os.path.join(work, out)
        r = subprocess.run(CMD + [reference] + points + ["--out", out, *extra],
                           capture_output=True, text=True)
        return r.returncode, r.stdout + r.stderr, out

    refusals = [
        ("--score front+deposit without a deposit", [nodeposit, "--score", "front+deposit"],
         [outputs.DEPOSIT, "no such file", "--score front"]),
        ("a deposit without h_volume_m", [emptydeposit, "--score", "front+deposit"],
         [outputs.DEPOSIT, "h_volume_m"]),
        ("an unknown --score", [ref, "--score", "deposit"],
         ["--score", "'deposit'", "front+deposit"]),
    ]
    for what, (reference, *extra), needles in refusals:
        code, msg, out = run(reference, *extra, "--target", target, out="refused.json")
        check(code == 2 and all(n in msg for n in needles),
              f"{what}: exit 2 ({code}) naming {needles}: {msg.strip()[-300:]}")
        check(not os.path.exists(out), f"{what}: nothing written")
    check("tanPhi 0.45" in open(bp).read(), "the target unchanged after the refusals")

    code, msg, out = run(ref)
    res = json.load(open(out)) if code == 0 else {}
    check(code == 0, f"--score front (the default) scores the finished points: "
                     f"{msg.strip()[-300:]}")
    by_point = {(g["tan_phi"], g["viscosity_m2_s"]): g for g in res.get("grid", [])}
    a, b = by_point.get(A, {}), by_point.get(B, {})
    check(abs(a.get("deposit_error", 1) - A_ERROR) < 1e-12,
          f"point A's deposit error {a.get('deposit_error')} = {A_ERROR:.6f} by hand")
    check(b.get("deposit_error", 1) < 1e-12,
          f"point B's deposit error {b.get('deposit_error')} = 0")
    check(a.get("deposit_time_s") == 3 and a.get("back_wall_m") == 0.5
          and a.get("deposit_max_m") == 0.5,
          f"A's deposit at 3 s, back wall and maximum 0.5 m ({a.get('deposit_time_s')}, "
          f"{a.get('back_wall_m')}, {a.get('deposit_max_m')})")
    dem = res.get("reference_deposit") or {}
    check(dem.get("x_m") == COLS and max(abs(u - v) for u, v in zip(dem.get("dem_h_m", [1] * 4),
                                                                    DEM_COLS)) < 1e-12,
          f"the DEM deposit on the cell columns {dem.get('dem_h_m')} = {DEM_COLS} by hand")
    check(abs(b.get("rms_error", 1) - 0.02) < 1e-12 and a.get("rms_error", 1) < 1e-12,
          f"front errors A 0, B 0.02 ({a.get('rms_error')}, {b.get('rms_error')})")
    best = res.get("best", {})
    check((best.get("tan_phi"), best.get("viscosity_m2_s")) == A and res.get("score") == "front",
          f"by the front the best is A ({best.get('tan_phi')}, {best.get('viscosity_m2_s')})")

    code, msg, out = run(ref, "--score", "front+deposit", "--target", target)
    res = json.load(open(out)) if code == 0 else {}
    best = res.get("best", {})
    check(code == 0 and (best.get("tan_phi"), best.get("viscosity_m2_s")) == B,
          f"by front+deposit the best is B ({best.get('tan_phi')}, {best.get('viscosity_m2_s')}): "
          f"{msg.strip()[-200:]}")
    scores = {(g["tan_phi"], g["viscosity_m2_s"]): g["score"] for g in res.get("grid", [])}
    check(abs(scores.get(A, 1) - A_ERROR) < 1e-12 and abs(scores.get(B, 1) - 0.02) < 1e-12,
          f"front+deposit scores hypot(rms, deposit): A {scores.get(A)}, B {scores.get(B)}")
    by = res.get("best_by_score", {})
    check(by.get("front", {}).get("tan_phi") == A[0] and by.get("front", {}).get("score") == 0
          and by.get("front+deposit", {}).get("tan_phi") == B[0]
          and abs(by.get("front+deposit", {}).get("score", 1) - 0.02) < 1e-12,
          f"best_by_score: A by the front (score 0), B by front+deposit (0.02): {by}")
    check("tanPhi 0.6" in open(bp).read(), "the target takes B's tanPhi 0.6")
    with open(os.path.splitext(out)[0] + ".csv") as f:
        head = f.readline().strip().split(",")
    check(head[:5] == ["tan_phi", "viscosity_m2_s", "rms_error", "deposit_error", "score"],
          f"the CSV has the deposit error and the score: {head[:5]}")
    print(f"{len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
