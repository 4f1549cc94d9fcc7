#!/usr/bin/env python3
"""The packing is an input: the W&P sample of the quick and of the reference tier (cases/W+P with
cases/tiers/quick or reference applied as `mixflow suite` applies them; 3 253 grains at E x 1e-4
and 5 420 at E x 1e-3) settles to sample.solidFraction 0.6056 within demDict
settle.packingTolerance 0.003 (demDict settle.packingControl friction, the default).

usage: test_packing_control.py MIXFLOWDEM ROOT WORKDIR

Checks, each with its tolerance and reason:
  1. each tier's sample fraction N V_p / (L W h) (dem/settled.state sampleFraction, the measure the
     control steers) within 0.003 of the case's sample.solidFraction: the issue's requirement, the
     tolerance Li & Zhao's 0.6056 is given to (without the control the same samples come out at
     0.629 (quick) and 0.606 (reference));
  2. the sample records the protocol: packingControl friction, packingTolerance 0.003, the
     settling friction found inside [minFriction, maxFriction] and the settles it took, at most
     maxSettles;
  3. negative control: the quick tier with a single settle allowed (settle.maxSettles 1) at
     settle.friction 0.7 (0.569 on the reference tier, far outside 0.003) stops the preparation
     (exit status 1) naming the achieved fraction, the target and demDict settle.maxSettles, and
     writes no settled sample.
The reference tier's sample is the full 0.12 m slice of the suite (about 50 s of CPU for one
settle on this machine), so the test costs 2-4 minutes serially.
"""
import os
import re
import subprocess
import sys

exe, root, work = (os.path.abspath(a) for a in sys.argv[1:4])
os.environ["MIXFLOW_BUILD"] = os.path.dirname(os.path.dirname(exe))
from mixflow import foamdict  # noqa: E402
from mixflow.commands import suite  # noqa: E402
from mixflow.synthcase import checker  # noqa: E402

failures = []
check = checker(failures)
TOL = 0.003  # settle.packingTolerance's default, the issue's ±0.003


def tier_copy(tier, name, sets=()):
    """ROOT/cases/W+P with ROOT/cases/tiers/TIER set as `mixflow suite` sets it, in WORK/NAME."""
    t = suite.Tier(os.path.join(root, "cases", "tiers", tier))
    t.set_entries(list(sets))
    d = os.path.join(work, name)
    suite.copy_at_tier("W+P", t, d)
    return d


def settle(case):
    r = subprocess.run([exe, "-case", case, "-settleOnly"], capture_output=True, text=True)
    with open(os.path.join(case, "log.mixflowDem"), "w") as f:
        f.write(r.stdout + r.stderr)
    return r


os.makedirs(work, exist_ok=True)
for tier in ("quick", "reference"):
    case = tier_copy(tier, tier)
    r = settle(case)
    if r.returncode != 0:
        sys.exit(f"mixflowDem -settleOnly failed on {case}:\n{r.stdout[-3000:]}{r.stderr[-2000:]}")
    for line in r.stdout.splitlines():
        if line.startswith("[dem] packing control") or line.startswith("[dem] settled in"):
            print(f"{tier}: {line}")
    target = float(foamdict.read_dict(os.path.join(case, "constant", "sceneProperties"))
                   ["sample"]["solidFraction"])
    st = foamdict.read_dict(os.path.join(case, "dem", "settled.state"))["settled"]
    settle_dict = foamdict.read_dict(os.path.join(case, "system", "demDict")).get("settle", {})
    phi = float(st["sampleFraction"])
    check(abs(phi - target) <= TOL,
          f"{tier}: sample fraction {phi:.4f} within {TOL} of sample.solidFraction {target}")
    friction, settles = float(st["settleFriction"]), int(st["settles"])
    lo = float(settle_dict.get("minFriction", 0))
    hi = float(settle_dict.get("maxFriction", 1))
    check(st["packingControl"] == "friction" and float(st["packingTolerance"]) == TOL and
          lo <= friction <= hi and 1 <= settles <= 6,
          f"{tier}: recorded packingControl {st['packingControl']}, tolerance "
          f"{st['packingTolerance']}, settling friction {friction:.4f} in [{lo}, {hi}], "
          f"{settles} settle(s) (at most maxSettles 6)")

case = tier_copy("quick", "quick_one_settle",
                 ["demDict.settle.maxSettles=1", "demDict.settle.friction=0.7"])
r = settle(case)
msg = r.stderr + r.stdout
achieved = re.search(r"gave (0\.\d+) after 1 settles", msg)
check(r.returncode == 1 and achieved is not None and "sample.solidFraction 0.6056" in msg and
      "settle.maxSettles" in msg and
      not os.path.exists(os.path.join(case, "dem", "settled.state")),
      f"one settle at friction 0.7 stops the preparation (exit {r.returncode}) naming the achieved "
      f"fraction ({achieved.group(1) if achieved else 'none'}), the target 0.6056 and "
      "settle.maxSettles, with no settled sample written")
if r.returncode != 1:
    print(msg[-3000:])

sys.exit(1 if failures else 0)
