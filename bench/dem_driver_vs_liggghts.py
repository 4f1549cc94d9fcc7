#!/usr/bin/env python3
"""Benchmark: our LIGGGHTS driver (mixflowDem) against the plain `liggghts` binary on the same work.

mixflowDem records every LIGGGHTS command it issues in <case>/dem/in.liggghts (settling, gate removal,
every `run` chunk, outlet deletions, snapshots). Replaying that script with plain `liggghts` does the
same particle work without our per-sample observables (energies, front clustering, MPI gathers), so the
wall-time ratio is the driver's overhead. Target: driver within 5 % of plain LIGGGHTS.

usage: dem_driver_vs_liggghts.py [--case DIR] [--ranks N] [--repeat K] [--json OUT]
       (default case cases/P-quick; binaries from build/bin and PATH)"""
import argparse
import json
import os
import re
import shutil
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.dont_write_bytecode = True
from mixflow import outputs  # noqa: E402
from mixflow.timing import timed  # noqa: E402


def mpi_prefix(ranks):
    if ranks <= 1:
        return []
    extra = ["--oversubscribe"] + (["--allow-run-as-root"] if os.geteuid() == 0 else [])
    return ["mpirun"] + extra + ["-np", str(ranks)]


def particle_steps(script, natoms):
    steps = sum(int(m.group(1)) for m in re.finditer(r"^run (\d+)", open(script).read(), re.M))
    return steps, steps * natoms


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--case", default=os.path.join(ROOT, "cases", "P-quick"))
    ap.add_argument("--ranks", type=int, default=1)
    ap.add_argument("--repeat", type=int, default=2)
    ap.add_argument("--json")
    ap.add_argument("--bin", default=os.path.join(ROOT, "build", "bin"))
    a = ap.parse_args()
    exe = os.path.join(a.bin, "mixflowDem")
    work = tempfile.mkdtemp(prefix="mixflow-bench-")
    case = os.path.join(work, "case")
    outputs.copy_inputs(a.case, case)
    ours, plain = [], []
    for _ in range(a.repeat):
        ours.append(timed(mpi_prefix(a.ranks) + [exe, "-case", "."] + (["-parallel"] if a.ranks > 1 else []), case))
        replay = os.path.join(case, "dem", "in.liggghts")
        plain.append(timed(mpi_prefix(a.ranks) + ["liggghts", "-in", replay, "-log", "dem/log.replay",
                                                   "-screen", "dem/screen.replay", "-echo", "none"], case))
    summary = json.load(open(os.path.join(case, "postProcessing", "dem", "summary.json")))
    steps, psteps = particle_steps(os.path.join(case, "dem", "in.liggghts"), summary["settled"]["particles"])
    cpu_ours, cpu_plain = min(c for _, c in ours), min(c for _, c in plain)
    wall_ours, wall_plain = min(w for w, _ in ours), min(w for w, _ in plain)
    result = {
        "case": os.path.relpath(a.case, ROOT), "ranks": a.ranks, "particles": summary["settled"]["particles"],
        "steps": steps, "runs_wall_cpu_s_mixflowDem": ours, "runs_wall_cpu_s_plain_liggghts": plain,
        "particle_steps_per_cpu_s_mixflowDem": psteps / cpu_ours,
        "particle_steps_per_cpu_s_plain_liggghts": psteps / cpu_plain,
        "ratio_cpu_mixflowDem_over_plain": cpu_ours / cpu_plain,
        "ratio_wall_mixflowDem_over_plain": wall_ours / wall_plain, "target_ratio_max": 1.05,
        "command": "bench/dem_driver_vs_liggghts.py " + " ".join(sys.argv[1:]),
    }
    print(f"particles {result['particles']}, steps {steps}, ranks {a.ranks}, best of {a.repeat}")
    for name, cpu, wall in (("mixflowDem", cpu_ours, wall_ours), ("plain liggghts", cpu_plain, wall_plain)):
        print(f"  {name:15s} cpu {cpu:8.2f} s  wall {wall:8.2f} s  {psteps / cpu:.3e} particle-steps per cpu-s")
    print(f"  ratio ours/plain: cpu {result['ratio_cpu_mixflowDem_over_plain']:.3f} (target <= 1.05), "
          f"wall {result['ratio_wall_mixflowDem_over_plain']:.3f} (wall is noisy on a shared machine)")
    if a.json:
        os.makedirs(os.path.dirname(os.path.abspath(a.json)), exist_ok=True)
        json.dump(result, open(a.json, "w"), indent=2)
    shutil.rmtree(work)


if __name__ == "__main__":
    main()
