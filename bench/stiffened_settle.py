#!/usr/bin/env python3
"""Benchmark: a sample settled softened and then stiffened (demDict settle.stiffenFrom) against
one settled at the full stiffness, on the same loose fill (same seed): CPU of each settle and the
settled sample of each -- height, solid fractions, coordination number, normal contact forces
over m g (mean, p10, p50, p90) and the share of the weight the bottom carries -- for several
seeds, so that the stiffened-minus-full difference can be set beside the seed-to-seed spread of
the full-stiffness settle itself.

The scene is the grains of a case (default cases/W+P-quick: 808 grains of 24 mm in a 3 d
periodic slice) as a dry scene at youngModulusFactor 1 (E = 70/700 GPa), DEM step auto
(0.1 T_R); each run settles and stops one sample interval after the gate opens, so its first
snapshot (particles_0.bin) is the settled sample (python/mixflow/contacts.py reads it).

usage: stiffened_settle.py [--case DIR] [--seeds 12345,2] [--stiffen-from 1e-3]
                           [--steps 10] [--step-time 0.01] [--json OUT] [--work DIR] [--bin DIR]
                           [--reuse]
"""
import argparse
import json
import os
import shutil
import sys

sys.dont_write_bytecode = True
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
from mixflow.timing import timed  # noqa: E402
from mixflow import contacts, foamdict  # noqa: E402

COMPARED = ("height_m", "sample_solid_fraction", "bulk_solid_fraction", "coordination_pairs",
            "force_mean_over_mg", "force_p10_over_mg", "force_p50_over_mg", "force_p90_over_mg",
            "bottom_load_over_weight")


def make_case(base, dst, seed, stiffen):
    """A dry copy of BASE's grains at full stiffness, stopping at the first sample interval (an
    earlier run's outputs in DST stay: run() reuses them only for the same inputs)."""
    shutil.rmtree(os.path.join(dst, "constant"), ignore_errors=True)
    os.makedirs(os.path.join(dst, "system"), exist_ok=True)
    shutil.copytree(os.path.join(base, "constant"), os.path.join(dst, "constant"),
                    ignore=lambda d, names: [n for n in names if n != "sceneProperties"])
    sp = os.path.join(dst, "constant", "sceneProperties")
    foamdict.edit_file(sp, {"content": "particles"}, note="bench")
    text = open(sp).read()
    start = text.find("\nliquid")
    if start >= 0:  # a dry scene has no liquid block
        end = text.index("\n}", text.index("{", start)) + 2
        open(sp, "w").write(text[:start] + text[end:])
    with open(os.path.join(dst, "system", "controlDict"), "w") as f:
        f.write("FoamFile { version 2.0; format ascii; class dictionary; object controlDict; }\n"
                "endTime 0.01;\nwriteInterval 0.01;\n")
    settle = f"friction 0.1; maxTime 3; seed {seed};"
    if stiffen:
        settle += (f" stiffenFrom {stiffen['from']}; stiffenSteps {stiffen['steps']};"
                   f" stiffenStepTime {stiffen['time']};")
    with open(os.path.join(dst, "system", "demDict"), "w") as f:
        f.write("FoamFile { version 2.0; format ascii; class dictionary; object demDict; }\n"
                "youngModulusFactor 1;\ntimeStep auto;\nsampleInterval 0.01;\n"
                f"settle {{ {settle} }}\n")
    return dst


def run(exe, case, reuse):
    """The settled sample's statistics and the run's wall and CPU seconds; with REUSE, those an
    earlier run of the very same inputs left in CASE/stats.json."""
    record = os.path.join(case, "stats.json")
    inputs = "".join(open(os.path.join(case, *p)).read() for p in
                     (("constant", "sceneProperties"), ("system", "demDict")))
    if reuse and os.path.isfile(record):
        old = json.load(open(record))
        if old.get("inputs") == inputs:
            return old["stats"]
    wall, cpu = timed([exe, "-case", case], cwd=case)
    stats = contacts.settled_stats(case)
    stats.update({"wall_s": round(wall, 2), "cpu_s": round(cpu, 2)})
    with open(record, "w") as f:
        json.dump({"inputs": inputs, "stats": stats}, f)
    return stats


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--case", default=os.path.join(ROOT, "cases", "W+P-quick"))
    ap.add_argument("--seeds", default="12345,2")
    ap.add_argument("--stiffen-from", type=float, default=1e-3)
    ap.add_argument("--steps", type=int, default=10)
    ap.add_argument("--step-time", type=float, default=0.01)
    ap.add_argument("--json")
    ap.add_argument("--work", default=os.path.join(ROOT, "runs", "stiffened_settle"))
    ap.add_argument("--bin", default=os.path.join(ROOT, "build", "bin"))
    ap.add_argument("--reuse", action="store_true",
                    help="take a run's figures from its WORK directory when it ran the same inputs")
    a = ap.parse_args()
    exe = os.path.join(os.path.abspath(a.bin), "mixflowDem")
    os.environ["MIXFLOW_BUILD"] = os.path.dirname(os.path.abspath(a.bin))  # its mixflowSchema: defaults
    stiffen = {"from": a.stiffen_from, "steps": a.steps, "time": a.step_time}
    seeds = [int(s) for s in a.seeds.split(",")]
    out = {"command": "bench/stiffened_settle.py " + " ".join(sys.argv[1:]),
           "case": os.path.relpath(os.path.abspath(a.case), ROOT), "stiffen": stiffen, "runs": []}
    for seed in seeds:
        row = {"seed": seed}
        for name, st in (("full", None), ("stiffened", stiffen)):
            tag = name if st is None else f"{name}_{st['from']:g}_{st['steps']}_{st['time']:g}"
            case = make_case(a.case, os.path.join(os.path.abspath(a.work), f"{tag}_{seed}"),
                             seed, st)
            row[name] = run(exe, case, a.reuse)
            print(name, seed, json.dumps(row[name]), flush=True)
        row["difference"] = {k: row["stiffened"][k] - row["full"][k] for k in COMPARED}
        row["cpu_ratio_full_over_stiffened"] = row["full"]["cpu_s"] / row["stiffened"]["cpu_s"]
        out["runs"].append(row)
    if len(seeds) > 1:
        # Seed-to-seed spread of each method: the largest difference between two of its samples.
        out["seed_spread"] = {
            name: {k: max(r[name][k] for r in out["runs"]) - min(r[name][k] for r in out["runs"])
                   for k in COMPARED} for name in ("full", "stiffened")}
    text = json.dumps(out, indent=1)
    print(text)
    if a.json:
        with open(a.json, "w") as f:
            f.write(text + "\n")


if __name__ == "__main__":
    main()
