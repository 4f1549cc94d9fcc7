"""Where a run writes its outputs inside its case directory, the readers of its time series, and
copy_inputs: a case copied without the outputs of a run in it.

Paths are relative to the case directory. Time series are CSV files with a header row; their
first column is time_s. A value at a time is taken either interpolated linearly between the two
rows around it (interpolated) or from the row nearest to it (nearest): each result script uses
the one its committed numbers were made with.
"""

import csv
import fnmatch
import math
import os
import re
import shutil

POST = "postProcessing"
DEM_SERIES = "postProcessing/dem/timeSeries.csv"  # particle counts, granular front, energies
DEM_SUMMARY = "postProcessing/dem/summary.json"  # settled sample, moduli, runout, stop reason
DEPOSIT = "postProcessing/dem/depositProfile.csv"  # final h(x)
VELOCITY_PROFILE = "postProcessing/dem/velocityProfile.csv"  # u(y) at a section and time
RANK_LOAD = "postProcessing/dem/rankLoad.csv"  # per MPI rank: particles, LIGGGHTS compute/comm s
LIQUID_SERIES = "postProcessing/liquid/timeSeries.csv"  # liquid fronts, depths, Froude number
LIQUID_PROFILES = "postProcessing/liquid/profiles.csv"
EXCHANGE = "postProcessing/coupling/exchange.csv"  # fluid-particle exchange, one row an exchange
DONE, FAILED = ".done", ".failed"  # markers scripts/suite.py writes into a run directory
SERIES = {"dem": DEM_SERIES, "liquid": LIQUID_SERIES, "exchange": EXCHANGE}
# What a run writes at its case directory's top level (shell patterns), with the time directories
# other than 0 (is_time_dir), and the state it leaves in dem/ to continue from (mixflowDem -resume:
# resume.state and its restart_N.bin; mixflowCoupled -resume: coupled.resume.state and its
# coupled_N.restart): what copy_inputs leaves behind.
OUTPUT_NAMES = (POST, "VTK", "dem", DONE, FAILED, "log.*", "previous-run.*", "processor*",
                "resume.state", "restart_*", "coupled.resume.state", "coupled_*.restart")

# Column names the scripts read.
TIME = "time_s"
GRANULAR_FRONT = "front_x_m"  # DEM_SERIES
LIQUID_FRONT = "front_bed_m"  # LIQUID_SERIES: largest x where the bed cell row holds alpha >= 0.5
SECTION_FROUDE = "section_froude"  # LIQUID_SERIES: Fr at paper.SECTION_X (nan below minDepth)


def is_time_dir(name):
    """NAME reads as a number and is not 0: a time directory a run wrote (0 holds the inputs)."""
    return re.fullmatch(r"[0-9.eE+-]+", name) is not None and name != "0"


def _named(name, patterns):
    return any(fnmatch.fnmatchcase(name, p) for p in patterns)


def copy_inputs(src, dst, keep=()):
    """SRC's inputs into DST (which must not exist): a run's outputs at SRC's top level
    (OUTPUT_NAMES, time directories other than 0) are left behind, except those KEEP names (names
    or shell patterns). A kept directory comes without the outputs inside it (its logs and resume
    state at any depth): keep=("dem",) takes a settled sample along, not the state to continue that
    run. Other directories (system/, constant/, 0/) are copied whole. Returns DST."""
    top = os.path.normpath(os.fspath(src))

    def ignore(d, names):
        rel = os.path.relpath(d, top)
        if rel == os.curdir:
            return [n for n in names
                    if (is_time_dir(n) or _named(n, OUTPUT_NAMES)) and not _named(n, keep)]
        first = rel.split(os.sep)[0]
        if _named(first, OUTPUT_NAMES) or is_time_dir(first):  # a kept output directory
            return [n for n in names if _named(n, OUTPUT_NAMES)]
        return []
    return shutil.copytree(src, dst, ignore=ignore)


def read_series(path, comments=False):
    """A CSV time series as a list of dicts of floats (COMMENTS: lines starting with # skipped)."""
    with open(path) as f:
        lines = (line for line in f if not line.startswith("#")) if comments else f
        return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(lines)]


def series(case, which="liquid"):
    """read_series of a case's time series WHICH (a key of SERIES)."""
    return read_series(os.path.join(case, SERIES[which]))


def read_rows(path):
    """CSV (lines starting with # skipped) -> list of dicts of floats (text kept if not a number)."""
    with open(path) as f:
        lines = [ln for ln in f if ln.strip() and not ln.startswith("#")]
    if not lines:
        return []
    keys = lines[0].strip().split(",")
    rows = []
    for ln in lines[1:]:
        vals = ln.strip().split(",")
        if len(vals) != len(keys):
            continue  # a row being written
        row = {}
        for k, v in zip(keys, vals):
            try:
                row[k] = float(v)
            except ValueError:
                row[k] = math.nan if v == "" else v  # a blank cell: no value at that time
        rows.append(row)
    return rows


def interpolated(rows, key, t):
    """ROWS' KEY at time T, linear between the rows around T (nan outside the series)."""
    for r0, r1 in zip(rows, rows[1:]):
        if r0["time_s"] <= t <= r1["time_s"]:
            w = (t - r0["time_s"]) / (r1["time_s"] - r0["time_s"]) if r1["time_s"] > r0["time_s"] \
                else 0.0
            return (1 - w) * r0[key] + w * r1[key]
    return float("nan")


def nearest(rows, key, t):
    """ROWS' KEY in the row whose time is nearest to T (the first of two as near)."""
    return min(rows, key=lambda r: abs(r["time_s"] - t))[key]


AT = {"interpolate": interpolated, "nearest": nearest}


def at(rows, key, t, method):
    """ROWS' KEY at time T, METHOD 'interpolate' or 'nearest'."""
    return AT[method](rows, key, t)


def write_json(path, obj, indent=1):
    """OBJ as JSON at PATH (its directory made if needed), ending with a newline."""
    import json
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    with open(path, "w") as f:
        json.dump(obj, f, indent=indent)
        f.write("\n")


def write_csv(path, rows):
    """ROWS (dicts with the same keys) as CSV at PATH, a header from the first row's keys."""
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
