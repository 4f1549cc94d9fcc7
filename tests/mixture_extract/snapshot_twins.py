"""Checks of a case mixflowDem wrote: every snapshot has its binary twin (python/mixflow/outputs.py
layout) holding the VTK's positions, mixflowExtract reads the twins, and its HDF5 equals the one
extracted from the VTK files alone. The VTK's POINTS are float32 (relative rounding at most 2^-24)
written with 6 significant digits (at most 5e-6 more), so positions agree within 5e-6 + 2^-24
relative and every extracted number within 1e-4 of its
dataset's largest magnitude (sums of rounded values; a cancelling sum such as the shear stress,
about a tenth of its terms, amplifies their rounding about tenfold: measured 2e-5), masks and
window counts exactly. The
particle-sample counts (a sphere counts in every bin it reaches) are the exception: a settled
column's stacked spheres have their surfaces on the bin planes within that rounding, so a bin's
count may move by 2 at most and all of them by 1 % of the total.

Run as a script, it makes such a case with 2 MPI ranks (the settled column of tests/collapse/column,
0.02 s after the gate opens, x slabs balanced so both ranks hold particles) and checks that each
binary snapshot holds two non-empty rank chunks that mixflowExtract reads as the VTK's particles;
then runs that case again in serial with demDict binarySnapshots off: no .bin is left (the earlier
run's would be read instead of the new VTK files) and the extractor reads the VTK files.

usage: snapshot_twins.py MIXFLOWDEM MIXFLOWEXTRACT COLUMN_CASE WORKDIR"""
import os
import re
import shutil
import subprocess

import sys

import h5py
import numpy as np

from mixflow import observables, outputs  # noqa: E402
from mixflow.synthcase import checker  # noqa: E402


def _extract(exe, case):
    r = subprocess.run([exe, "-case", case, "-overwrite"], capture_output=True, text=True)
    m = re.search(r"(\d+) snapshots read \((\d+) binary\)", r.stdout)
    return r.returncode, (int(m.group(1)), int(m.group(2))) if m else None, r.stdout + r.stderr


def _datasets(path):
    out = {}
    with h5py.File(path, "r") as f:
        f.visititems(lambda n, o: out.__setitem__(n, o[()]) if isinstance(o, h5py.Dataset) else None)
    return out


# float32 POINTS (2^-24) printed with 6 significant digits (5e-6), both relative.
POINT_ROUNDING = 5e-6 + 2.0 ** -24


def check_twins(exe, case, check):
    """CHECK(cond, what) for each check; needs the case's system/extractDict."""
    snaps = observables.vtk_series(case)
    check(len(snaps) > 0, f"{len(snaps)} snapshots listed")
    for t, vtk in snaps:
        bin_path = os.path.splitext(vtk)[0] + ".bin"
        if not os.path.isfile(bin_path):
            check(False, f"binary twin {bin_path} written")
            continue
        rows = outputs.read_binary_snapshot(bin_path)
        pts = observables.vtk_points(vtk)
        c = outputs.SNAPSHOT_COLUMNS
        xyz = rows[:, c.index("x"):c.index("z") + 1]
        err = np.max(np.abs(xyz - pts) / np.maximum(np.abs(xyz), 1e-12)) if len(pts) else 0.0
        check(len(rows) == len(pts) and err <= POINT_ROUNDING,
              f"t = {t}: {len(rows)} binary rows, positions within {err:.3e} relative of the VTK's "
              f"(tolerance {POINT_ROUNDING:.3e})")
    rc, counts, log = _extract(exe, case)
    check(rc == 0 and counts is not None and counts[0] > 0 and counts[1] == counts[0],
          f"mixflowExtract read the binary snapshots (read, binary: {counts})")
    h5 = os.path.join(case, "postProcessing/mixture/mixture.h5")
    from_bin = _datasets(h5)
    hidden = os.path.join(case, "binary-snapshots-aside")
    os.makedirs(hidden, exist_ok=True)
    for _, vtk in snaps:
        shutil.move(os.path.splitext(vtk)[0] + ".bin", hidden)
    rc, counts2, log2 = _extract(exe, case)
    check(rc == 0 and counts2 == (counts[0], 0), f"without them it reads the VTK files ({counts2})")
    from_vtk = _datasets(h5)
    check(from_bin.keys() == from_vtk.keys(), f"same {len(from_bin)} datasets from both forms")
    worst, where, unequal, moved, total = 0.0, "", [], 0, 0
    for name in sorted(from_bin.keys() & from_vtk.keys()):
        a, b = np.asarray(from_bin[name]), np.asarray(from_vtk[name])
        if name.endswith("particle_samples"):
            # A grain centre within the VTK's rounding of a bin edge changes bin: at most 2 per
            # bin. A region's count is a sum over its bins (their flips add up), so regions are
            # held to the total's 1 % below, not to the per-bin 2.
            diff = np.abs(a - b)
            if diff.max(initial=0) > 2 and not name.startswith("regions/"):
                unequal.append(name)
            moved, total = moved + diff.sum(), total + np.abs(a).sum()
        elif a.dtype.kind != "f":
            if not np.array_equal(a, b):
                unequal.append(name)
        elif not np.array_equal(np.isnan(a), np.isnan(b)):
            unequal.append(name + " (NaN places)")
        elif np.any(np.isfinite(a)) and np.nanmax(np.abs(a)) > 0:
            d = np.nanmax(np.abs(a - b)) / np.nanmax(np.abs(a))
            if d > worst:
                worst, where = d, name
    check(not unequal, f"masks, window counts, NaN places equal; bin sample counts within 2 a bin "
          f"(differing: {unequal or 'none'})")
    check(moved <= 0.01 * total, f"particle-sample counts moved by {moved:g} of {total:g} "
          f"(tolerance 1 %)")
    check(worst <= 1e-4, f"HDF5 from binary vs VTK: largest difference {worst:.1e} of the dataset's "
          f"scale ({where or 'none'}; tolerance 1e-4)")
    for name in os.listdir(hidden):
        shutil.move(os.path.join(hidden, name), os.path.join(case, "VTK/particles"))
    os.rmdir(hidden)


def run_short_column(dem, column, case, ranks=1):
    """mixflowDem on a copy of COLUMN at CASE until 0.02 s after the gate opens (snapshots at 0
    and 0.02 s; with RANKS > 1 on x slabs balanced by particles), with an extractDict of 2 d bins
    and one window at t = 0. Exits on a failed run. Returns CASE."""
    if os.path.exists(case):
        shutil.rmtree(case)
    shutil.copytree(column, case)
    ctrl = os.path.join(case, "system/controlDict")
    text = re.sub(r"endTime [^;]*;", "endTime 0.02;", open(ctrl).read())
    open(ctrl, "w").write(re.sub(r"writeInterval [^;]*;", "writeInterval 0.02;", text))
    cmd = [dem, "-case", case]
    if ranks > 1:
        with open(os.path.join(case, "system/demDict"), "a") as f:
            f.write(f'processors "{ranks} 1 1";\nbalanceInterval 0.01;\n')
        cmd = ["mpirun", "--oversubscribe", "-np", str(ranks)] + (
            ["--allow-run-as-root"] if os.geteuid() == 0 else []) + cmd + ["-parallel"]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        print(r.stdout, r.stderr)
        sys.exit(1)
    with open(os.path.join(case, "system/extractDict"), "w") as f:
        f.write("grid { x (0 0.24 10); y (0 0.192 8); }\nwindows { list ((0 0.01)); }\n")
    return case


if __name__ == "__main__":
    dem_exe, extract_exe, column_case, workdir = sys.argv[1:5]
    failures = []
    check = checker(failures)
    case2 = run_short_column(dem_exe, column_case, os.path.join(workdir, "column2"), ranks=2)
    for t, vtk in observables.vtk_series(case2):
        sizes = [len(p) for p in outputs.binary_snapshot_chunks(os.path.splitext(vtk)[0] + ".bin")]
        check(len(sizes) == 2 and min(sizes) > 0, f"t = {t}: rank chunks of {sizes} particles")
    check_twins(extract_exe, case2, check)
    demdict = os.path.join(case2, "system/demDict")
    text = open(demdict).read().replace('processors "2 1 1";', "") + "binarySnapshots off;\n"
    open(demdict, "w").write(text)
    r = subprocess.run([dem_exe, "-case", case2], capture_output=True, text=True)
    left = [n for n in os.listdir(os.path.join(case2, "VTK/particles")) if n.endswith(".bin")]
    check(r.returncode == 0 and not left, f"binarySnapshots off: run exit {r.returncode}, "
          f".bin files left {left}")
    rc, counts, _ = _extract(extract_exe, case2)
    check(rc == 0 and counts is not None and counts[1] == 0, f"then the VTK files are read ({counts})")
    print(f"{len(failures)} failure(s)")
    sys.exit(1 if failures else 0)
