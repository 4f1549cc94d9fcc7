"""Contact forces of a granular sample at rest from its particle positions (a binary snapshot,
outputs.read_binary_snapshot): the Hertz normal force of every overlap, as LIGGGHTS' hertz model
computes it for grains at rest (no damping: the relative velocity is zero).

  F_n = 4/3 E* sqrt(R* delta) delta,  1/E* = (1 - nu_1^2)/E_1 + (1 - nu_2^2)/E_2,  R* = R1 R2/(R1 + R2)

(a plane wall: R* = R). Overlaps at 70 GPa are about 1e-6 d, so the positions must be the binary
snapshot's full-precision ones. sample_contacts() returns the statistics that compare two settled
samples: coordination number, mean and quantiles of F_n / (m g), the mean overlap and the share of
the weight the bottom carries; virial_trace() is the same forces' sum of r . F, to set beside
LIGGGHTS' own per-atom contact virial (snapshot columns c_pstress)."""
import numpy as np

G = 9.81


def effective_modulus(e1, nu1, e2, nu2):
    return 1.0 / ((1 - nu1 ** 2) / e1 + (1 - nu2 ** 2) / e2)


def hertz_force(e_eff, r_eff, delta):
    return 4.0 / 3.0 * e_eff * np.sqrt(r_eff * delta) * delta


def pair_overlaps(x, radius, period_z=None):
    """(i, j, overlap, branch vector j -> i) of every overlapping pair i < j; z periodic with
    period period_z (minimum image) when given."""
    d = x[:, None, :] - x[None, :, :]
    if period_z:
        d[:, :, 2] -= period_z * np.round(d[:, :, 2] / period_z)
    dist = np.linalg.norm(d, axis=2)
    reach = radius[:, None] + radius[None, :]
    i, j = np.nonzero(np.triu(dist < reach, k=1))
    return i, j, reach[i, j] - dist[i, j], d[i, j]


def sample_contacts(rows, columns, young, wall_young, poisson, walls, period_z=None):
    """Statistics of the contacts of a snapshot's particles (rows, with the names in columns).
    walls: (axis, position, side) of each plane wall, side +1 when the grains are on its
    positive side (the bottom: (1, 0.0, +1)); the first one is the bottom."""
    c = {n: k for k, n in enumerate(columns)}
    x = rows[:, [c["x"], c["y"], c["z"]]]
    rad = rows[:, c["radius"]]
    mass = rows[:, c["mass"]]
    mg = float(np.mean(mass)) * G
    i, j, dpp, _ = pair_overlaps(x, rad, period_z)
    e_pp = effective_modulus(young, poisson, young, poisson)
    f_pp = hertz_force(e_pp, rad[i] * rad[j] / (rad[i] + rad[j]), dpp)
    e_pw = effective_modulus(young, poisson, wall_young, poisson)
    wall_forces = []
    for axis, pos, side in walls:
        gap = side * (x[:, axis] - pos) - rad
        k = gap < 0
        wall_forces.append(hertz_force(e_pw, rad[k], -gap[k]))
    n = len(rows)
    q = np.quantile(f_pp / mg, [0.1, 0.5, 0.9]) if len(f_pp) else [np.nan] * 3
    return {
        "particles": n,
        "pair_contacts": int(len(f_pp)),
        "coordination_pairs": 2.0 * len(f_pp) / n,  # particle-particle contacts per grain
        "coordination_all": (2.0 * len(f_pp) + sum(len(w) for w in wall_forces)) / n,
        "force_mean_over_mg": float(np.mean(f_pp) / mg) if len(f_pp) else np.nan,
        "force_p10_over_mg": float(q[0]),
        "force_p50_over_mg": float(q[1]),
        "force_p90_over_mg": float(q[2]),
        "force_max_over_mg": float(np.max(f_pp) / mg) if len(f_pp) else np.nan,
        "overlap_mean_over_d": float(np.mean(dpp / (2 * rad[i]))) if len(dpp) else np.nan,
        "bottom_load_over_weight": float(np.sum(wall_forces[0]) / (n * mg)),
        "wall_contacts": [int(len(w)) for w in wall_forces],
    }


def virial_trace(rows, columns, young, poisson, period_z=None):
    """Sum over particle-particle contacts of branch . force (N m, > 0 for repulsion) from the
    Hertz forces of the positions; LIGGGHTS' stress/atom gives minus this as the sum over all
    particles of c_pstress[1] + [2] + [3]."""
    c = {n: k for k, n in enumerate(columns)}
    x = rows[:, [c["x"], c["y"], c["z"]]]
    rad = rows[:, c["radius"]]
    i, j, dpp, branch = pair_overlaps(x, rad, period_z)
    e_pp = effective_modulus(young, poisson, young, poisson)
    f = hertz_force(e_pp, rad[i] * rad[j] / (rad[i] + rad[j]), dpp)
    return float(np.sum(f * np.linalg.norm(branch, axis=1)))


def liggghts_virial_trace(rows, columns):
    c = {n: k for k, n in enumerate(columns)}
    return -float(np.sum(rows[:, c["c_pstress[1]"]] + rows[:, c["c_pstress[2]"]] +
                         rows[:, c["c_pstress[3]"]]))


def settled_stats(case):
    """The settled sample of a dry case run through its first snapshot (mixflowDem with a short
    endTime): summary.json's settled block and sample_contacts() of VTK/particles/particles_0.bin
    (the gate is open but no step has run). Moduli and walls from the case's sceneProperties
    (the declared defaults where it sets none: mixflow.schema)."""
    import json
    import os
    from mixflow import foamdict, outputs, schema
    rel = "constant/sceneProperties"
    sp = foamdict.read_dict(os.path.join(case, rel))
    sample = sp["sample"]
    young = float(schema.value(sp, rel, "particles.youngModulus"))
    wall_young = float(schema.value(sp, rel, "particles.wallYoungModulus"))
    poisson = float(schema.value(sp, rel, "particles.poissonRatio"))
    length, width = float(sample["length"]), float(sample["width"])
    periodic = schema.value(sp, rel, "channel.sideWalls") == "periodic"
    walls = [(1, 0.0, 1), (0, 0.0, 1), (0, length, -1)]
    if not periodic:
        walls += [(2, 0.0, 1), (2, width, -1)]
    rows = outputs.read_binary_snapshot(os.path.join(case, outputs.SNAPSHOT_BIN.format(step=0)))
    cols = outputs.SNAPSHOT_COLUMNS
    with open(os.path.join(case, "postProcessing", "dem", "summary.json")) as f:
        settled = json.load(f)["settled"]
    stats = sample_contacts(rows, cols, young, wall_young, poisson, walls,
                            width if periodic else None)
    stats.update({k: settled[k] for k in ("height_m", "sample_solid_fraction",
                                          "bulk_solid_fraction", "settle_time_s", "converged")})
    # Hertz forces of the positions against LIGGGHTS' own contact virial: equal only if LIGGGHTS
    # ran at the moduli given here (after a stiffening, the full ones).
    stats["virial_ratio"] = (virial_trace(rows, cols, young, poisson, width if periodic else None)
                             / liggghts_virial_trace(rows, cols))
    return stats
