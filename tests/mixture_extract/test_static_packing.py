#!/usr/bin/env python3
"""Granular pressure on a real LIGGGHTS packing: the settled column of tests/collapse/column (about 1700
beads of 12 mm, periodic width, softened 7 MPa) at the gate opening, t = 0, from mixflowDem's own
snapshot (positions, c_pstress from compute stress/atom: the virial route of particles.stress, as
the run writes no contact snapshots; extract.contact_stress has the contact-line route). On bins
of 2 d in the column's interior (x in [d.., 0.216] m, away from the back wall and the gate):
  - the vertical normal stress -sigma_yy of rows 1-5 equals the weight of the material above the
    bin centre, rho_s g int alpha_s dy (from the extracted alpha_s, averaged over the columns),
    within 5 % (measured: about 1 %; the rest of the weight goes to the back wall and the gate by
    friction and to sampling noise of one snapshot);
  - p_s = -tr(sigma)/3 equals that weight within 15 % (p_s = (1 + K_x + K_z)/3 x weight with the
    packing's lateral stress ratios K, printed; about 0.9 here);
  - the floor row is short by the floor contacts' share: LIGGGHTS' wall/gran has no per-atom virial,
    so the bottom bin misses (r / dy) x (floor stress); -sigma_yy there equals weight - (r / dy) x
    floor stress within 5 %;
  - the run wrote a binary twin of each snapshot, which mixflowExtract reads, and the HDF5 equals
    the one extracted from the VTK files within their text rounding (snapshot_twins.py).

usage: test_static_packing.py MIXFLOWDEM MIXFLOWEXTRACT COLUMN_CASE WORKDIR"""
import os
import subprocess
import sys

import h5py
import numpy as np

from mixflow.synthcase import checker  # noqa: E402
from snapshot_twins import check_twins, run_short_column  # noqa: E402

dem, exe, column, work = sys.argv[1:5]
case = run_short_column(dem, column, os.path.join(work, "column"))
r = subprocess.run([exe, "-case", case], capture_output=True, text=True)
print(r.stdout, r.stderr)
if r.returncode != 0:
    sys.exit(1)

rho, g, d = 2500.0, 9.81, 0.012
with h5py.File(os.path.join(case, "postProcessing/mixture/mixture.h5"), "r") as f:
    cols = slice(1, 9)  # x from 0.024 to 0.216 m
    a = f["fields/alpha_s"][0][:, cols].mean(1)
    syy = -f["fields/sigma_s_yy"][0][:, cols].mean(1)
    sxx = -f["fields/sigma_s_xx"][0][:, cols].mean(1)
    szz = -f["fields/sigma_s_zz"][0][:, cols].mean(1)
    ps = f["fields/p_s"][0][:, cols].mean(1)
    dy = f["grid/y_edges"][1] - f["grid/y_edges"][0]
    assert f.attrs["stress_kinetic_term"] == "included"
weight = np.array([(0.5 * a[j] + a[j + 1:].sum()) * dy * rho * g for j in range(len(a))])
floor = a.sum() * dy * rho * g
failures = 0
print(" row  y_c(m)  alpha_s  weight(Pa)  -sigma_yy  ratio   p_s   ratio   K_x   K_z")
for j in range(len(a)):
    print(f"{j:4d}  {(j + 0.5) * dy:.3f}  {a[j]:.3f}  {weight[j]:9.1f}  {syy[j]:9.1f}  {syy[j] / weight[j]:.3f} "
          f"{ps[j]:7.1f}  {ps[j] / weight[j]:.3f}  {sxx[j] / syy[j]:.2f}  {szz[j] / syy[j]:.2f}")
for j in range(1, 6):
    if abs(syy[j] / weight[j] - 1) > 0.05:
        print(f"FAIL row {j}: -sigma_yy / weight = {syy[j] / weight[j]:.3f} (tolerance 5 %)")
        failures += 1
    if abs(ps[j] / weight[j] - 1) > 0.15:
        print(f"FAIL row {j}: p_s / weight = {ps[j] / weight[j]:.3f} (tolerance 15 %)")
        failures += 1
expected0 = weight[0] - (d / 2) / dy * floor
ok0 = abs(syy[0] / expected0 - 1) < 0.05
print(f"{'ok  ' if ok0 else 'FAIL'} floor row: -sigma_yy {syy[0]:.1f} Pa vs weight - (r/dy) floor stress "
      f"= {weight[0]:.1f} - {(d / 2) / dy * floor:.1f} = {expected0:.1f} Pa (ratio {syy[0] / expected0:.3f})")
failures += not ok0
twin_failures = []
check_twins(exe, case, checker(twin_failures))
failures += len(twin_failures)
print(f"{failures} failure(s)")
sys.exit(1 if failures else 0)
