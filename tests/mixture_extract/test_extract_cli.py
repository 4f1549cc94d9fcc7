#!/usr/bin/env python3
"""mixflowExtract end to end on a synthetic coupled-like case on disk:
particles in mixflowDem's snapshot format moving at u_s(t), w_s(t) uniform in space, the fluid
as OpenFOAM ASCII time directories (the format mixflowCoupled writes) at u_f = 1.3 u_s,
w_f = 1.3 w_s, liquid up to y = 0.1 m (air above).

Checks: lambda_u = lambda_w = 1.3 to 1e-12 through the files; every field has units and meaning;
root attributes carry the version and the case parameters; masked entries are NaN exactly where
the mask is 0 and the reason bits say why (unsaturated top row); the XDMF references datasets of
the right shape; the tidy CSV; a still-running case defers its incomplete window and a re-run on
the grown case appends only the new window, leaving the old data bit for bit; a stale temporary
file from a killed run is ignored; a failing run leaves the previous file untouched; the t = 0 fluid
write (unsolved) is left out; a changed window width or start is refused without -overwrite; windows
after the end of the case are warned about (some) or refused (all).

usage: test_extract_cli.py MIXFLOWEXTRACT WORKDIR"""
import csv
import hashlib
import math
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
from mixflow import synthcase as sc  # noqa: E402

exe, work = sys.argv[1], sys.argv[2]
case = os.path.join(work, "coupled")
if os.path.exists(case):
    shutil.rmtree(case)
os.makedirs(case)
failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        failures.append(what)


def run(*extra):
    r = subprocess.run([exe, "-case", case, *extra], capture_output=True, text=True)
    return r.returncode, r.stdout + r.stderr


L, H, W, d, rho = 0.3, 0.12, 0.06, 0.012, 2500.0
sc.scene(case, L=L, H=H, W=W, d=d, end_time=0.1, write_interval=0.01, content="particles")
sc.write(os.path.join(case, "system/extractDict"),
         "grid { x (0 0.3 6); y (0 0.12 3); }\n"
         "windows { start 0; end 0.1; width 0.05; }\n"
         "fluid { source openfoam; }\n"
         "liquidDensity 1000;\n"
         "regions { all { x (0 0.3); y (0 0.12); } lower { x (0 0.3); y (0 0.08); } }\n")
x = sc.jittered_lattice(L, H, W, d)
n = len(x)
r = np.full(n, d / 2)
m = rho * np.pi / 6 * d**3 * np.ones(n)
U = lambda t: 0.4 + 0.3 * math.sin(7 * t)  # noqa: E731
Wv = lambda t: -0.05 - 0.02 * math.cos(5 * t)  # noqa: E731

# Fluid cells: 12 x 6 over [0, 0.3] x [0, 0.12], one cell across the width.
cx, cy = np.meshgrid((np.arange(12) + 0.5) * 0.025, (np.arange(6) + 0.5) * 0.02)
C = np.column_stack([cx.ravel(), cy.ravel(), np.full(cx.size, W / 2)])
Vc = np.full(len(C), 0.025 * 0.02 * W)
alpha = (C[:, 1] < 0.1).astype(float)


def add_time(k):
    t = round(0.01 * k, 10)
    v = np.column_stack([np.full(n, U(t)), np.full(n, Wv(t)), np.zeros(n)])
    c = -200.0 * np.pi / 6 * d**3
    s = np.column_stack([c - m * v[:, 0]**2, c - m * v[:, 1]**2, np.full(n, c), -m * v[:, 0] * v[:, 1],
                         np.zeros(n), np.zeros(n)])  # contact + LAMMPS kinetic term -m v v
    sc.vtk(os.path.join(case, f"VTK/particles/particles_{100 * k}.vtk"), x, v, m, r, s)
    Uf = np.column_stack([np.full(len(C), 1.3 * U(t)), np.full(len(C), 1.3 * Wv(t)), np.zeros(len(C))])
    sc.foam_time(case, "%g" % t, C, Vc, Uf, np.full(len(C), 500.0), alpha, np.full(len(C), 0.45))
    return (f"particles/particles_{100 * k}.vtk", t)


# Stage 1: a running case with snapshots up to t = 0.05.
entries = [add_time(k) for k in range(6)]
sc.series(case, entries)
rc, out = run()
print(out)
check(rc == 0, "stage 1 runs")
check("1 new windows" in out and "1 waiting for data" in out, "incomplete window deferred")
h5 = os.path.join(case, "postProcessing/mixture/mixture.h5")
with h5py.File(h5, "r") as f:
    check(f["windows/t0"].shape == (1,), "one window written")
    old = {k: f["fields/" + k][0].tobytes() for k in f["fields"]}

# Stage 2: the case grew and finished.
entries += [add_time(k) for k in range(6, 10)]
sc.series(case, entries)
sc.finish(case)
rc, out = run()
print(out)
check(rc == 0 and "1 new windows, 1 already in the file" in out, "grown case: only the new window appended")
rc, out = run()
check(rc == 0 and "0 new windows, 2 already in the file" in out, "re-run: nothing to add")

with h5py.File(h5, "r") as f:
    nw = f["windows/t0"].shape[0]
    check(nw == 2 and list(f["windows/t0"][:]) == [0.0, 0.05], "windows t0 = [0, 0.05]")
    check(all(f["fields/" + k][0].tobytes() == old[k] for k in old), "old window unchanged bit for bit")
    # The t = 0 fluid write is the unsolved initial state: left out, and with it the t = 0 snapshot
    # (no solved partner), so both phases are averaged at the same instants.
    check(list(f["windows/n_snapshots"][:]) == [4, 5] and list(f["windows/n_fluid_times"][:]) == [4, 5]
          and list(f["windows/t_first_fluid"][:]) == [0.01, 0.05] and list(f["windows/max_pair_gap"][:]) == [0, 0],
          "4 + 5 paired snapshots and fluid times (t = 0 left out), pairs 0 s apart")
    ny, nx = 3, 6
    for name, ds in f["fields"].items():
        check(ds.shape == (nw, ny, nx) and ds.attrs.get("units") is not None and len(ds.attrs["meaning"]) > 10,
              f"field {name}: shape (2, 3, 6), units '{ds.attrs.get('units')}'")
    a = f.attrs
    check(len(a["mixflow_version"]) > 0 and a["sample_width_m"] == W and a["particle_density_kg_m3"] == rho
          and "grid" in a["extract_dict"] and a["stress_kinetic_term"] == "included",
          f"root attributes (version {a['mixflow_version']}, case parameters, settings)")
    lam = f["fields/lambda_u"][:]
    valid = f["masks/valid_lambda_u"][:]
    reasons = f["masks/reasons"][:]
    check(np.array_equal(np.isnan(lam), valid == 0), "lambda_u is NaN exactly where masked")
    lower = valid[:, :2, :]
    err_u = np.max(np.abs(lam[valid == 1] - 1.3))
    lw = f["fields/lambda_w"][:]
    err_w = np.max(np.abs(lw[f["masks/valid_lambda_w"][:] == 1] - 1.3))
    check(lower.all() and err_u < 1e-12 and err_w < 1e-12,
          f"lambda_u = lambda_w = 1.3 in every saturated bin (worst errors {err_u:.2e}, {err_w:.2e})")
    top = reasons[:, 2, :]
    check((valid[:, 2, :] == 0).all() and ((top & 16) != 0).all(),
          "top row (half air): masked with reason 'unsaturated' (bit 16)")
    check(f["masks/reasons"].attrs["bit_16"].startswith("unsaturated"), "reason bits described")
    check(list(f["windows/n_masked_unsaturated"][:]) == [6, 6] and list(f["windows/n_valid_lambda_u"][:]) == [12, 12],
          "per-window counts: 6 unsaturated bins, 12 valid lambda_u")
    sat = f["fields/saturation"][0]
    check(abs(sat[2, 0] - 0.5) < 1e-12, f"saturation of the top row = 0.5 ({sat[2, 0]:.3f})")
    ps = f["fields/p_s"][0]
    check(np.allclose(ps, 200 * f["fields/alpha_s"][0], rtol=1e-9, atol=1e-9),
          "p_s = 200 Pa x alpha_s (contact part; LAMMPS kinetic term removed)")
    check(f["counts/particle_samples"][0].min() > 0 and f["counts/fluid_samples"][0, 0, 0] == 4 * 4,
          "sample counts stored (4 cells per bin x 4 times)")
    reg = f["regions/lower"]
    check(abs(reg["lambda_u"][0] - 1.3) < 1e-12 and reg["valid_lambda_u"][0] == 1, "region 'lower': lambda_u = 1.3")
    check(reg["valid_lambda_u"][0] == 1 and f["regions/all/valid_lambda_u"][0] == 0,
          "region 'all' (includes the unsaturated row): masked")

# XDMF: every HDF item exists with the stated dimensions.
xdmf = h5.replace(".h5", ".xdmf")
tree = ET.parse(xdmf)
items = [e for e in tree.iter("DataItem") if e.get("Format") == "HDF"]
ok = len(items) > 0
with h5py.File(h5, "r") as f:
    for e in items:
        fn, path = e.text.strip().split(":")
        dims = tuple(int(v) for v in e.get("Dimensions").split())
        ok = ok and fn == "mixture.h5" and path in f and f[path].shape == dims
times = [float(t.get("Value")) for t in tree.iter("Time")]
check(ok and np.allclose(times, [0.025, 0.075], rtol=1e-12), f"XDMF: {len(items)} HDF references valid, times {times}")

# Tidy CSV.
rows = list(csv.DictReader(open(h5.replace(".h5", "_regions.csv"))))
cols = ["region", "t0_s", "t1_s", "t_mid_s", "quantity", "unit", "value", "valid", "mask_reasons", "snapshots",
        "fluid_times", "particle_samples", "fluid_samples"]
lam_rows = [r for r in rows if r["quantity"] == "lambda_u" and r["region"] == "lower"]
check(list(rows[0].keys()) == cols and len(lam_rows) == 2 and all(abs(float(r["value"]) - 1.3) < 1e-9 for r in lam_rows),
      f"CSV: {len(rows)} tidy rows, lambda_u(lower) = 1.3")
check(all(r["value"] == "" for r in rows if r["valid"] == "0"), "CSV: masked values left empty")

# A stale temporary file from a killed run is ignored and removed.
sc.write(h5 + ".tmp", "garbage from a killed run")
rc, out = run()
check(rc == 0 and not os.path.exists(h5 + ".tmp"), "stale .tmp ignored and removed")

# A run that fails half way (a corrupt snapshot in the 2nd window) leaves the file untouched.
digest = hashlib.sha256(open(h5, "rb").read()).hexdigest()
snap = os.path.join(case, "VTK/particles/particles_700.vtk")
good = open(snap).read()
open(snap, "w").write(good[: len(good) // 2])
rc, out = run("-overwrite")
print(out.strip().splitlines()[-1])
check(rc == 2 and "particles_700.vtk" in out, "truncated snapshot: input error naming the file")
check(hashlib.sha256(open(h5, "rb").read()).hexdigest() == digest and not os.path.exists(h5 + ".tmp"),
      "failed run left the previous file untouched and no temporary file")
open(snap, "w").write(good)

# A changed window width without -overwrite is refused before anything is written, naming the
# file, the entry and the stored width (appending would interleave two widths in one series).
digest = hashlib.sha256(open(h5, "rb").read()).hexdigest()
dict_path = os.path.join(case, "system/extractDict")
good_dict = open(dict_path).read()
open(dict_path, "w").write(good_dict.replace("width 0.05;", "width 0.025;"))
for extra in ([], ["-check"]):
    rc, out = run(*extra)
    print(out.strip().splitlines()[-1])
    check(rc == 2 and "mixture.h5" in out and "windows.width" in out and "width 0.05 s" in out
          and "now 0.025 s" in out and "-overwrite" in out,
          f"changed width{' (-check)' if extra else ''}: refused, naming file, entry, stored 0.05 s and new 0.025 s")
check(hashlib.sha256(open(h5, "rb").read()).hexdigest() == digest and not os.path.exists(h5 + ".tmp"),
      "changed width: file untouched")
open(dict_path, "w").write(good_dict.replace("start 0;", "start 0.01;"))
rc, out = run()
check(rc == 2 and "windows.start" in out and "from 0 s" in out, "changed start: refused, naming the entry")
# Windows after the end of a finished case: a warning naming them (some), an input error (all).
open(dict_path, "w").write(good_dict.replace("end 0.1;", "end 0.2;"))
rc, out = run("-output", "after_end")
print("\n".join(ln for ln in out.splitlines() if "warning" in ln))
check(rc == 0 and "warning: 2 windows in [0.1, 0.2) s start after the last snapshot (t = 0.09 s)" in out,
      "windows after the case's end: warned with their range and the last snapshot")
open(dict_path, "w").write(good_dict.replace("start 0; end 0.1;", "start 0.5; end 0.6;"))
rc, out = run("-output", "after_end2")
print(out.strip().splitlines()[-1])
check(rc == 2 and "windows.start" in out and "every window" in out and "[0, 0.09)" in out
      and not os.path.exists(os.path.join(case, "after_end2.h5")),
      "every window after the case's end: input error naming windows.start and its range, nothing written")
open(dict_path, "w").write(good_dict)

print(f"{len(failures)} failure(s)")
sys.exit(1 if failures else 0)
