"""calibrate_solid.py: bad input exits 2 naming the file or option and the allowed range before
anything runs; and on a reference made by the bulk model itself at a known (tanPhi, nu_s) the
grid search finds that point with a zero score and writes it into the target's bulkProperties,
every other byte kept.

usage: test_calibrate_solid.py BINDIR WORKDIR"""
import json
import os
import shutil
import subprocess
import sys

from mixflow.cli import command  # noqa: E402
from mixflow import outputs  # noqa: E402
from mixflow.synthcase import checker, write  # noqa: E402

CMD = command("calibrate-solid")
HEADER = "FoamFile { version 2.0; format ascii; class dictionary; object bulkProperties; }\n"
TRUE_TAN_PHI, TRUE_NU = 0.6, 0.01


def main():
    bindir, work = sys.argv[1], sys.argv[2]
    env = dict(os.environ, MIXFLOW_BUILD=os.path.dirname(os.path.abspath(bindir)))
    failures = []
    check = checker(failures)
    shutil.rmtree(work, ignore_errors=True)
    target = os.path.join(work, "target")
    bp = os.path.join(target, "constant", "bulkProperties")
    original = HEADER + "// kept\ndrifts { lambdaU 1.2; }\nsolid { tanPhi 0.4; mY 50; }\n"
    write(bp, original)
    nofront = os.path.join(work, "nofront")
    write(os.path.join(nofront, outputs.DEM_SERIES), "time_s,particles\n0,10\n")
    # A DEM series of any front: the reference of the refusals and of the first bulk run.
    seed = os.path.join(work, "seed")
    write(os.path.join(seed, outputs.DEM_SERIES), "time_s,front_x_m\n0,0.9\n3,0.9\n")
    bare = os.path.join(work, "bare")
    os.makedirs(bare)
    broken = os.path.join(work, "broken")
    write(os.path.join(broken, "constant", "bulkProperties"), HEADER + "solid { tanPhi 0.5;\n")
    grid_work = os.path.join(work, "grid")
    out = os.path.join(work, "calibration.json")
    common = ["--work", grid_work, "--out", out]

    nowhere = os.path.join(work, "nowhere")
    cases = [
        ("missing reference", [nowhere], [nowhere, "no such file", "finished DEM case of P"]),
        ("no front column", [nofront], [outputs.DEM_SERIES, "front_x_m"]),
        ("tanPhi not numbers", [seed, "--tan-phi", "a,b"], ["--tan-phi a,b", "numbers"]),
        ("tanPhi 7", [seed, "--tan-phi", "0.5,7"], ["--tan-phi 0.5,7", "[0, 5]"]),
        ("viscosity 0", [seed, "--viscosity", "0"], ["--viscosity 0", "[1e-09, 1000.0]"]),
        ("times reversed", [seed, "--times", "3:1:0.5"], ["--times 3:1:0.5", "T0 <= T1"]),
        ("target without constant/", [seed, "--target", bare], [bare, "no constant/"]),
        ("mu(I) with a target", [seed, "--rheology", "muI", "--target", target],
         ["--target", "--rheology muI", "not calibrated"]),
    ]
    for what, args, needles in cases:
        r = subprocess.run(CMD + args + common, capture_output=True, text=True, env=env)
        msg = r.stdout + r.stderr
        check(r.returncode == 2 and all(n in msg for n in needles),
              f"{what}: exit 2 ({r.returncode}) naming {needles}: {msg.strip()[-300:]}")
    check(not os.path.exists(grid_work) and not os.path.exists(out),
          "nothing ran and nothing was written after the refusals")

    # The reference: the bulk model at the true point, its front written as a DEM series.
    ref = os.path.join(work, "reference")
    r = subprocess.run(CMD + [seed, "--tan-phi", str(TRUE_TAN_PHI),
                              "--viscosity", str(TRUE_NU), "--work", ref, "--out",
                              os.path.join(work, "ref.json")],
                       capture_output=True, text=True, env=env)
    check(r.returncode == 0, f"the bulk run at the true point: {r.stderr.strip()[-300:]}")
    rows = outputs.series(os.path.join(ref, f"tanPhi{TRUE_TAN_PHI:g}_nu{TRUE_NU:g}"))
    dem = os.path.join(work, "dem")
    write(os.path.join(dem, outputs.DEM_SERIES),
          "time_s,front_x_m\n" + "".join(f"{row[outputs.TIME]},{row[outputs.LIQUID_FRONT]}\n"
                                          for row in rows))

    # The grid: the true point among others, reusing the base case made above.
    shutil.copytree(os.path.join(ref, "base"), os.path.join(grid_work, "base"))
    r = subprocess.run(CMD + [dem, "--tan-phi", "0.4,0.6,0.8", "--viscosity", "0.01",
                              "--target", target] + common,
                       capture_output=True, text=True, env=env)
    check(r.returncode == 0, f"the grid runs: {r.stderr.strip()[-300:]}")
    res = json.load(open(out))
    best = res["best"]
    check(best["tan_phi"] == TRUE_TAN_PHI and best["viscosity_m2_s"] == TRUE_NU,
          f"best point is the true one ({best['tan_phi']}, {best['viscosity_m2_s']})")
    check(best["rms_error"] < 1e-9, f"its score is zero ({best['rms_error']:.2e})")
    others = [g["rms_error"] for g in res["grid"] if g["tan_phi"] != TRUE_TAN_PHI]
    check(min(others) > 0.01, f"the other points score > 1 % ({min(others):.3f})")
    text = open(bp).read()
    check(text == original.replace("tanPhi 0.4; mY 50;", "tanPhi 0.6; mY 50; viscosity 0.01;"),
          f"target's bulkProperties: solid set, the rest kept:\n{text}")
    check(os.path.isfile(os.path.splitext(out)[0] + ".csv"), "the CSV is written")

    # An unreadable target bulkProperties stops before any run.
    r = subprocess.run(CMD + [dem, "--target", broken, "--work", os.path.join(work, "g2"),
                              "--out", os.path.join(work, "g2.json")],
                       capture_output=True, text=True, env=env)
    msg = r.stdout + r.stderr
    check(r.returncode == 2 and "bulkProperties" in msg and "not closed" in msg
          and not os.path.exists(os.path.join(work, "g2")),
          f"unreadable target bulkProperties: exit 2, nothing run: {msg.strip()[-200:]}")
    print(f"{len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
