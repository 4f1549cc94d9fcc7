#!/usr/bin/env python3
"""The small collapse with 2 MPI ranks gives the serial runout (LIGGGHTS' equal x slabs); with the
slabs re-balanced by particles (balanceWeight particles) the 2 ranks hold equal shares (max/mean
<= 1.15); with the default weight (pairs: 1 + a particle's neighbour pairs) the back slab, which
holds the column's dense rest, holds fewer particles than the front one over the collapse.

Tolerance: 2 particle diameters (2.4 cm, about 8 % of this runout): the front of a granular deposit is
only defined to a grain or two. On this machine the 2-rank run (x split) reproduces the serial
trajectories bit for bit, so the difference is 0. Caution: a round-off-level perturbation of the same
serial run (e.g. atoms re-ordered by a restart write) moves this small column's runout by up to
±0.03 m (0.307 to 0.371 m seen when each restart write left LIGGGHTS on stale neighbour
lists for the next steps, which LiggghtsSession::writeRestart now prevents), because the front particle of a thin tail attaches or detaches; a
future LIGGGHTS that were not bit-reproducible across ranks would need a statistical comparison."""
import csv
import os
import sys

from run_column import run

exe, work = sys.argv[1], sys.argv[2]
serial = run(exe, work + "/serial", 1)
EQUAL_SLABS = 'balanceInterval 0;\nprocessors "* * *";'
parallel = run(exe, work + "/np2", 2, EQUAL_SLABS)
d = 0.012
tol = 2 * d
diff = abs(serial["runout_m"] - parallel["runout_m"])
print(f"runout serial {serial['runout_m']:.4f} m, np2 {parallel['runout_m']:.4f} m, |diff| {diff:.4f} m, "
      f"tolerance {tol:.4f} m")
assert serial["particles_remaining"] + serial["deleted_outlet"] + serial["deleted_top"] + serial["lost"] == \
    serial["settled"]["particles"], "particle count not conserved (serial)"
assert parallel["particles_remaining"] + parallel["deleted_outlet"] + parallel["deleted_top"] + parallel["lost"] == \
    parallel["settled"]["particles"], "particle count not conserved (np2)"

# The per-rank load (rankLoad.csv) accounts for every particle of the series at every sample, on
# both ranks, with compute seconds that only grow.
out = os.path.join(work, "np2", "postProcessing", "dem")
series = {r["time_s"]: int(r["particles"]) for r in csv.DictReader(open(os.path.join(out, "timeSeries.csv")))}
load = list(csv.DictReader(open(os.path.join(out, "rankLoad.csv"))))
by_time = {}
for r in load:
    by_time.setdefault(r["time_s"], []).append(r)
assert set(by_time) == set(series), "rankLoad.csv and timeSeries.csv sample different times"
for t, rows in by_time.items():
    assert sorted(int(r["rank"]) for r in rows) == [0, 1], f"rankLoad.csv at t = {t}: ranks {rows}"
    held = sum(int(r["particles"]) for r in rows)
    assert held == series[t], f"rankLoad.csv at t = {t}: ranks hold {held}, series has {series[t]}"
for rank in ("0", "1"):
    work_s = [float(r["dem_compute_s"]) for r in load if r["rank"] == rank]
    assert all(b >= a for a, b in zip(work_s, work_s[1:])), f"rank {rank}: compute seconds decrease"
print(f"rankLoad.csv: {len(by_time)} samples, particles of both ranks = series particles")



def collapse_shares(name, extra=None):
    """Each sample's particles per rank over the collapse of a 2-rank run, every particle
    accounted for. The runout is not compared: the reordered contact sums perturb this chaotic
    collapse."""
    res = run(exe, os.path.join(work, name), 2, extra)
    assert res["particles_remaining"] + res["deleted_outlet"] + res["deleted_top"] + \
        res["lost"] == res["settled"]["particles"], f"particle count not conserved ({name})"
    rows = csv.DictReader(open(os.path.join(work, name, "postProcessing", "dem", "rankLoad.csv")))
    shares = {}
    for r in rows:
        if float(r["time_s"]) > 0:
            shares.setdefault(r["time_s"], {})[int(r["rank"])] = int(r["particles"])
    return [[n[k] for k in sorted(n)] for n in shares.values()]


# Slabs re-balanced by particles (demDict balanceInterval, balanceWeight particles): the 2 ranks
# hold equal shares over the collapse (time mean of max/mean <= 1.15).
shares = collapse_shares("np2-balanced", "balanceWeight particles;")
ratios = [max(n) / (sum(n) / len(n)) for n in shares]
imbalance = sum(ratios) / len(ratios)
print(f"balanced slabs: particle imbalance {imbalance:.3f} (max/mean, time mean over "
      f"{len(ratios)} samples); equal slabs would give up to 2")
if imbalance > 1.15:
    sys.exit(f"FAIL: balanced 2-rank particle imbalance {imbalance:.3f} > 1.15")

# The default weight (pairs): a grain of the dense rest has more neighbour pairs than one of the
# spread front, so the back slab (rank 0) holds fewer particles than the front one on time mean.
back = [n[0] / sum(n) for n in collapse_shares("np2-pairs")]
back_share = sum(back) / len(back)
print(f"balanceWeight pairs: back slab's particle share {back_share:.3f} (time mean over "
      f"{len(back)} samples; < 0.5 expected)")
if back_share >= 0.5:
    sys.exit(f"FAIL: with balanceWeight pairs the back slab holds {back_share:.3f} >= 0.5 of the "
             "particles: the weight does not see the dense column")
if diff > tol:
    sys.exit(f"FAIL: serial and parallel runouts differ by {diff:.4f} m > {tol:.4f} m")
print("PASS")
