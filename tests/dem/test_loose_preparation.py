#!/usr/bin/env python3
"""A loose sample is reachable: W&P's column of the reference tier (cases/W+P with
cases/tiers/reference applied as `mixflow suite` applies them, E x 1e-3) settled by
`mixflow viscous-packing`'s loose preparation (viscous_packing.LOOSE: the grain count of a 0.55
sample, friction 2 and the grains' rolling friction 0.1 while settling, a drag holding every grain
below 0.1 m/s, demDict settle.sedimentationSpeed) comes to rest looser than the grains' critical
packing, and the same column settled by sliding friction alone does not.

usage: test_loose_preparation.py MIXFLOWDEM ROOT WORKDIR

Checks, each with its tolerance and reason:
  1. the loose preparation settles (dem/settled.state converged yes) to a bulk fraction below
     phi_c - 0.002 = 0.5633: phi_c = 0.5653 the grains' critical packing in steady plane shear
     (results/critical_packing), 0.002 its systematic uncertainty from the wall zone, so the
     sample is loose by the measurement, not within its error;
  2. negative control: the same entries without the rolling friction and the drag (sliding
     friction 2 alone) give a bulk fraction above phi_c: friction alone does not hold a pile
     looser than the critical state (results/critical_packing, "Preparing a loose sample":
     0.569-0.576 at friction 1-2).
Two settles of about 5 000 grains at E x 1e-3: a few minutes serially.
"""
import os
import subprocess
import sys

exe, root, work = (os.path.abspath(a) for a in sys.argv[1:4])
os.environ["MIXFLOW_BUILD"] = os.path.dirname(os.path.dirname(exe))
from mixflow import foamdict  # noqa: E402
from mixflow.commands import suite  # noqa: E402
from mixflow.commands.viscous_packing import LOOSE, PHI_C  # noqa: E402
from mixflow.synthcase import checker  # noqa: E402

failures = []
check = checker(failures)
MARGIN = 0.002  # results/critical_packing: phi_c's systematic uncertainty (wall zone)


def settled(name, sets):
    """cases/W+P at the reference tier with SETS, settled in WORK/NAME: its settled.state."""
    t = suite.Tier(os.path.join(root, "cases", "tiers", "reference"))
    t.set_entries(list(sets))
    d = os.path.join(work, name)
    suite.copy_at_tier("W+P", t, d)
    r = subprocess.run([exe, "-case", d, "-settleOnly"], capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"mixflowDem -settleOnly failed on {d}:\n{r.stdout[-3000:]}{r.stderr[-2000:]}")
    print(f"{name}: " + next(ln for ln in r.stdout.splitlines() if ln.startswith("[dem] settled in")))
    return foamdict.read_dict(os.path.join(d, "dem", "settled.state"))["settled"]


os.makedirs(work, exist_ok=True)
loose = settled("loose", LOOSE)
phi = float(loose["bulkFraction"])
check(loose["converged"] == "yes" and phi < PHI_C - MARGIN,
      f"loose preparation: bulk fraction {phi:.4f} below phi_c - {MARGIN} = {PHI_C - MARGIN:.4f}, "
      f"settled (converged {loose['converged']})")
sliding = settled("sliding_friction", [s for s in LOOSE if "sedimentationSpeed" not in s and
                                         "rollingFriction" not in s])
phi_sliding = float(sliding["bulkFraction"])
check(phi_sliding > PHI_C,
      f"sliding friction 2 alone: bulk fraction {phi_sliding:.4f} above phi_c {PHI_C}")
sys.exit(1 if failures else 0)
