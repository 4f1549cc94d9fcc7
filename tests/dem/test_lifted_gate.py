#!/usr/bin/env python3
"""The grains' lifted gate (sceneProperties gate { removal lifted; speed V; }): a plate at x = L
whose lower edge rises at V, the grains held by it until it passes (dem/LiftedGate.h).

usage: test_lifted_gate.py MIXFLOWDEM ROOT WORKDIR

cases/P at the quick tier (3 d periodic slice, E x 1e-4) with a smaller column (L = H = 0.3 m,
about 540 grains), run to END four times from the same settle:
  1. held (speed 0): every grain centre stays behind the plate, x <= L + r + 1e-3 d, at every
     snapshot (the plate holds; nothing leaks through the gaps it leaves at the periodic planes),
     and no grain is lost or deleted;
  2. lifted at 1 m/s: the grains leave below the plate (the front passes L + 2 d), every grain is
     accounted for (remaining + deleted = settled, lost 0), the plate is removed once its edge is
     2 d above the column, and the front lags the instant gate's at 0.1 and 0.2 s (a gate that
     opens from the floor releases the column later);
  3. the default (no gate block) and an explicit `removal instant` give the same time series, bit
     for bit (the lifted gate's code stays off the paper's path);
  4. the lifted run stopped at 0.2 s and resumed to END (mixflowDem -resume, the plate placed
     again at h(t) from the last snapshot's restart) gives the uninterrupted run's time series,
     bit for bit (measured: equal).
"""
import shutil
import csv
import os
import subprocess
import sys

exe, root, work = (os.path.abspath(a) for a in sys.argv[1:4])
os.environ["MIXFLOW_BUILD"] = os.path.dirname(os.path.dirname(exe))
from mixflow import foamdict  # noqa: E402
from mixflow.foamcase import set_entry  # noqa: E402
from mixflow.commands import suite  # noqa: E402
from mixflow.observables import vtk_points, vtk_series  # noqa: E402
from mixflow.synthcase import checker  # noqa: E402

END = 0.4  # s: the 1 m/s plate passes the 0.3 m column (and 2 d) at about 0.35 s
L, D = 0.3, 0.024
SPEED = 1.0  # m/s
failures = []
check = checker(failures)


def run(name, gate):
    t = suite.Tier(os.path.join(root, "cases", "tiers", "quick"))
    t.set_entries([f"controlDict.endTime={END}", f"sceneProperties.sample.length={L}",
                   "sceneProperties.sample.height=0.3"])
    case = os.path.join(work, name)
    suite.copy_at_tier("P", t, case)
    if gate:
        with open(os.path.join(case, "constant", "sceneProperties"), "a") as f:
            f.write(f"gate {{ {gate} }}\n")
    r = subprocess.run([exe, "-case", case], capture_output=True, text=True)
    with open(os.path.join(case, "log.mixflowDem"), "w") as f:
        f.write(r.stdout + r.stderr)
    if r.returncode != 0:
        sys.exit(f"mixflowDem failed on {case}:\n{r.stdout[-3000:]}{r.stderr[-2000:]}")
    with open(os.path.join(case, "postProcessing", "dem", "timeSeries.csv")) as f:
        rows = list(csv.DictReader(ln for ln in f if not ln.startswith("#")))
    return case, rows, r.stdout


def front_at(rows, t):
    return float(min(rows, key=lambda r: abs(float(r["time_s"]) - t))["front_x_m"])


def accounted(rows):
    first, last = rows[0], rows[-1]
    n0 = int(first["particles"])
    n = int(last["particles"]) + int(last["deleted_outlet"]) + int(last["deleted_top"])
    return n == n0 and int(last["lost"]) == 0, n0, n, int(last["lost"])


os.makedirs(work, exist_ok=True)
held_case, held, _ = run("held", "removal lifted; speed 0;")
worst = max(float(vtk_points(p)[:, 0].max()) for _, p in vtk_series(held_case))
check(worst <= L + D / 2 + 1e-3 * D,
      f"held plate: the largest grain centre x over all snapshots {worst:.5f} m <= L + r "
      f"+ 1e-3 d = {L + D / 2 + 1e-3 * D:.5f} m")
ok, n0, n, lost = accounted(held)
check(ok and int(held[-1]["deleted_outlet"]) == 0,
      f"held plate: {n} of {n0} grains accounted for, lost {lost}, none deleted")

lifted_case, lifted, out = run("lifted", f"removal lifted; speed {SPEED};")
instant_case, instant, _ = run("instant", "removal instant;")
ok, n0, n, lost = accounted(lifted)
check(ok, f"lifted plate: remaining + deleted {n} = settled {n0}, lost {lost}")
check(front_at(lifted, END) > L + 2 * D,
      f"lifted plate: the grains passed below it (front {front_at(lifted, END):.3f} m > L + 2 d)")
check("plate removed" in out, "lifted plate: removed once past the column (log: 'plate removed')")
for t in (0.1, 0.2):
    fl, fi = front_at(lifted, t), front_at(instant, t)
    check(fl < fi, f"front at {t} s: lifted {fl:.3f} m behind instant {fi:.3f} m")

default_case, default, _ = run("default", "")
same = [r == s for r, s in zip(default, instant)]
check(len(default) == len(instant) and all(same),
      f"no gate block and `removal instant`: {sum(same)} of {len(default)} time-series rows "
      "equal bit for bit")
# 4. Stopped at 0.2 s, resumed to END.
resumed = os.path.join(work, "resumed")
shutil.rmtree(resumed, ignore_errors=True)
shutil.copytree(os.path.join(work, "lifted"), resumed,
                ignore=shutil.ignore_patterns("postProcessing", "VTK", "restart_*", "resume.state"))
for args, end in (([], 0.2), (["-resume"], END)):
    set_entry(os.path.join(resumed, "system", "controlDict"), "endTime", repr(end))
    r = subprocess.run([exe, "-case", resumed] + args, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"mixflowDem {' '.join(args)} failed on {resumed}:\n{r.stdout[-3000:]}")
with open(os.path.join(resumed, "postProcessing", "dem", "timeSeries.csv")) as f:
    again = list(csv.DictReader(ln for ln in f if not ln.startswith("#")))
same = [r == s for r, s in zip(again, lifted)]
check(len(again) == len(lifted) and all(same),
      f"stopped at 0.2 s and resumed: {sum(same)} of {len(lifted)} time-series rows equal the "
      "uninterrupted run's bit for bit")
settled = [foamdict.read_dict(os.path.join(c, "dem", "resume.state"))["settled"]["particles"]
           for c in (held_case, lifted_case, instant_case, default_case)]
check(len(set(settled)) == 1, f"the four runs start from the same settle ({settled[0]} grains)")
if failures:
    sys.exit("FAIL: " + "; ".join(failures))
print("PASS")
