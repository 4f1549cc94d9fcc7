#!/usr/bin/env python3
"""A dry run stopped early continues with `mixflowDem -resume` from its last restart state.

Checks (exact, not statistical): the resumed time series joins the first part without a gap or a
duplicate (times strictly increasing, steps of sampleInterval within 1 %), it reaches the new endTime,
and particles are conserved (remaining + deleted + lost = settled count). DEM trajectories are chaotic,
so the runout itself is not compared: a restart re-orders atoms, which changes round-off.

usage: test_resume.py MIXFLOWDEM WORKDIR"""
import csv
import json
import os
import re
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
exe, work = sys.argv[1], sys.argv[2]
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
    res = subprocess.run([exe, "-case", case] + list(extra), capture_output=True, text=True)
    print(res.stdout[-800:], res.stderr[-800:])
    if res.returncode != 0:
        sys.exit(f"mixflowDem {' '.join(extra)} failed ({res.returncode})")


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
total = summary["particles_remaining"] + summary["deleted_outlet"] + summary["deleted_top"] + summary["lost"]
if total != summary["settled"]["particles"]:
    failures.append(f"particles not conserved: {total} != {summary['settled']['particles']}")
print(f"{len(rows)} rows from {times[0]} to {times[-1]} s, steps {min(gaps):.5f}..{max(gaps):.5f} s, "
      f"particles {total}/{summary['settled']['particles']}")
print("\n".join("FAIL: " + f for f in failures) or "PASS")
sys.exit(1 if failures else 0)
