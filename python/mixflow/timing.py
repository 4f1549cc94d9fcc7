"""Timing a command for the benchmarks (bench/) and the studies' runs: wall time and the CPU time
of the command with all its descendants (e.g. MPI ranks)."""

import json
import os
import resource
import subprocess
import sys
import time


def timed(cmd, cwd, with_output=False):
    """Wall seconds and CPU seconds (user + sys of the command and all its descendants, e.g. MPI ranks).
    CPU time is the fair measure on a shared machine: wall time also counts waiting for the core."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    res = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if res.returncode != 0:
        sys.exit(f"failed ({res.returncode}): {' '.join(cmd)}\n{res.stdout[-2000:]}\n{res.stderr[-2000:]}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return (wall, cpu, res.stdout) if with_output else (wall, cpu)


def recorded_run(cmd, work, cwd=None, stdout=None, name="rusage.json"):
    """Runs cmd (its exit status returned) and adds its cost to WORK/NAME, accumulated over
    attempts: cpu_s (user_s + sys_s of the command and its descendants), wall_s, attempts, and
    the last attempt's cmd and rc. A study's run that resumes keeps counting what it spent; runs
    of different scenes in one WORK need a NAME each."""
    r0, t0 = resource.getrusage(resource.RUSAGE_CHILDREN), time.time()
    rc = subprocess.call(cmd, cwd=cwd, stdout=stdout, stderr=subprocess.STDOUT if stdout else None)
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    os.makedirs(work, exist_ok=True)
    path = os.path.join(work, name)
    rec = {"cpu_s": 0.0, "user_s": 0.0, "sys_s": 0.0, "wall_s": 0.0, "attempts": 0}
    if os.path.isfile(path):
        with open(path) as f:
            rec.update(json.load(f))
    rec["user_s"] += r1.ru_utime - r0.ru_utime
    rec["sys_s"] += r1.ru_stime - r0.ru_stime
    rec["cpu_s"] = rec["user_s"] + rec["sys_s"]
    rec["wall_s"] += time.time() - t0
    rec["attempts"] += 1
    rec["cmd"], rec["rc"] = cmd, rc
    with open(path, "w") as f:
        json.dump(rec, f, indent=1)
    return rc
