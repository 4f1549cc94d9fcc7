#!/usr/bin/env python3
"""mixflowExtract pairs particle snapshots with solved fluid times: the t = 0 fluid write (the unsolved initial state, p = -rho g y) is never averaged, and each
solved fluid time goes with its nearest snapshot within pairTolerance, so a window averages both
phases at the same instants even when the writes drift apart. Also u_f masked where the bin holds
almost no liquid and p_s masked in empty bins.

The synthetic case (synthcase.drift_case) mimics a coupled run whose writeInterval (0.01 s) is not a
multiple of the CFD step (0.0007 s): the fluid is written at the first CFD step at or after each
multiple of 0.01 s (0.0105, 0.0203, ..., 0.1001 s), the snapshots come every 0.00995 s (a snapshot
period off writeInterval by half a percent), so the two drift apart by up to 0.0009 s and cross the
window boundary at 0.05 s differently: by time alone the first window [0, 0.05) held 6 snapshots and
5 fluid times (the unsolved t = 0 one among them). The fluid written for snapshot k moves at
1.3 u_s(t_k), so only the right pairing gives lambda_u = 1.3 exactly.

usage: test_extract_pairing.py MIXFLOWEXTRACT WORKDIR"""
import math
import os
import sys

import h5py
import numpy as np

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
from mixflow import synthcase as sc  # noqa: E402

exe, work = sys.argv[1], sys.argv[2]
os.makedirs(work, exist_ok=True)
failures = []
check = sc.checker(failures)


def run(case, *extra):
    return sc.run_extract(exe, case, *extra)


snaps = [round(0.00995 * k, 10) for k in range(11)]
fluid = [0.0] + [round(math.ceil(0.01 * k / 0.0007 - 1e-9) * 0.0007, 10) for k in range(1, 11)]
partners = [0.0] + snaps[1:]
print("snapshots  ", snaps)
print("fluid times", fluid)

# 1. Drifting writes, every pair within the default pairTolerance (0.1 writeInterval = 0.001 s).
case = os.path.join(work, "drift")
sc.drift_case(case, snaps, fluid, partners)
rc, out = run(case)
print(out)
check(rc == 0, "drifting case extracts")
check("t = 0 s is the initial state" in out and "warning" not in out,
      "the t = 0 fluid write is said to be left out; no warning")
h5 = os.path.join(case, "postProcessing/mixture/mixture.h5")
with h5py.File(h5, "r") as f:
    w = f["windows"]
    ns, nf = list(w["n_snapshots"][:]), list(w["n_fluid_times"][:])
    gaps = w["max_pair_gap"][:] if "max_pair_gap" in w else None
    check(ns == [5, 5] and nf == [5, 5], f"paired: snapshots {ns}, fluid times {nf} (by time alone: [6, 5], [5, 5])")
    check(list(w["t_first_snapshot"][:]) == [snaps[1], snaps[6]] and "t_first_fluid" in w
          and list(w["t_first_fluid"][:]) == [fluid[1], fluid[6]] and list(w["t_last_fluid"][:]) == [fluid[5], fluid[10]],
          "window 1 pairs 0.00995-0.04975 s with 0.0105-0.0504 s; window 2 ends with 0.0995 s - 0.1001 s")
    check(gaps is not None and np.allclose(gaps, [0.0008, 0.0009], rtol=0, atol=1e-9), f"max_pair_gap {gaps} s")
    vu, vw = f["masks/valid_lambda_u"][:], f["masks/valid_lambda_w"][:]
    lu, lw = f["fields/lambda_u"][:], f["fields/lambda_w"][:]
    err = max(np.max(np.abs(lu[vu == 1] - 1.3)), np.max(np.abs(lw[vw == 1] - 1.3)))
    check(vu[:, :2, :].all() and vw[:, :2, :].all() and err < 1e-12,
          f"lambda_u = lambda_w = 1.3 in every mixture bin (worst error {err:.2e})")
    print(f"lambda_u over the mixture bins: {lu[:, :2, :].min():.6f} .. {lu[:, :2, :].max():.6f}")
    pf = f["fields/p_f"][:, :2, :]
    check(np.abs(pf - 500).max() < 1e-9, f"p_f = 500 Pa, the solved pressure (worst {np.abs(pf - 500).max():.2e} Pa)")
    lp, ps = f["fields/lambda_p_raw"][:, :2, :], f["fields/p_s"][:, :2, :]
    check(np.allclose(lp, 500 / ps, rtol=1e-12) and np.all(lp > 0),
          f"lambda_p_raw = p_f / p_s > 0 in the first window ({lp[0].min():.4f} to {lp[0].max():.4f})")
    check("t = 0 write" in f.attrs.get("fluid_times", "") and f.attrs.get("pair_tolerance_s") == 0.001
          and "solved fluid time" in w.attrs["rule"],
          "metadata: fluid_times and /windows rule state the solved-times-only pairing, pair_tolerance_s 0.001")
    # Item 4: the top row (no particles, VOF smear alpha = 5e-8 in air at 7.9 m/s).
    uf, sat, reasons = f["fields/u_f"][:], f["fields/saturation"][:], f["masks/reasons"][:]
    print(f"top row: saturation {sat[0, 2, 0]:.3g}, u_f {uf[0, 2, 0]} m/s; p_s {f['fields/p_s'][0, 2, 0]} Pa")
    check(np.allclose(sat[:, 2, :], 5e-8, rtol=1e-9) and np.isnan(uf[:, 2, :]).all()
          and (f["masks/valid_u_f"][:, 2, :] == 0).all() and ((reasons[:, 2, :] & 2048) != 0).all(),
          "u_f masked (NaN, little_liquid bit 2048) at saturation 5e-8, where the air moves at 7.9 m/s")
    check(f["masks/reasons"].attrs.get("bit_2048", "").startswith("little_liquid")
          and f.attrs.get("threshold_min_liquid_share") == 0.01, "little_liquid described, threshold 0.01 stored")
    check("valid_p_s" in f["masks"] and np.isnan(f["fields/p_s"][:, 2, :]).all()
          and (f["masks/valid_p_s"][:, 2, :] == 0).all() and (f["masks/valid_p_s"][:, :2, :] == 1).all()
          and list(w["n_valid_p_s"][:]) == [12, 12],
          "p_s masked (NaN) in the empty top row, valid in the 12 bins holding particles")

# 2. One fluid write far from its snapshot (0.083 s instead of 0.0805 s): warned by name, left out.
moved = list(fluid)
moved[8] = 0.083
case2 = os.path.join(work, "moved")
sc.drift_case(case2, snaps, moved, partners)
rc, out = run(case2)
print("\n".join(ln for ln in out.splitlines() if "warning" in ln))
check(rc == 0 and "warning: window [0.05, 0.1): snapshots t = 0.0796 s have no solved fluid time within "
      "pairTolerance 0.001 s" in out and "nearest solved fluid time 0.083 s, 0.0034 s away" in out
      and "fluid times t = 0.083 s pair with no snapshot" in out,
      "unpaired snapshot and fluid time named in warnings")
with h5py.File(os.path.join(case2, "postProcessing/mixture/mixture.h5"), "r") as f:
    ns, nf = list(f["windows/n_snapshots"][:]), list(f["windows/n_fluid_times"][:])
    lu, vu = f["fields/lambda_u"][:], f["masks/valid_lambda_u"][:]
    check(ns == [5, 4] and nf == [5, 4] and np.max(np.abs(lu[vu == 1] - 1.3)) < 1e-12,
          f"the unpaired instants are left out: {ns} snapshots, {nf} fluid times, lambda_u still 1.3")
rc, out = run(case2, "-check", "-output", "other")
check(rc == 0 and "window [0.05, 0.1): 4 snapshots, 4 fluid times" in out
      and not os.path.exists(os.path.join(case2, "other.h5")), "-check lists the paired counts, writes nothing")

# 3. A listed window whose only snapshot (t = 0) has no solved fluid partner: input error, nothing
#    written.
case3 = os.path.join(work, "list_t0")
sc.drift_case(case3, snaps, fluid, partners, extract_dict=(
    "grid { x (0 0.3 6); y (0 0.18 3); }\nwindows { list ((0 0.005) (0.005 0.05)); }\nfluid { source openfoam; }\n"))
rc, out = run(case3)
print(out.strip().splitlines()[-1])
check(rc == 2 and "windows.list" in out and "1st pair" in out and "t = 0 s" in out and "pairTolerance 0.001 s" in out
      and "allowed range [0, 0.005] s" in out and not os.path.exists(os.path.join(case3, "postProcessing/mixture")),
      "listed window without a solved fluid partner: input error naming entry, times and range; nothing written")

print(f"{len(failures)} failure(s)")
sys.exit(1 if failures else 0)
