"""A scene's record: what the report reads of a finished run (observables.Scene), in the run's
own layout, small enough to commit (a few hundred kB).

A long study then advances a scene at a time across sessions and machines: each finished run is
recorded into the repository, and the report is made from records and runs alike
(results/li_zhao_2018/make.sh). A record keeps
- the run's dictionaries (system/ and constant/ files, not the mesh) and its .done marker;
- the short outputs whole: the DEM time series, summary, deposit and velocity profiles; the
  liquid's surface profiles with their numbers to DIGITS significant digits;
- the liquid time series and the exchange log (one row per exchange) thinned to the first row
  of each STEP_S, with the last row, numbers to DIGITS;
- of the particle snapshots nearest each of paper.PROFILE_TIMES, the grains that make the
  granular surface (observables.surface_grains: the same surface as the full snapshot).
"""

import math
import os
import shutil

from . import outputs
from .observables import surface_grains, vtk_points, vtk_series
from .paper import PROFILE_TIMES

# Rows kept of the thinned series: one per step, the step at least STEP_S and long enough that
# a series keeps at most MAX_ROWS rows. An event read from a thinned series (an arrival, the
# Froude rule's subcritical time) moves by up to one step: 2 ms in a 3 s scene, where the report
# quotes times to 0.01 s.
STEP_S = {outputs.LIQUID_SERIES: 0.002, outputs.EXCHANGE: 0.01}
MAX_ROWS = 2000
DIGITS = 7  # significant digits of the rewritten series' numbers (relative change 5e-8)
WHOLE = (outputs.DONE, outputs.DEM_SERIES, outputs.DEM_SUMMARY, outputs.DEPOSIT,
         outputs.VELOCITY_PROFILE)
ROUNDED = (outputs.LIQUID_PROFILES,)  # every row, numbers to DIGITS
THINNED = tuple(STEP_S)  # thinned (STEP_S, MAX_ROWS), numbers to DIGITS
DICTIONARY_DIRS = ("system", "constant")
RECORD = "record.json"  # what was recorded from where
SNAPSHOT_SURFACE_X_M = 4.0  # the report's granular surfaces span 0-4 m


def rounded(line):
    """A CSV row with its numbers written to DIGITS significant digits (text kept)."""
    def one(v):
        try:
            return f"{float(v):.{DIGITS}g}"
        except ValueError:
            return v
    return ",".join(one(v) for v in line.rstrip("\n").split(",")) + "\n"


def thinned_lines(path, step):
    """thinned(the lines of CSV time series PATH, STEP)."""
    with open(path) as f:
        return thinned(f.readlines(), step)


def thinned(lines, step):
    """The LINES of a CSV time series ('#' comments and the header kept) whose time (first column)
    is the first of its interval of length max(STEP, its span / MAX_ROWS), with the last row; a
    row cut short by a stopped run is left out."""
    head = [ln for ln in lines if ln.startswith("#")]
    body = [ln for ln in lines if ln.strip() and not ln.startswith("#")]
    if not body:
        return head
    header, rows = body[0], body[1:]
    width = header.count(",")
    rows = [ln for ln in rows if ln.count(",") == width and ln.endswith("\n")]
    if rows:
        span = float(rows[-1].split(",", 1)[0]) - float(rows[0].split(",", 1)[0])
        step = max(step, span / MAX_ROWS)
    kept, last_slot = [], None
    for ln in rows:
        slot = math.floor(float(ln.split(",", 1)[0]) / step + 1e-9)
        if slot != last_slot:
            kept.append(ln)
            last_slot = slot
    if rows and (not kept or kept[-1] is not rows[-1]):
        kept.append(rows[-1])
    return head + [header] + [rounded(ln) for ln in kept]


def write_surface_snapshot(path, points):
    """POINTS (n, 3) as a legacy VTK point set that ParaView opens and observables.vtk_points
    reads."""
    with open(path, "w") as f:
        f.write("# vtk DataFile Version 2.0\nmixflow record: the grains of the granular surface\n"
                f"ASCII\nDATASET POLYDATA\nPOINTS {len(points)} float\n")
        for p in points:
            f.write(" ".join(f"{v:.6g}" for v in p) + "\n")


def record_snapshots(case, out, times=PROFILE_TIMES):
    """The surface grains of CASE's snapshots nearest each of TIMES into OUT's VTK/ with their
    series file (nothing where CASE has no snapshots)."""
    snaps = vtk_series(case)
    if not snaps:
        return
    chosen = sorted({min(snaps, key=lambda e: abs(e[0] - t)) for t in times})
    os.makedirs(os.path.join(out, os.path.dirname(outputs.SNAPSHOT_VTK)), exist_ok=True)
    files = []
    for t, path in chosen:
        rel = os.path.relpath(path, os.path.join(case, "VTK"))
        write_surface_snapshot(os.path.join(out, "VTK", rel),
                               surface_grains(vtk_points(path), SNAPSHOT_SURFACE_X_M))
        files.append({"name": rel, "time": t})
    outputs.write_json(os.path.join(out, outputs.SNAPSHOT_SERIES),
                       {"file-series-version": "1.0", "files": files})


def record_scene(case, out, scale=1.0):
    """CASE's record into OUT (replaced if it exists), the thinning steps STEP_S x SCALE, with
    record.json (the source, the steps). CASE must be a finished run (its .done marker); returns
    {relative path: bytes} of the files written."""
    if not os.path.isfile(os.path.join(case, outputs.DONE)):
        raise ValueError(f"{case}: not a finished run (no {outputs.DONE}); a record is made of a "
                         "finished one")
    if os.path.isdir(out):
        shutil.rmtree(out)
    for d in DICTIONARY_DIRS:
        src = os.path.join(case, d)
        for name in sorted(os.listdir(src)) if os.path.isdir(src) else []:
            if os.path.isfile(os.path.join(src, name)):
                os.makedirs(os.path.join(out, d), exist_ok=True)
                shutil.copy2(os.path.join(src, name), os.path.join(out, d, name))
    for rel in WHOLE + ROUNDED + THINNED:
        src, dst = os.path.join(case, rel), os.path.join(out, rel)
        if not os.path.isfile(src):
            continue
        os.makedirs(os.path.dirname(dst), exist_ok=True)
        if rel in WHOLE:
            shutil.copy2(src, dst)
            continue
        if rel in THINNED:
            lines = thinned_lines(src, STEP_S[rel] * scale)
        else:
            with open(src) as f:
                lines = [ln if ln.startswith("#") else rounded(ln) for ln in f if ln.strip()]
        with open(dst, "w") as f:
            f.writelines(lines)
    record_snapshots(case, out)
    outputs.write_json(os.path.join(out, RECORD), {
        "source": os.path.abspath(case), "thinned_step_s": {k: v * scale for k, v in STEP_S.items()},
        "max_rows": MAX_ROWS, "digits": DIGITS, "snapshot_times_s": list(PROFILE_TIMES)})
    return file_sizes(out)


def file_sizes(out):
    """{path relative to OUT: bytes} of every file under OUT."""
    return {os.path.relpath(os.path.join(d, n), out): os.path.getsize(os.path.join(d, n))
            for d, _, names in os.walk(out) for n in names}

