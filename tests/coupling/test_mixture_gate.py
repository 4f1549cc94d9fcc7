"""A mixture's lifted gate holds both phases until it passes (sceneProperties gate, lifted).

The quick W&P (cases/W+P-quick, 813 grains, 2-D fluid on 0.06 m cells) runs to 0.3 s through
run_mixture_case.py (which checks its conservation laws: every grain and the liquid volume
accounted for, action = reaction) twice:
  held (speed 0): every grain centre stays behind the grains' plate (x <= L + r + 1e-3 d at every
    particle snapshot) and the liquid's bed-row front behind the liquid's plate (x < L + its
    two-cell thickness);
  lifted at 1 m/s: the grains pass below the plate (front beyond L + 2 d at 0.3 s) and so does the
    liquid (bed-row front beyond the plate).
Usage: test_mixture_gate.py ROOT BINDIR WORKDIR
"""

import csv
import os
import subprocess
import sys

END, L, D, DX = 0.3, 0.45, 0.024, 0.06  # s, m: W+P-quick's sample length, grain and cell size


def run(root, bindir, work, speed):
    cmd = [sys.executable, os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                        "run_mixture_case.py"),
           "--root", root, "--bindir", bindir, "--workdir", work, "--end", str(END),
           "--scene", "gate.removal=lifted", "--scene", f"gate.speed={speed}"]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        print(r.stdout[-3000:], r.stderr[-3000:])
        sys.exit(f"FAIL: the run with the plate lifted at {speed} m/s failed (its checks above)")
    return os.path.join(work, "W+P-quick")


def last(path, key):
    with open(path) as f:
        rows = list(csv.DictReader(ln for ln in f if not ln.startswith("#")))
    return float(rows[-1][key])


def main():
    root, bindir, work = sys.argv[1:4]
    sys.path.insert(0, os.path.join(root, "python"))
    from mixflow.observables import vtk_points, vtk_series
    from mixflow.synthcase import checker
    failures = []
    check = checker(failures)

    held = run(root, bindir, os.path.join(work, "held"), 0)
    worst = max(float(vtk_points(p)[:, 0].max()) for _, p in vtk_series(held))
    check(worst <= L + D / 2 + 1e-3 * D,
          f"held: largest grain centre x {worst:.4f} m <= L + r + 1e-3 d = {L + D / 2 + 1e-3 * D:.4f} m")
    front = last(os.path.join(held, "postProcessing", "liquid", "timeSeries.csv"), "front_bed_m")
    check(front < L + 2 * DX, f"held: liquid front {front:.4f} m behind the plate's end {L + 2 * DX} m")
    lifted = run(root, bindir, os.path.join(work, "lifted"), 1)
    grains = last(os.path.join(lifted, "postProcessing", "dem", "timeSeries.csv"), "front_x_m")
    check(grains > L + 2 * D, f"lifted at 1 m/s: granular front {grains:.3f} m beyond L + 2 d")
    front = last(os.path.join(lifted, "postProcessing", "liquid", "timeSeries.csv"), "front_bed_m")
    check(front > L + 2 * DX, f"lifted at 1 m/s: liquid front {front:.3f} m beyond the plate")
    if failures:
        sys.exit("FAIL: " + "; ".join(failures))
    print("PASS")


if __name__ == "__main__":
    main()
