#!/usr/bin/env python3
"""A sample settled softened and then stiffened (demDict settle.stiffenFrom 1e-2, as the paper
tier, in the default 10 steps of 0.01 s) is the sample a settle at the paper's stiffness makes,
on the tiny column of tests/dem/stiffen_column (241 grains, E = 70/700 GPa, same loose fill).

usage: test_stiffened_settle.py MIXFLOWDEM ROOT WORKDIR

Checks, each with its tolerance and reason:
  1. after stiffening LIGGGHTS runs at the full moduli: the Hertz forces of the settled positions
     at 70 GPa give LIGGGHTS' own contact virial within 1e-4 (measured within 2e-6; the static
     forces have no damping part; at E x 1e-2 the ratio would be 100^(1/3) = 4.6), for both
     samples; and the stiffened sample's mean overlap is the full one's within 15 % (measured
     1-10 %; overlap ~ E^(-2/3): 21x larger if the last steps did not take);
  2. the settled column against the full-stiffness one, within tolerances set by
     results/bench/stiffened_settle_tiny.json (3 seeds of this column): height within 0.25 d
     (measured at most 0.07 d; the full settle's seed-to-seed spread 0.19 d), sample solid
     fraction within 1.5 % (measured at most 0.7 %; spread 2 %), bulk fraction within 2.5 %
     (at most 1.5 %), coordination number within 0.2 (at most 0.075), mean normal contact force
     over m g within 20 % (at most 13 %; spread 9.5 %), bottom load within 0.2 of the weight (at
     most 0.11: wall friction holds part of the column's swelling as the overlaps shrink).
The cost of each settle is measured by bench/stiffened_settle.py, not here.
"""
import json
import os
import shutil
import subprocess
import sys

exe, root, work = sys.argv[1], os.path.abspath(sys.argv[2]), os.path.abspath(sys.argv[3])
# contacts.settled_stats takes the declared defaults from this build's mixflowSchema.
os.environ["MIXFLOW_BUILD"] = os.path.dirname(os.path.dirname(os.path.abspath(exe)))
from mixflow import contacts, foamdict  # noqa: E402
from mixflow.synthcase import checker  # noqa: E402

failures = []
check = checker(failures)
D = 0.024


def settle(name, stiffen):
    case = os.path.join(work, name)
    shutil.rmtree(case, ignore_errors=True)
    shutil.copytree(os.path.join(root, "tests", "dem", "stiffen_column"), case)
    if stiffen:
        foamdict.edit_file(os.path.join(case, "system", "demDict"),
                           {"settle": {"stiffenFrom": "1e-2"}})
    r = subprocess.run([exe, "-case", case], capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"mixflowDem failed on {case}:\n{r.stdout[-2000:]}{r.stderr[-2000:]}")
    stats = contacts.settled_stats(case)
    print(name, json.dumps(stats))
    return stats


os.makedirs(work, exist_ok=True)
full = settle("full", False)
stiff = settle("stiffened", True)

for name, s in (("full", full), ("stiffened", stiff)):
    check(s["converged"], f"{name}: the settle converged")
    check(abs(s["virial_ratio"] - 1) < 1e-4,
          f"{name}: Hertz forces at 70 GPa / LIGGGHTS contact virial = {s['virial_ratio']:.6f} (1 +- 1e-4)")
check(abs(stiff["overlap_mean_over_d"] / full["overlap_mean_over_d"] - 1) < 0.15,
      f"mean overlap stiffened/full = {stiff['overlap_mean_over_d'] / full['overlap_mean_over_d']:.3f} (1 +- 0.15)")
dh = (stiff["height_m"] - full["height_m"]) / D
check(abs(dh) < 0.25, f"height difference {dh:+.3f} d (within 0.25 d)")
for key, tol in (("sample_solid_fraction", 0.015), ("bulk_solid_fraction", 0.025),
                 ("force_mean_over_mg", 0.20)):
    rel = stiff[key] / full[key] - 1
    check(abs(rel) < tol, f"{key}: {stiff[key]:.4f} against {full[key]:.4f} ({100 * rel:+.2f} %, within {100 * tol:g} %)")
dz = stiff["coordination_pairs"] - full["coordination_pairs"]
check(abs(dz) < 0.2, f"coordination number {stiff['coordination_pairs']:.3f} against {full['coordination_pairs']:.3f} (within 0.2)")
db = stiff["bottom_load_over_weight"] - full["bottom_load_over_weight"]
check(abs(db) < 0.2, f"bottom load / weight {stiff['bottom_load_over_weight']:.3f} against {full['bottom_load_over_weight']:.3f} (within 0.2)")
print(f"{len(failures)} failed" if failures else "all passed")
sys.exit(1 if failures else 0)
