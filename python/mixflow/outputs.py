"""Where a run writes its outputs inside its case directory, and the readers of its time series.

Paths are relative to the case directory. Time series are CSV files with a header row; their
first column is time_s. A value at a time is taken either interpolated linearly between the two
rows around it (interpolated) or from the row nearest to it (nearest): each result script uses
the one its committed numbers were made with.
"""

import csv
import math
import os

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

# Column names the scripts read.
TIME = "time_s"
GRANULAR_FRONT = "front_x_m"  # DEM_SERIES
LIQUID_FRONT = "front_bed_m"  # LIQUID_SERIES: largest x where the bed cell row holds alpha >= 0.5
SECTION_FROUDE = "section_froude"  # LIQUID_SERIES: Fr at paper.SECTION_X (nan below minDepth)


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
