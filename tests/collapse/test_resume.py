#!/usr/bin/env python3
"""A dry run stopped early continues with `mixflowDem -resume` from its last restart state.

Checks (exact, not statistical): the resumed time series joins the first part without a gap or a
duplicate (times strictly increasing, steps of sampleInterval within 1 %), it reaches the new endTime,
and particles are conserved (remaining + deleted + lost = settled count); summary.json's
runout_final_m is the largest granular front over the last arrestWindow of the whole series minus L.
And the resumed run is the
uninterrupted one: every row equal to 1e-9 relative (LIGGGHTS reads its restart bit for bit, and the
uninterrupted run sets up again after each restart write, as the resumed one does after reading it).
Without a set-up after each restart write the uninterrupted run would go on on stale neighbour lists
and this check would fail (LiggghtsSession::writeRestart).

On RANKS > 1 (mpirun, the DEM's x slabs re-balanced every 0.05 s by default) the resumed run
starts from the stopped run's slabs, atom order and re-balance count, and the same 1e-9 holds.

usage: test_resume.py MIXFLOWDEM WORKDIR [RANKS]"""
import csv
import json
import os
import re
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
exe, work = sys.argv[1], sys.argv[2]
ranks = int(sys.argv[3]) if len(sys.argv) > 3 else 1
# mpirun's flags as scripts/RunFunctions' mpiFlags (more ranks than cores on a small machine).
launch = (["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(ranks), exe]
          if ranks > 1 else [exe])
parallel = ["-parallel"] if ranks > 1 else []
case = os.path.join(work, "case")
if os.path.exists(work):
    shutil.rmtree(work)
shutil.copytree(os.path.join(HERE, "column"), case)
control = os.path.join(case, "system", "controlDict")


def set_end(t):
    text = open(control).read()
    text = re.sub(r"endTime\s+[^;]+;", f"endTime {t};", text)
    text = re.sub(r"writeInterval\s+[^;]+;", "writeInterval 0.1;", text)
    open(control, "w").write(text)


def run(*extra):
    res = subprocess.run(launch + ["-case", case] + parallel + list(extra), capture_output=True,
                         text=True)
    print(res.stdout[-800:], res.stderr[-800:])
    if res.returncode != 0:
        sys.exit(f"mixflowDem {' '.join(extra)} failed ({res.returncode})")


# The uninterrupted run, in a copy of the case.
whole = os.path.join(work, "whole")
shutil.copytree(os.path.join(HERE, "column"), whole)
set_end(0.45)
shutil.copy(control, os.path.join(whole, "system", "controlDict"))
res = subprocess.run(launch + ["-case", whole] + parallel, capture_output=True, text=True)
if res.returncode != 0:
    sys.exit(f"the uninterrupted run failed ({res.returncode}): {res.stderr[-800:]}")

set_end(0.25)
run()
set_end(0.45)
run("-resume")
rows = list(csv.DictReader(open(os.path.join(case, "postProcessing", "dem", "timeSeries.csv"))))
times = [float(r["time_s"]) for r in rows]
gaps = [b - a for a, b in zip(times, times[1:])]
summary = json.load(open(os.path.join(case, "postProcessing", "dem", "summary.json")))
dt_sample = 0.02
failures = []
if min(gaps) <= 0:
    failures.append(f"time not strictly increasing (min step {min(gaps)})")
if max(gaps) > 1.01 * dt_sample:
    failures.append(f"gap in the time series: {max(gaps):.5f} s > {dt_sample} s")
if abs(times[-1] - 0.45) > 1e-3:
    failures.append(f"resumed run ended at {times[-1]} s, not 0.45 s")
load = list(csv.DictReader(open(os.path.join(case, "postProcessing", "dem", "rankLoad.csv"))))
if [r["time_s"] for r in load] != [r["time_s"] for r in rows for _ in range(ranks)]:
    failures.append("rankLoad.csv does not continue with the time series (a row a sample and rank)")
total = summary["particles_remaining"] + summary["deleted_outlet"] + summary["deleted_top"] + summary["lost"]
if total != summary["settled"]["particles"]:
    failures.append(f"particles not conserved: {total} != {summary['settled']['particles']}")
# The final runout is the largest front over the last arrestWindow (default 0.25 s) of the whole
# series, the resumed part and the first part together: robust to the tip detaching at the end.
L = float(re.search(r"sample\s*\{[^}]*\blength\s+([0-9.eE+-]+);",
                    open(os.path.join(case, "constant", "sceneProperties")).read()).group(1))
expect = max(float(r["front_x_m"]) for r in rows if float(r["time_s"]) >= times[-1] - 0.25 - 1e-9) - L
if abs(summary["runout_final_m"] - expect) > 1e-9 or summary["runout_final_m"] < summary["runout_m"] - 1e-12:
    failures.append(f"runout_final_m {summary['runout_final_m']} is not the largest front of the last "
                    f"0.25 s minus L ({expect}), or below runout_m {summary['runout_m']}")
print(f"final runout {summary['runout_final_m']:.6g} m (last sample's {summary['runout_m']:.6g} m)")
ref = list(csv.DictReader(open(os.path.join(whole, "postProcessing", "dem", "timeSeries.csv"))))
worst = 0.0
for a, b in zip(ref, rows):
    for k in a:
        if a[k] == b[k]:  # also both empty (no Savage number where the section is dry)
            continue
        if not a[k] or not b[k]:
            worst = float("inf")
            continue
        x, y = float(a[k]), float(b[k])
        worst = max(worst, abs(x - y) / max(abs(x), abs(y), 1e-30))
if len(ref) != len(rows) or worst > 1e-9:
    failures.append(f"the resumed run differs from the uninterrupted one: {len(rows)} against "
                    f"{len(ref)} rows, largest relative difference {worst:.3g} (> 1e-9)")
print(f"resumed against uninterrupted: {len(rows)}/{len(ref)} rows, largest relative difference {worst:.3g}")
print(f"{len(rows)} rows from {times[0]} to {times[-1]} s, steps {min(gaps):.5f}..{max(gaps):.5f} s, "
      f"particles {total}/{summary['settled']['particles']}")
print("\n".join("FAIL: " + f for f in failures) or "PASS")
sys.exit(1 if failures else 0)
