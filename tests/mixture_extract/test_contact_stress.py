#!/usr/bin/env python3
"""Coarse-grained stress of mixflowExtract from the contact snapshots on a real LIGGGHTS bed at rest:
the settled column of tests/collapse/column (1707 beads of 12 mm, periodic width, E = 7 MPa) with
frictionless walls (the back wall and the gate carry no weight, so every horizontal slice of the
bed carries all the weight above it), relaxed until its kinetic energy per particle is below
2e-7 m g d, written at the gate opening with demDict contactSnapshots on. From that snapshot:
  - the bed is at rest: the floor's contact forces (VTK/contacts/walls_0.txt) carry the weight
    within 2 % (the premise of the checks below);
  - floor row, exact bins: the bottom row's vertical load over the whole bed, -sum_x sigma_yy dx W,
    equals the weight of the grains above (each grain's share of the row's height, as the
    contact lines are split) within 2 %; the per-particle virial route misses the floor contacts
    there (about 0.7 of the load, printed);
  - sigma_yy(y), exact bins of 1 d and 2 d: every row's load equals the weight above within 2 %,
    and the momentum balance with the snapshot's total forces (weight + m a) within 1e-3: the
    contact-line split is exact;
  - plateau: in the bed's interior (x in (0.06, 0.2) m, y in (0.05, 0.12) m) -sigma_yy, p_s and
    alpha_s vary by less than 2 % over Lucy widths w = 1 ... 3 d and Gaussian widths 1 ... 2 d
    (a Gaussian is cut at 3 w: at 2.5 d it reaches the floor and the surface of this 14 d bed from
    mid-height), and both kernels agree there within 2 %;
  - local momentum balance, Lucy w = 2 d on 1 d bins: d sigma_yy/dy + d sigma_xy/dx = rho_s alpha_s g
    in every interior bin within 5 % of rho_s alpha_s g (central differences over 2 d; measured
    3.2 %, mean 0.9 %).

usage: test_contact_stress.py MIXFLOWDEM MIXFLOWEXTRACT COLUMN_CASE WORKDIR"""
import os
import re
import shutil
import subprocess
import sys

import h5py
import numpy as np

from mixflow import outputs
from mixflow.synthcase import checker

G, W, RHO_S = 9.81, 0.06, 2500.0
INTERIOR_X, INTERIOR_Y = (0.06, 0.2), (0.05, 0.12)


def settled_bed(dem, column, case):
    """The column with frictionless walls, relaxed, snapshots at 0 and 0.002 s with contacts."""
    if os.path.exists(case):
        shutil.rmtree(case)
    shutil.copytree(column, case)

    def edit(name, pattern, repl):
        path = os.path.join(case, name)
        text = re.sub(pattern, repl, open(path).read())
        open(path, "w").write(text)

    edit("system/controlDict", r"endTime [^;]*;", "endTime 0.002;")
    edit("system/controlDict", r"writeInterval [^;]*;", "writeInterval 0.002;")
    edit("system/demDict", r"settle \{[^}]*\}",
         "settle { maxTime 5; packingControl off; kineticTolerance 2e-7; relaxTime 0.3; }")
    edit("system/demDict", r"sampleInterval [^;]*;", "sampleInterval 0.002;")
    edit("constant/sceneProperties", r"particles \{ diameter 0.012; \}",
         "particles { diameter 0.012; wallFriction 0; }")
    with open(os.path.join(case, "system/demDict"), "a") as f:
        f.write("contactSnapshots on;\n")
    r = subprocess.run([dem, "-case", case], capture_output=True, text=True)
    if r.returncode != 0:
        print(r.stdout, r.stderr)
        sys.exit(1)
    return case


def extract(exe, case, name, grid, extra=""):
    with open(os.path.join(case, "system/extractDict"), "w") as f:
        f.write(f"grid {{ {grid} }}\nwindows {{ list ((0 0.001)); }}\n{extra}\n"
                f"output postProcessing/mixture/{name};\n")
    r = subprocess.run([exe, "-case", case, "-overwrite"], capture_output=True, text=True)
    if r.returncode != 0:
        print(r.stdout, r.stderr)
        sys.exit(1)
    return os.path.join(case, f"postProcessing/mixture/{name}.h5")


def row_loads(h5):
    """Per row: the vertical load over the whole bed (N), the row's edges and the kernel."""
    with h5py.File(h5, "r") as f:
        xe, ye = f["grid/x_edges"][()], f["grid/y_edges"][()]
        load = np.nansum(-f["fields/sigma_s_yy"][0] * (xe[1] - xe[0]) * W, axis=1)
        return load, ye


def interior(h5):
    with h5py.File(h5, "r") as f:
        xe, ye = f["grid/x_edges"][()], f["grid/y_edges"][()]
        xc, yc = 0.5 * (xe[1:] + xe[:-1]), 0.5 * (ye[1:] + ye[:-1])
        sel = np.ix_((yc > INTERIOR_Y[0]) & (yc < INTERIOR_Y[1]),
                     (xc > INTERIOR_X[0]) & (xc < INTERIOR_X[1]))
        return {"-sigma_yy": -f["fields/sigma_s_yy"][0][sel].mean(),
                "p_s": f["fields/p_s"][0][sel].mean(),
                "alpha_s": f["fields/alpha_s"][0][sel].mean()}


def balance_residual(h5):
    """Largest |d sigma_yy/dy + d sigma_xy/dx - rho_s alpha_s g| over the interior bins, by central
    differences, as a fraction of the interior's mean rho_s alpha_s g (the static momentum balance
    in y; tension positive, so sigma_yy grows upward by the weight)."""
    with h5py.File(h5, "r") as f:
        xe, ye = f["grid/x_edges"][()], f["grid/y_edges"][()]
        syy, sxy = f["fields/sigma_s_yy"][0], f["fields/sigma_s_xy"][0]
        rho_g = RHO_S * G * f["fields/alpha_s"][0][1:-1, 1:-1]
    res = ((syy[2:, 1:-1] - syy[:-2, 1:-1]) / (ye[2] - ye[0])
           + (sxy[1:-1, 2:] - sxy[1:-1, :-2]) / (xe[2] - xe[0]) - rho_g)
    xc, yc = 0.5 * (xe[2:-1] + xe[1:-2]), 0.5 * (ye[2:-1] + ye[1:-2])
    inside = np.ix_((yc > INTERIOR_Y[0]) & (yc < INTERIOR_Y[1]),
                    (xc > INTERIOR_X[0]) & (xc < INTERIOR_X[1]))
    return np.abs(res[inside]).max() / rho_g[inside].mean()


def main():
    dem, exe, column, work = sys.argv[1:5]
    failures = []
    check = checker(failures)
    case = settled_bed(dem, column, os.path.join(work, "bed"))
    snap = outputs.read_binary_snapshot(os.path.join(case, "VTK/particles/particles_0.bin"))
    c = outputs.SNAPSHOT_COLUMNS
    y, m, fy = snap[:, c.index("y")], snap[:, c.index("mass")], snap[:, c.index("fy")]
    weight = (m * G).sum()

    walls = open(os.path.join(case, "VTK/contacts/walls_0.txt")).read().split("\n")
    start = next(i for i, l in enumerate(walls) if l.startswith("ITEM: ATOMS")) + 1
    floor = sum(float(l.split()[2]) for l in walls[start:] if l.strip())
    check(abs(floor / weight - 1) <= 0.02, f"the floor's contacts carry {floor / weight:.4f} of the "
          f"bed's weight {weight:.3f} N (tolerance 2 %)")

    # Whole-bed rows: x from the back wall past the gate, y to above the surface.
    grids = {"bins 2 d": "x (0 0.264 11); y (0 0.192 8);", "bins 1 d": "x (0 0.264 22); y (0 0.192 16);"}
    for label, grid in grids.items():
        load, ye = row_loads(extract(exe, case, label.replace(" ", ""), grid))
        dy = ye[1] - ye[0]
        print(f"{label}: row  y_c(m)   load(N)  weight above(N)  ratio   with m a")
        worst_w, worst_m = 0.0, 0.0
        for j in range(len(load)):
            share = np.clip((y - ye[j]) / dy, 0, 1)  # a grain's share of the row's height
            above, dyn = (m * G * share).sum(), ((m * G + fy) * share).sum()
            if above < 0.01 * weight:
                continue
            print(f"  {j:3d}  {0.5 * (ye[j] + ye[j + 1]):.3f}  {load[j]:8.4f}  {above:8.4f}  "
                  f"{load[j] / above:.4f}  {load[j] / dyn:.5f}")
            worst_w = max(worst_w, abs(load[j] / above - 1))
            worst_m = max(worst_m, abs(load[j] / dyn - 1))
            if j == 0:
                check(abs(load[0] / above - 1) <= 0.02, f"{label}: floor row carries "
                      f"{load[0] / above:.4f} of the weight above (tolerance 2 %)")
        check(worst_w <= 0.02, f"{label}: sigma_yy(y) = weight above within {worst_w:.2e} "
              f"(tolerance 2 %)")
        check(worst_m <= 1e-3, f"{label}: sigma_yy(y) = momentum balance (weight + m a) within "
              f"{worst_m:.1e} (tolerance 1e-3)")
    load, ye = row_loads(extract(exe, case, "virial", grids["bins 2 d"], "particles { stress virial; }"))
    above0 = (m * G * np.clip((y - ye[0]) / (ye[1] - ye[0]), 0, 1)).sum()
    print(f"virial route (no wall contacts): floor row carries {load[0] / above0:.3f} of the weight above")

    values = {}
    for shape, widths in (("lucy", (0.5, 1, 1.5, 2, 2.5, 3)), ("gaussian", (0.5, 1, 1.5, 2, 2.5, 3))):
        for w in widths:
            name = f"{shape}{w}"
            h5 = extract(exe, case, name, grids["bins 1 d"], f"kernel {{ shape {shape}; width {w}; }}")
            values[(shape, w)] = interior(h5)
            if (shape, w) == ("lucy", 2):
                res = balance_residual(h5)
                check(res <= 0.05, f"Lucy w = 2 d: interior momentum balance residual at most "
                      f"{res:.4f} of rho_s alpha_s g (tolerance 5 %)")
            v = values[(shape, w)]
            print(f"{shape:8s} w = {w:3} d: " + "  ".join(f"{k} {x:9.4f}" for k, x in v.items()))
    plateau = {"lucy": (1, 1.5, 2, 2.5, 3), "gaussian": (1, 1.5, 2)}
    for shape, widths in plateau.items():
        for q in ("-sigma_yy", "p_s", "alpha_s"):
            v = np.array([values[(shape, w)][q] for w in widths])
            spread = v.max() / v.min() - 1
            check(spread <= 0.02, f"{shape}: interior {q} varies by {spread:.4f} over w = "
                  f"{widths[0]} ... {widths[-1]} d (tolerance 2 %)")
    for q in ("-sigma_yy", "p_s", "alpha_s"):
        a, b = values[("lucy", 2)][q], values[("gaussian", 1)][q]
        check(abs(a / b - 1) <= 0.02, f"interior {q}: Lucy w = 2 d {a:.4f}, Gaussian w = 1 d "
              f"{b:.4f} (tolerance 2 %)")
    print(f"{len(failures)} failure(s)")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
