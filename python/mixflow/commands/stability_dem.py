"""DEM step against stiffness: where a run goes wrong as dt / T_R grows, at several softenings.

Runs plain LIGGGHTS (/usr/bin/liggghts) with the simulator's contact lines (the paper material,
hertz + tangential history + rolling cdt, limitForce on, as dem/LiggghtsCommands.cpp writes them)
on three small set-ups, for every youngModulusFactor f and step fraction dt / T_R:
  pair    8 head-on pairs at v_rel (contact phases spread over one step), e_input 0.7:
          worst |e - 0.7182| (tests/reference/liggghts_hertz_actual_restitution.csv)
  elastic the same with e_input 1: worst |e - 1| (the energy error of one contact)
  wall    8 spheres onto the floor (wall modulus 10 E) at v_rel, e_input 0.7
  settle  a 5 x 5 x 8 lattice poured into a closed box under gravity, e_input 0.7: grains lost,
          largest overlap / d at the end, kinetic energy left after the settling time and the
          potential energy released (over m g d); dt_over_tc against the shorter elastic contact
          time at the pour's impact speed sqrt(2 g h_top)
Writes a CSV (one row per set-up, f, fraction) and prints it.

  mixflow stability-dem --work /tmp/stab-dem --csv results/stability/dem_step.csv
"""
import argparse
import csv
import math
import os
import subprocess
import sys

import numpy as np

# Paper material (docs/model.md §2, dem/Scene.h ParticleMaterial defaults).
D, RHO, E_P, E_W, NU, E_IN = 0.024, 2500.0, 70e9, 700e9, 0.3, 0.7
R = D / 2
M = RHO * math.pi * D**3 / 6
E_REF_ON = 0.7182  # tests/reference/liggghts_hertz_actual_restitution.csv, e_input 0.7, limitForce on
G = 9.81


def rayleigh_time(e):
    shear = e / (2 * (1 + NU))
    return math.pi * R * math.sqrt(RHO / shear) / (0.1631 * NU + 0.8766)


def e_star(e1, e2):
    return 1 / ((1 - NU**2) / e1 + (1 - NU**2) / e2)


def hertz_time(es, rs, ms, v):
    return 2.868 * (ms * ms / (rs * es * es * v)) ** 0.2


def hertz_min(factor, v):
    """The shorter elastic contact time, grain-grain or grain-wall, at impact speed v (as
    dem/Scene.cpp hertzTimeMin)."""
    pp = hertz_time(e_star(E_P * factor, E_P * factor), R / 2, M / 2, v)
    pw = hertz_time(e_star(E_P * factor, E_W * factor), R, M, v)
    return min(pp, pw)


def contact_lines(factor, e_in):
    ep, ew = E_P * factor, E_W * factor
    pair = lambda pp, pw: f"peratomtypepair 2 {pp} {pw} {pw} {pw}"
    c = []
    if max(ep, ew) > 1e9:
        c.append("hard_particles yes")
    if ep < 5e6:
        c.append("soft_particles yes")
    c += [
        f"fix m1 all property/global youngsModulus peratomtype {ep!r} {ew!r}",
        f"fix m2 all property/global poissonsRatio peratomtype {NU} {NU}",
        f"fix m3 all property/global coefficientRestitution {pair(e_in, e_in)}",
        f"fix m4 all property/global coefficientFriction {pair(0.7, 0.7)}",
        f"fix m5 all property/global coefficientRollingFriction {pair(0.1, 0.1)}",
        "pair_style gran model hertz tangential history rolling_friction cdt limitForce on",
        "pair_coeff * *",
    ]
    return c


WALL = "model hertz tangential history rolling_friction cdt primitive type 2"


def header(box, factor, e_in, dt):
    return [
        "units si", "atom_style granular", "atom_modify map array", "boundary f f f",
        "newton off", "communicate single vel yes",
        "region box block " + " ".join(repr(b) for b in box) + " units box",
        "create_box 2 box", f"neighbor {0.2 * D!r} bin", "neigh_modify delay 0",
    ] + contact_lines(factor, e_in) + [
        f"timestep {dt!r}", "fix integr all nve/sphere",
        "thermo_style custom step atoms ke", "thermo_modify lost ignore norm no", "thermo 100000000",
    ]


def run_liggghts(lines, work, name):
    os.makedirs(work, exist_ok=True)
    inp = os.path.join(work, name + ".in")
    with open(inp, "w") as f:
        f.write("\n".join(lines) + "\n")
    r = subprocess.run(["nice", "-n", "15", "liggghts", "-in", inp, "-log",
                        os.path.join(work, name + ".log"), "-screen", "none"], cwd=work)
    dump = os.path.join(work, name + ".dump")
    if r.returncode != 0 or not os.path.exists(dump):
        return None
    return read_last_dump(dump)


def read_last_dump(path):
    """The last snapshot of a 'dump custom id x y z vx vy vz' file: {id: row}."""
    with open(path) as f:
        text = f.read().split("ITEM: TIMESTEP")[-1].splitlines()
    i = text.index(next(l for l in text if l.startswith("ITEM: ATOMS")))
    rows = {}
    for line in text[i + 1:]:
        if line.strip():
            v = line.split()
            rows[int(v[0])] = [float(x) for x in v[1:]]
    return rows


def impacts(kind, factor, frac, v, e_in, work):
    """Worst restitution over 8 contact phases; nan when a contact did not complete."""
    dt = frac * rayleigh_time(E_P * factor)
    n = 8
    wall = kind == "wall"
    es = e_star(E_P * factor, (E_W if wall else E_P) * factor)
    tc = hertz_time(es, R if wall else R / 2, M if wall else M / 2, v)
    pitch = 3 * D
    box = ([-2 * D, n * pitch, -2 * D, 2 * D, -0.1 * R, 3 * D + 2 * v * tc] if wall
           else [-3 * D - v * tc, 3 * D + v * tc, -2 * D, n * pitch, -2 * D, 2 * D])
    lines = header(box, factor, e_in, dt)
    if wall:
        lines.append(f"fix wFloor all wall/gran {WALL} zplane 0.0 limitForce on")
    for k in range(n):
        gap = (k + 0.5) / n * v * dt
        if wall:
            lines += [f"create_atoms 1 single {k * pitch!r} 0 {R + gap!r} units box",
                      f"set atom {k + 1} diameter {D} density {RHO} vx 0 vy 0 vz {-v!r}"]
        else:
            for j, s in ((2 * k + 1, -1), (2 * k + 2, 1)):
                lines += [f"create_atoms 1 single {s * (R + 0.5 * gap)!r} {k * pitch!r} 0 units box",
                          f"set atom {j} diameter {D} density {RHO} vx {-s * 0.5 * v!r} vy 0 vz 0"]
    steps = int(1.5 * tc / dt) + 20
    lines += [f"dump d all custom {steps} {kind}.dump id x y z vx vy vz", f"run {steps}"]
    atoms = run_liggghts(lines, work, kind)
    if atoms is None or len(atoms) != (n if wall else 2 * n):
        return math.nan, dt, tc
    es_ = []
    for k in range(n):
        if wall:
            z, vz = atoms[k + 1][2], atoms[k + 1][5]
            es_.append(vz / v if z > R else -math.inf)  # still in contact or through the wall
        else:
            a, b = atoms[2 * k + 1], atoms[2 * k + 2]
            es_.append((b[3] - a[3]) / v if b[0] - a[0] > D else -math.inf)
    ref = E_REF_ON if e_in < 1 else 1.0
    return max(es_, key=lambda e: abs(e - ref)), dt, tc


def pour_height():
    """Centre height of the pour's top layer (m)."""
    return 0.6 * D + 7 * 1.15 * D


def settle(factor, dt, work, settle_time):
    """5 x 5 x 8 grains poured into a box 6 d wide at step dt. Returns grains lost, the largest
    overlap / d at the end (grain-grain or floor), the kinetic energy left and the potential energy
    released, both over m g d (nan when no grain is left)."""
    w = 6 * D
    box = [0, w, 0, w, -0.1 * R, 12 * D]
    lines = header(box, factor, E_IN, dt) + ["fix gravi all gravity 9.81 vector 0.0 0.0 -1.0"]
    for name, plane, pos in (("w0", "zplane", 0.0), ("w1", "xplane", 0.0), ("w2", "xplane", w),
                             ("w3", "yplane", 0.0), ("w4", "yplane", w)):
        lines.append(f"fix {name} all wall/gran {WALL} {plane} {pos!r} limitForce on")
    rng = np.random.default_rng(1)
    pitch = 1.15 * D
    k, z0 = 0, 0.0
    for iz in range(8):
        for iy in range(5):
            for ix in range(5):
                k += 1
                x = 0.6 * D + ix * pitch + rng.uniform(-0.05, 0.05) * D
                y = 0.6 * D + iy * pitch + rng.uniform(-0.05, 0.05) * D
                z = 0.6 * D + iz * pitch
                z0 += z
                lines += [f"create_atoms 1 single {x!r} {y!r} {z!r} units box",
                          f"set atom {k} diameter {D} density {RHO} vx 0 vy 0 vz 0"]
    steps = int(settle_time / dt)
    lines += [f"dump d all custom {steps} settle.dump id x y z vx vy vz", f"run {steps}"]
    atoms = run_liggghts(lines, work, "settle") or {}
    x = np.array([a[:3] for a in atoms.values()]).reshape(-1, 3)
    v = np.array([a[3:6] for a in atoms.values()]).reshape(-1, 3)
    inside = np.all((x >= [0, 0, -R]) & (x <= [w, w, 12 * D]), axis=1) & np.all(np.isfinite(x), axis=1)
    out = dict(lost=200 - int(inside.sum()), overlap=math.nan, ke=math.nan, pe_drop=math.nan)
    xi = x[inside]
    if len(xi) == 200:
        dist = np.linalg.norm(xi[:, None, :] - xi[None, :, :], axis=2) + np.eye(len(xi)) * 10
        out["overlap"] = max(float((D - dist).max()), float((R - xi[:, 2]).max()), 0.0) / D
        out["ke"] = 0.5 * float((v[inside] ** 2).sum()) / (G * D)
        out["pe_drop"] = (z0 - float(xi[:, 2].sum())) / D
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--work", required=True)
    ap.add_argument("--csv", required=True)
    ap.add_argument("--factors", default="1,1e-2,1e-4")
    ap.add_argument("--fractions", default="0.05,0.1,0.15,0.2,0.25,0.3,0.4,0.5,0.7,1,1.2,1.5,2")
    ap.add_argument("--speeds", default="1,3.4", help="v_rel of the impacts (m/s); 3.4 = sqrt(2 g 0.6)")
    ap.add_argument("--settle-factors", default="1e-2,1e-4", help="the settling test's factors")
    ap.add_argument("--settle-time", type=float, default=0.5)
    a = ap.parse_args()
    factors = [float(f) for f in a.factors.split(",")]
    fracs = [float(f) for f in a.fractions.split(",")]
    speeds = [float(v) for v in a.speeds.split(",")]
    rows = []
    for f in factors:
        tr = rayleigh_time(E_P * f)
        for frac in fracs:
            for v in speeds:
                for kind, e_in in (("pair", E_IN), ("elastic", 1.0), ("wall", E_IN)):
                    work = os.path.join(a.work, f"{kind}_f{f:g}_r{frac:g}_v{v:g}")
                    e, dt, tc = impacts("wall" if kind == "wall" else "pair", f, frac, v, e_in, work)
                    ref = 1.0 if kind == "elastic" else E_REF_ON
                    rows.append(dict(test=kind, factor=f, fraction=frac, v_rel=v, T_R=tr, dt=dt,
                                     dt_over_tc=dt / tc, value=e, error=abs(e - ref)))
                    print(rows[-1], flush=True)
            if f in [float(s) for s in a.settle_factors.split(",")]:
                dt = frac * tr
                r = settle(f, dt, os.path.join(a.work, f"settle_f{f:g}_r{frac:g}"), a.settle_time)
                rows.append(dict(test="settle", factor=f, fraction=frac, v_rel="", T_R=tr, dt=dt,
                                 dt_over_tc=dt / hertz_min(f, math.sqrt(2 * G * pour_height())),
                                 value=r["overlap"], error=r["lost"], ke_over_mgd=r["ke"],
                                 pe_drop_over_mgd=r["pe_drop"]))
                print(rows[-1], flush=True)
    os.makedirs(os.path.dirname(os.path.abspath(a.csv)), exist_ok=True)
    keys = ["test", "factor", "fraction", "v_rel", "T_R", "dt", "dt_over_tc", "value", "error",
            "ke_over_mgd", "pe_drop_over_mgd"]
    with open(a.csv, "w", newline="") as fh:
        w = csv.DictWriter(fh, keys)
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{r[k]:.6g}" if isinstance(r.get(k), float) else r.get(k, "")) for k in keys})
    return 0


if __name__ == "__main__":
    sys.exit(main())
