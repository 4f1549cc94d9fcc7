#!/usr/bin/env python3
"""Small dry column collapse run through mixflowDem (serial, or with mpirun).

usage: run_column.py MIXFLOWDEM WORKDIR RANKS
Copies tests/collapse/column to WORKDIR, runs it, prints and returns summary.json."""
import json
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


def run(exe, work, ranks, dem_entries=""):
    """DEM_ENTRIES: lines appended to the copy's system/demDict."""
    if os.path.exists(work):
        shutil.rmtree(work)
    shutil.copytree(os.path.join(HERE, "column"), work)
    if dem_entries:
        with open(os.path.join(work, "system", "demDict"), "a") as f:
            f.write(dem_entries + "\n")
    cmd = [exe, "-case", work]
    if ranks > 1:
        cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(ranks)] + cmd + ["-parallel"]
    res = subprocess.run(cmd, capture_output=True, text=True)
    sys.stdout.write(res.stdout[-3000:])
    sys.stderr.write(res.stderr[-3000:])
    if res.returncode != 0:
        sys.exit(f"mixflowDem failed with exit code {res.returncode}")
    return json.load(open(os.path.join(work, "postProcessing", "dem", "summary.json")))


if __name__ == "__main__":
    s = run(sys.argv[1], sys.argv[2], int(sys.argv[3]))
    print(json.dumps(s, indent=1))
