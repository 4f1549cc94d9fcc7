#!/usr/bin/env python3
"""The gated water column against the gated experiment: Lobovský et al. (2014), H = 300 mm.

usage: test_lobovsky_gate.py PREPARE SOLVER BLOCKMESH WORKDIR

`mixflow lobovsky-gate --heights 300 --cell 0.01 --end 0.45` (python/mixflow/commands/
lobovsky_gate.py: 2-D, 1 cm cells, the plate lifted at the experiment's median 3.46 m/s and the
instant removal) into WORKDIR. Asserted, over the data whose front is one column height or more
out (x >= H) up to the tank's wall, where the bed-row front is resolved:
  1. the lifted gate's front within 5 % of the measured one (the issue's tolerance; measured
     2.3 %);
  2. the instant gate's is not (measured 7.5 %): the gate's lift is what the 5 % needs.
"""
import csv
import os
import subprocess
import sys

prepare, solver, blockmesh, work = sys.argv[1:5]
TOLERANCE = 0.05
out = os.path.join(work, "out")
r = subprocess.run([sys.executable, "-m", "mixflow", "lobovsky-gate", "--heights", "300",
                    "--cell", "0.01", "--end", "0.45", "--work", work, "--out", out,
                    "--prepare", prepare, "--solver", solver, "--blockmesh", blockmesh],
                   capture_output=True, text=True)
print(r.stdout[-2000:])
if r.returncode != 0:
    sys.exit(f"FAIL: mixflow lobovsky-gate exited {r.returncode}:\n{r.stderr[-3000:]}")
with open(os.path.join(out, "summary.csv")) as f:
    rows = {row["gate"]: row for row in csv.DictReader(f)}
lifted = float(rows["lifted"]["max_abs_err_x_ge_H"])
instant = float(rows["instant"]["max_abs_err_x_ge_H"])
ok = True
for what, value, want in (("lifted", lifted, True), ("instant", instant, False)):
    inside = value <= TOLERANCE
    print(f"{'ok  ' if inside == want else 'FAIL'} {what} gate: largest |x - x_exp| / x_exp over "
          f"x >= H {value:.4f} {'<=' if inside else '>'} {TOLERANCE}")
    ok &= inside == want
if not ok:
    sys.exit("FAIL")
print("PASS")
