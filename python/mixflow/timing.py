"""Timing a command for the benchmarks (bench/): wall time and the CPU time of the command with
all its descendants (e.g. MPI ranks)."""

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
