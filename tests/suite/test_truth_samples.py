#!/usr/bin/env python3
"""The truth tier's shipped settled samples (samples/truth) start its mixtures without settling.

usage: test_truth_samples.py WORKDIR   (the build's bin/ from MIXFLOW_BUILD, else ROOT/build)

For each mixture of Table 1 (W&P, HB&P, B&P), exact checks:
  1. the tier names a shipped sample and it is there (settled.state, .restart, .entries, .inputs);
  2. a fresh truth-tier copy accepts it: `mixflowDem -check -settleOnly -reuse` finds the copy's
     settling inputs identical to the sample's by fingerprint (the check mixflow suite makes before
     it passes the sample to Allrun);
  3. the sample holds what the tier promises: settled, at the paper's stiffness (settled.entries
     youngModulusFactor 1), a sample solid fraction within the packing control's 0.003 of the
     case's sample.solidFraction;
  4. a copy whose settling inputs differ (--set demDict.settle.friction=0.3, or the settle's own
     step, demDict.settle.rayleighFraction=0.2) is refused with the entry named, so the suite
     settles afresh instead;
  5. a copy whose collapse runs at another DEM step (demDict.rayleighFraction=0.2) accepts it: the
     settle keeps its own step (settle.rayleighFraction), so one sample serves a DEM-step ladder.
"""
import os
import shutil
import sys

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
from mixflow.commands import suite  # noqa: E402
from mixflow import foamdict  # noqa: E402

failures = []
TOLERANCE = 0.003  # demDict settle.packingTolerance: the packing control's band


def check(cond, what):
    failures.extend([] if cond else [what])
    print(("ok   " if cond else "FAIL ") + what)


def entry(path, name):
    for line in open(path):
        parts = line.split()
        if len(parts) >= 3 and parts[0] == "system/demDict" and parts[1] == name:
            return parts[2]
    return None


work = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else "/tmp/test_truth_samples")
shutil.rmtree(work, ignore_errors=True)
tier = suite.Tier("truth")
check(tier.settled_samples is not None, f"tier truth names its shipped samples ({tier.settled_samples})")
for scene in ("W+P", "HB+P", "B+P"):
    p = suite.plan_scene(scene, os.path.join(work, "fit"), tier, 1)
    sample = p.get("shipped")
    files = [os.path.join(sample or "", f"settled.{x}") for x in ("state", "restart", "entries", "inputs")]
    check(sample is not None and all(os.path.isfile(f) for f in files),
          f"{scene}: shipped sample planned and complete ({sample})")
    if not sample:
        continue
    suite.make_copy(p["scene"], p["run_dir"], tier, p["texts"], p["records"], p["content"])
    fits, why = suite.shipped_sample_fits(p["run_dir"], sample)
    check(fits, f"{scene}: a fresh truth-tier copy accepts it ({why})")
    state = foamdict.read_dict(files[0])["settled"]
    phi = float(state["sampleFraction"])
    target = float(foamdict.read_dict(os.path.join(p["run_dir"], "constant", "sceneProperties"))
                   ["sample"]["solidFraction"])
    check(state["converged"] == "yes" and entry(files[2], "youngModulusFactor") == "1"
          and abs(phi - target) <= TOLERANCE,
          f"{scene}: settled at E x 1, sample fraction {phi:.4f} within {TOLERANCE} of {target}")
    for n, (entry_set, accepted, named) in enumerate((
            ("demDict.settle.friction=0.3", False, "friction"),
            ("demDict.settle.rayleighFraction=0.2", False, "timestep"),
            ("demDict.rayleighFraction=0.2", True, ""))):
        t2 = suite.Tier("truth")
        t2.set_entries([entry_set])
        q = suite.plan_scene(scene, os.path.join(work, f"set{n}"), t2, 1)
        suite.make_copy(q["scene"], q["run_dir"], t2, q["texts"], q["records"], q["content"])
        fits, why = suite.shipped_sample_fits(q["run_dir"], sample)
        check(fits == accepted and named in why,
              f"{scene}: a copy with {entry_set} {'accepts' if accepted else 'refuses'} it ({why})")

print(f"{len(failures)} failed" if failures else "all checks passed")
sys.exit(1 if failures else 0)
