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
import struct

POST = "postProcessing"
DEM_SERIES = "postProcessing/dem/timeSeries.csv"  # particle counts, granular front, energies
DEM_SUMMARY = "postProcessing/dem/summary.json"  # settled sample, moduli, runout, stop reason
DEPOSIT = "postProcessing/dem/depositProfile.csv"  # final h(x)
VELOCITY_PROFILE = "postProcessing/dem/velocityProfile.csv"  # u(y) at a section and time
RANK_LOAD = "postProcessing/dem/rankLoad.csv"  # per MPI rank: particles, LIGGGHTS compute/comm s
LIQUID_SERIES = "postProcessing/liquid/timeSeries.csv"  # liquid fronts, depths, Froude number
LIQUID_PROFILES = "postProcessing/liquid/profiles.csv"
EXCHANGE = "postProcessing/coupling/exchange.csv"  # fluid-particle exchange, one row an exchange
STAGE_TIMES = "postProcessing/coupling/stageTimes.csv"  # wall s per exchange stage, rows as EXCHANGE
DONE, FAILED = ".done", ".failed"  # markers mixflow suite writes into a run directory
SERIES = {"dem": DEM_SERIES, "liquid": LIQUID_SERIES, "exchange": EXCHANGE}
# What a run writes at its case directory's top level (shell patterns), with the time directories
# other than 0 (is_time_dir), and the state it leaves in dem/ to continue from (mixflowDem -resume:
# resume.state and its restart_N.bin; mixflowCoupled -resume: coupled.resume.state and its
# coupled_N.restart): what copy_inputs leaves behind.
OUTPUT_NAMES = (POST, "VTK", "dem", DONE, FAILED, "log.*", "previous-run.*", "processor*",
                "resume.state", "restart_*", "coupled.resume.state", "coupled_*.restart")

# Particle snapshots (the C++ twin is dem/SnapshotFiles.h: keep them consistent). Each one is
# written twice at the same step: legacy VTK ASCII for ParaView (6 significant digits) and, with
# demDict binarySnapshots on, LIGGGHTS' binary dump of the same columns, which mixflowExtract reads.
SNAPSHOT_SERIES = "VTK/particles.vtk.series"  # ParaView index: names relative to VTK/, times
SNAPSHOT_VTK = "VTK/particles/particles_{step}.vtk"
SNAPSHOT_BIN = "VTK/particles/particles_{step}.bin"
SNAPSHOT_COLUMNS = ("id", "type", "x", "y", "z", "vx", "vy", "vz", "fx", "fy", "fz", "omegax",
                    "omegay", "omegaz", "radius", "mass", "c_pstress[1]", "c_pstress[2]",
                    "c_pstress[3]", "c_pstress[4]", "c_pstress[5]", "c_pstress[6]")
# Binary header (native byte order; little-endian on the machines mixflow runs on): step, natoms
# (int64), triclinic (int32), boundary (6 int32), box lo/hi x y z (6 float64), columns, chunks
# (int32); then per chunk (one per MPI rank): int32 count of values, that many float64, row-major.
_BIN_HEAD = struct.Struct("<qqi6i6dii")


def write_binary_snapshot(path, rows, step=0, chunks=1, box=(0, 1, 0, 1, 0, 1)):
    """ROWS (n, len(SNAPSHOT_COLUMNS)) into PATH in the binary layout, split into CHUNKS rank
    chunks as an MPI run writes them."""
    import numpy as np
    rows = np.ascontiguousarray(rows, dtype="<f8")
    with open(path, "wb") as f:
        f.write(_BIN_HEAD.pack(step, len(rows), 0, *[1] * 6, *box, rows.shape[1], chunks))
        for part in np.array_split(rows, chunks):
            f.write(struct.pack("<i", part.size))
            f.write(part.tobytes())


def binary_snapshot_chunks(path):
    """The rank chunks of a binary snapshot, in file order: a list of (rows, columns) arrays."""
    import numpy as np
    with open(path, "rb") as f:
        b = f.read()
    head = _BIN_HEAD.unpack_from(b, 0)
    natoms, triclinic, cols, chunks = head[1], head[2], head[-2], head[-1]
    off = _BIN_HEAD.size + (24 if triclinic else 0)
    parts = []
    for _ in range(chunks):
        (n,) = struct.unpack_from("<i", b, off)
        parts.append(np.frombuffer(b, dtype="<f8", count=n, offset=off + 4).reshape(-1, cols))
        off += 4 + 8 * n
    if sum(len(p) for p in parts) != natoms or off != len(b):
        raise ValueError(f"{path}: the chunks do not hold the header's {natoms} particles")
    return parts


def read_binary_snapshot(path):
    """The rows (n, columns) of a binary snapshot, all chunks in file order."""
    import numpy as np
    parts = binary_snapshot_chunks(path)
    return np.vstack(parts) if parts else np.zeros((0, len(SNAPSHOT_COLUMNS)))


# Column names the scripts read.
TIME = "time_s"
GRANULAR_FRONT = "front_x_m"  # DEM_SERIES
LIQUID_FRONT = "front_bed_m"  # LIQUID_SERIES: largest x where the bed cell row holds alpha >= 0.5
SECTION_FROUDE = "section_froude"  # LIQUID_SERIES: Fr at paper.SECTION_X (nan below minDepth)
PROFILE_X = "x_m"  # LIQUID_PROFILES and DEPOSIT: the cell column's or the bin's centre
PROFILE_DEPTH = "depth_m"  # LIQUID_PROFILES: liquid (bulk model: mixture) volume / column area
PROFILE_SURFACE = "surface_m"  # LIQUID_PROFILES: the same with the pores counted full
DEPOSIT_TOP = "h_top_m"  # DEPOSIT: the mean top of the bin's 2 d wide columns of grains
DEPOSIT_VOLUME = "h_volume_m"  # DEPOSIT: grain volume / (sample solidFraction x W x bin length)


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


def profile_at(case, t):
    """The rows of CASE's LIQUID_PROFILES (read_rows) at the write time nearest T (the first of
    two as near), in the file's order (x increasing)."""
    rows = read_rows(os.path.join(case, LIQUID_PROFILES))
    tn = min({r[TIME] for r in rows}, key=lambda v: (abs(v - t), v))
    return [r for r in rows if r[TIME] == tn]


def deposit(case):
    """The rows of CASE's DEPOSIT (read_rows): the final h(x) of a DEM run, x increasing."""
    return read_rows(os.path.join(case, DEPOSIT))


# A run stops up to a DEM step short of its endTime: its last row then stands for a time at most
# this far (s) past it, and no farther.
END_TOLERANCE_S = 1e-3


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
