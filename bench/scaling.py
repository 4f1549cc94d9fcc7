#!/usr/bin/env python3
"""Benchmark: how the DEM work spreads over MPI ranks, and the 2-rank parallel efficiency.

Each scene (default: the reference tier's mixture W+P and dry column P, to 1 s) runs with
./Allrun N for N in --ranks (more ranks than cores oversubscribe: their load figures hold, their
times do not). From the run's postProcessing/dem/rankLoad.csv (written by the DEM half at every
sample, dem/RankLoad.h), over the collapse (after the gate opens):
  - particles_max_over_mean: the time mean of max/mean over ranks of the particles held;
  - compute_max_over_mean: max/mean over ranks of the LIGGGHTS compute seconds (pair, neighbour
    lists, fixes) the collapse took on each rank.
The efficiency at 2 ranks is T1 / (2 T2) of the wall time of the whole ./Allrun, from serial and
2-rank runs alternated --repeat times (median of each), on a machine with 2 idle cores.
--balance S sets demDict balanceInterval S and processors "* 1 1" (x slabs re-balanced by
particles weighted by --weight, demDict balanceWeight, dem/SlabBalance.h; in a mixture the fluid
keeps its slabs and the exchange routes each particle to its cells' ranks; demDict's default); 0:
LIGGGHTS' own grid and equal slabs. --tier T
runs the scene as mixflow suite --tier T would (none: the case as it is), --end S sets its
controlDict endTime.

--repeat 0 runs each rank count of --ranks above 1 once, for the load figures alone.

usage: scaling.py [--scenes W+P,P] [--ranks 1,2,4,8] [--repeat 2] [--balance 0.05] [--weight W]
                  [--tier reference|none|...] [--end 1.0] [--json results/bench/scaling.json]
                  [--work runs/scaling]
"""
import argparse
import os
import shutil
import statistics
import subprocess
import sys
import time

sys.dont_write_bytecode = True
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
from mixflow import foamcase, foamdict, outputs  # noqa: E402
from mixflow.commands import suite  # noqa: E402

SCENE_NAMES = {"P-quick": "P", "W+P-quick": "W&P", "P": "P", "W+P": "W&P"}


def run_case(scene, ranks, work, tag, balance, tier=None, end=None, weight="pairs"):
    """Fresh copy of cases/SCENE (with TIER's overrides) run with ./Allrun RANKS; (wall s, case
    dir)."""
    case = os.path.join(work, f"{scene}-np{ranks}-{tag}")
    shutil.rmtree(case, ignore_errors=True)
    if tier:
        src = os.path.join(ROOT, "cases", scene)
        texts, records = suite.tier_edits(src, tier, scene)
        suite.make_copy(scene, case, tier, texts, records, suite.scene_content(src))
    else:
        outputs.copy_inputs(os.path.join(ROOT, "cases", scene), case)
    foamdict.edit_file(os.path.join(case, "system", "demDict"),
                       {"balanceInterval": str(balance), "balanceWeight": weight,
                        "processors": '"* 1 1"' if balance > 0 else '"* * *"'},
                       note="bench/scaling.py")
    if end:
        foamdict.edit_file(os.path.join(case, "system", "controlDict"), {"endTime": str(end)},
                           note="bench/scaling.py --end")
    env = foamcase.run_env()
    t0 = time.perf_counter()
    with open(os.path.join(case, "log.Allrun"), "w") as log:
        res = subprocess.run(["./Allrun", str(ranks)], cwd=case, env=env, stdout=log,
                             stderr=subprocess.STDOUT)
    wall = time.perf_counter() - t0
    if res.returncode != 0:
        sys.exit(f"{case}: ./Allrun {ranks} failed ({res.returncode}); see its log.Allrun")
    return wall, case


def load_figures(case):
    """Imbalance figures over the collapse from the case's rankLoad.csv (outputs.RANK_LOAD)."""
    by_time = {}  # time -> rows of the ranks, in file order
    for r in outputs.read_series(os.path.join(case, outputs.RANK_LOAD)):
        by_time.setdefault(r[outputs.TIME], []).append(r)
    times = sorted(by_time)
    ratios = []
    for t in times[1:]:
        n = [r["particles"] for r in by_time[t]]
        if sum(n) > 0:
            ratios.append(max(n) / statistics.mean(n))
    first = {int(r["rank"]): r["dem_compute_s"] for r in by_time[times[0]]}
    last = {int(r["rank"]): r["dem_compute_s"] for r in by_time[times[-1]]}
    work = [last[k] - first[k] for k in sorted(last)]
    return {
        "ranks": len(last),
        "particles_max_over_mean": statistics.mean(ratios),
        "compute_max_over_mean": max(work) / statistics.mean(work) if sum(work) > 0 else None,
        "compute_s_per_rank": work,
        "particles_per_rank_at_end": [int(r["particles"]) for r in by_time[times[-1]]],
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--scenes", default="W+P,P")
    ap.add_argument("--ranks", default="1,2,4,8")
    ap.add_argument("--repeat", type=int, default=2)
    ap.add_argument("--balance", type=float, default=0.05)
    ap.add_argument("--weight", default="pairs", choices=("particles", "pairs", "contacts"),
                    help="demDict balanceWeight: what a particle weighs in the re-balance")
    ap.add_argument("--tier", default="reference", help="a tier of mixflow suite applied to "
                    "the scene's copy; none: the case as it is")
    ap.add_argument("--end", type=float, default=1.0, help="controlDict endTime (s) of every run; "
                    "0: the case's")
    ap.add_argument("--json", default=os.path.join(ROOT, "results", "bench", "scaling.json"))
    ap.add_argument("--work", default=os.path.join(ROOT, "runs", "scaling"))
    args = ap.parse_args()
    ranks = [int(r) for r in args.ranks.split(",")]
    tier = suite.Tier(args.tier) if args.tier != "none" else None
    out = {"imbalance_max_over_mean": {}, "compute_imbalance_max_over_mean": {},
           "efficiency_2_ranks": {}, "wall_s": {}, "per_run": {},
           "balance_interval_s": args.balance, "balance_weight": args.weight, "tier": args.tier,
           "end_time_s": args.end,
           "command": "mixflow bench scaling " + " ".join(sys.argv[1:])}
    for scene in args.scenes.split(","):
        name = SCENE_NAMES.get(scene, scene)
        walls = {1: [], 2: []}
        # Serial and 2-rank runs alternate so that a drift of the machine hits both alike.
        for k in range(args.repeat):
            for n in (1, 2):
                wall, case = run_case(scene, n, args.work, f"r{k}", args.balance, tier,
                                      args.end, args.weight)
                walls[n].append(wall)
                out["per_run"][f"{scene} np{n} r{k}"] = load_figures(case)
                print(f"{scene} np{n} r{k}: wall {wall:.1f} s", flush=True)
        for n in ranks:
            if n == 1 or (n == 2 and args.repeat > 0):
                continue
            wall, case = run_case(scene, n, args.work, "r0", args.balance, tier, args.end,
                                  args.weight)
            out["per_run"][f"{scene} np{n} r0"] = load_figures(case)
            print(f"{scene} np{n}: wall {wall:.1f} s (oversubscribed)", flush=True)
        out["imbalance_max_over_mean"][name] = {
            str(n): out["per_run"][f"{scene} np{n} r0"]["particles_max_over_mean"]
            for n in ranks if n > 1}
        out["compute_imbalance_max_over_mean"][name] = {
            str(n): out["per_run"][f"{scene} np{n} r0"]["compute_max_over_mean"]
            for n in ranks if n > 1}
        if args.repeat > 0:
            t1, t2 = statistics.median(walls[1]), statistics.median(walls[2])
            out["efficiency_2_ranks"][name] = t1 / (2 * t2)
            out["wall_s"][name] = {"1": walls[1], "2": walls[2]}
        print(f"{name}: efficiency at 2 ranks {out['efficiency_2_ranks'].get(name)}; particle "
              f"imbalance {out['imbalance_max_over_mean'][name]}; compute imbalance "
              f"{out['compute_imbalance_max_over_mean'][name]}", flush=True)
    outputs.write_json(args.json, out)
    print("wrote", args.json)


if __name__ == "__main__":
    main()
