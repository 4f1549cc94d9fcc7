#!/usr/bin/env python3
"""A settled bed in still liquid (formulation B consistency, docs/model.md §3).

Case: a box 3 x 6 x 3 cm of 6 mm cells (3 dp), open to the atmosphere at the top, water up to
4.5 cm, at rest; a bed of 4 layers of 15 x 15 glass spheres (d 2 mm, 2500 kg/m3) in simple-cubic
contact on the floor (8 mm high: eps_f 0.476 in the bottom cell row, 0.825 in the next, where the
bed surface cuts the cells). The spheres settle into their contact overlaps (Hertz, E 5 MPa) and
must then stay at rest. Frictionless contacts (so that the side walls carry no weight by
friction), restitution 0.3.
Forces: DiFeliceDrag, buoyancy, viscousForce; voidFractionModel divided (no eps_f clipping).
LIGGGHTS stores the floor's force on each particle (wall/gran ... store_force yes) and writes
its sum (dem/floor.txt, every exchange).

Checks at the end (--end, default 0.5 s), averaged over the last 0.1 s where noted:
  - the bed is at rest: mean |v_y| of the particles <= 1e-4 m/s (from exchange.csv);
  - the floor carries the bed's buoyant weight (rho_s - rho_l) g V_s within 1 % (0.1 s mean);
  - the liquid is at rest: max |U| in cells with alpha > 0.99 <= 1e-5 m/s (measured 1.4e-7);
  - the liquid is hydrostatic through the bed: dp/dy = -rho_l g within 1e-5 (relative) between
    vertically adjacent all-liquid cells (alpha > 0.999), bed cells included.
  - the bed stays where it settled: the particles' mean height changes by less than 0.01 d
    from 0.1 s to the end.
--settle S first settles the bed without the fluid, under its buoyant weight (--settle-under
buoyant: a bed settled in the liquid) or its full weight (dry: settled dry, then filled).
--liquid hb or bingham fills the box with the paper's Herschel-Bulkley liquid (rho 1000, tau_y
30.002 Pa, K 4.279 Pa s^n, n 0.479) or Bingham liquid (rho 1400, tau_y 2.1 Pa, mu_p 4 Pa s),
capped at 1e4 Pa s, with the default drag (its slip viscosity closure): a saturated bed at rest in
a yield-stress liquid must stay at rest with its pore liquid hydrostatic (the same checks).
--extract EXE also dumps the particle snapshots with their contact virial and the fluid every
0.05 s and runs mixflowExtract (EXE) on the bed (settled_bed_extract.py): the pore-pressure ratio
of the bed at rest must be its neutral value 0 within 0.05.
A double-counted or missing buoyancy fails both the floor and the pressure checks: --models
DiFeliceDrag (no buoyancy; registered as a negative control with --expect-fail) makes the floor
carry the full weight (+67 %).
"""

import argparse
import json
import math
import os
import sys

sys.dont_write_bytecode = True
from mixflow import coupledcase as cc  # noqa: E402
from mixflow import foamcase as fc  # noqa: E402
import settled_bed_extract  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--solver", required=True)
    ap.add_argument("--blockmesh", required=True)
    ap.add_argument("--workdir", required=True)
    ap.add_argument("--models", default="DiFeliceDrag buoyancy viscousForce")
    ap.add_argument("--end", type=float, default=0.5)
    ap.add_argument("--layers", type=int, default=4)
    ap.add_argument("--nu", type=float, default=1e-6,
                    help="kinematic viscosity of the liquid (m2/s; water 1e-6)")
    ap.add_argument("--liquid", choices=("newtonian", "hb", "bingham"), default="newtonian",
                    help="newtonian (--nu), or the paper's Herschel-Bulkley or Bingham liquid")
    ap.add_argument("--settle", type=float, default=0.0, metavar="S",
                    help="first settle the bed without the fluid for S s (--settle-under), so that "
                         "its contacts carry that weight before the liquid couples")
    ap.add_argument("--settle-under", choices=("buoyant", "dry"), default="buoyant",
                    help="buoyant: gravity x (1 - rho_l / rho_s), a bed settled in the liquid; "
                         "dry: full gravity, a bed settled dry and then filled (the scenes' "
                         "preparation)")
    ap.add_argument("--hydrostatic-tol", type=float, default=1e-5,
                    help="relative bound on |dp/dy + rho_l g| between liquid cells")
    ap.add_argument("--json", help="also write the measured numbers to this file")
    ap.add_argument("--extract", metavar="EXE",
                    help="mixflowExtract: dump snapshots, extract the bed and check its pore-"
                    "pressure ratio")
    ap.add_argument("--expect-fail", action="store_true",
                    help="negative control: pass only if the floor or pressure check fails")
    cc.add_parallel_args(ap)
    cc.add_fluid_response_arg(ap)
    a = ap.parse_args()

    d, rho_p = 2e-3, 2500.0
    # The paper's liquids (docs/model.md): rho, tau_y, K, n; capped at 1e4 Pa s.
    liquids = {"hb": (1000.0, 30.002, 4.279, 0.479), "bingham": (1400.0, 2.1, 4.0, 1.0)}
    rho_l = liquids[a.liquid][0] if a.liquid in liquids else 1000.0
    transport = (cc.transport_herschel_bulkley(*liquids[a.liquid], 1e4)
                 if a.liquid in liquids else None)
    box = cc.Box((0.03, 0.06, 0.03), (5, 10, 5))
    dt_dem, every = 1e-5, 100
    # Simple-cubic packing of spheres in contact (spacing d), touching the side walls and the
    # floor: the bed starts settled and the liquid at rest (a bed that falls in first leaves the
    # free surface sloshing for many seconds in water).
    m = int(round(box.L[0] / d))
    atoms = [((i + 0.5) * d, (j + 0.5) * d, (k + 0.5) * d)
             for j in range(a.layers) for i in range(m) for k in range(m)]
    Lx, Ly, Lz = box.L
    g_settle = cc.G * (1 - rho_l / rho_p) if a.settle_under == "buoyant" else cc.G
    dem = cc.liggghts_header(box, dt_dem, skin=0.25 * d, restitution=0.3, friction=0.0) + f"""fix wylo all wall/gran model hertz tangential history primitive type 1 yplane 0.0 store_force yes
fix wxlo all wall/gran model hertz tangential history primitive type 1 xplane 0.0
fix wxhi all wall/gran model hertz tangential history primitive type 1 xplane {Lx!r}
fix wzlo all wall/gran model hertz tangential history primitive type 1 zplane 0.0
fix wzhi all wall/gran model hertz tangential history primitive type 1 zplane {Lz!r}
fix integr all nve/sphere
""" + "".join(f"create_atoms 1 single {x!r} {y!r} {z!r} units box\n" for x, y, z in atoms) + \
        f"set group all diameter {d!r} density {rho_p!r}\n" + \
        "compute floorForce all reduce sum f_force_wylo[2]\n" + \
        (f"unfix gravi\nfix gravs all gravity {g_settle!r} vector 0 -1 0\n"
         f"run {int(round(a.settle / dt_dem))}\nunfix gravs\n"
         f"fix gravi all gravity {cc.G!r} vector 0 -1 0\n" if a.settle > 0 else "") + \
        f"fix floorOut all ave/time 1 {every} {every} c_floorForce file dem/floor.txt\n" + \
        (settled_bed_extract.dem_commands(dt_dem) if a.extract else "")
    coupling = f"""demScript "system/in.liggghts";
exchangeEvery {every};
forceModels ({a.models});
voidFractionModel divided;
""" + cc.fluid_response_entry(a)
    case = os.path.join(a.workdir, "case")
    write_steps = (int(round(settled_bed_extract.SNAPSHOT_S / (every * dt_dem))) if a.extract
                   else None)
    cc.write_case(case, box, a.end, every * dt_dem, dem, coupling, rho_l=rho_l, nu_l=a.nu,
                  liquid_height=0.045, open_top=True, transport_text=transport,
                  write_steps=write_steps)
    os.makedirs(os.path.join(case, "dem"), exist_ok=True)
    if a.extract:
        os.makedirs(os.path.join(case, "VTK", "particles"), exist_ok=True)
    cc.run(case, a.solver, a.blockmesh, np=a.np, mpiexec=a.mpiexec, decomposepar=a.decomposepar,
           reconstructpar=a.reconstructpar)

    rows = cc.read_exchange_log(case)
    t_end = rows[-1]["time"]
    win = [r for r in rows if r["time"] >= t_end - 0.1]
    vmean = max(abs(r["meanVy"]) for r in win)
    y_settled = min(rows, key=lambda r: abs(r["time"] - 0.1))["meanY"]
    drift = abs(rows[-1]["meanY"] - y_settled)
    floor = []
    with open(os.path.join(case, "dem", "floor.txt")) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            floor.append(tuple(float(v) for v in line.split()[:2]))
    n_floor = max(1, int(round(0.1 / (every * dt_dem))))
    f_floor = sum(v for _, v in floor[-n_floor:]) / len(floor[-n_floor:])
    vs = len(atoms) * math.pi * d ** 3 / 6
    buoyant_weight = (rho_p - rho_l) * cc.G * vs

    tdir = fc.latest_time(case)
    n = box.ncells
    rd = lambda name: fc.read_internal_field(os.path.join(case, tdir, name), n)
    alpha, U, p, eps = rd("alpha.water"), rd("U"), rd("p"), rd("voidfraction")
    umax = max(math.sqrt(sum(c * c for c in U[c])) for c in range(n) if alpha[c] > 0.99)
    nx, ny, nz = box.n
    worst, npairs, eps_min = 0.0, 0, min(eps)
    for k in range(nz):
        for i in range(nx):
            for j in range(ny - 1):
                c0, c1 = i + nx * (j + ny * k), i + nx * (j + 1 + ny * k)
                if alpha[c0] > 0.999 and alpha[c1] > 0.999:
                    g = (p[c1] - p[c0]) / box.h[1]
                    worst = max(worst, abs(g + rho_l * cc.G) / (rho_l * cc.G))
                    npairs += 1
    print(f"{len(atoms)} particles, V_s {vs:.5g} m3; end {t_end} s: max |mean v_y| (last 0.1 s) "
          f"{vmean:.3g} m/s, mean y {rows[-1]['meanY'] * 1e3:.2f} mm, min eps_f {eps_min:.3f}; "
          f"floor {f_floor:.6g} N vs (rho_s - rho_l) g V_s {buoyant_weight:.6g} N; liquid max |U| "
          f"{umax:.3g} m/s; dp/dy worst {worst:.3g} rel over {npairs} pairs")
    ok = True
    ok &= cc.check(vmean <= 1e-4, f"bed at rest: |mean v_y| {vmean:.3g} <= 1e-4 m/s")
    ok &= cc.check(drift <= 0.01 * d, f"bed stays where it settled: mean height moved "
                   f"{drift / d:.3g} d from 0.1 s to the end (tol 0.01 d)")
    floor_ok = abs(f_floor - buoyant_weight) <= 0.01 * buoyant_weight
    ok &= cc.check(floor_ok, f"floor carries the buoyant weight: {f_floor:.6g} N vs "
                   f"{buoyant_weight:.6g} N, {100 * (f_floor / buoyant_weight - 1):+.3f} % (tol 1 %)")
    ok &= cc.check(umax <= 1e-5, f"liquid at rest: max |U| {umax:.3g} <= 1e-5 m/s")
    p_ok = worst <= a.hydrostatic_tol and npairs > 0
    ok &= cc.check(p_ok, f"hydrostatic through the bed: worst |dp/dy + rho_l g| / rho_l g = "
                   f"{worst:.3g} (tol {a.hydrostatic_tol:g})")
    extracted = {}
    if a.extract:
        extracted = settled_bed_extract.run(a.extract, os.path.abspath(case),
                                            os.path.abspath(a.workdir), box, d, rho_p, rho_l,
                                            a.layers * d, t_end, dt_dem, cc.check)
        ok &= bool(extracted) and extracted["chi_max_abs"] <= settled_bed_extract.CHI_TOL
    if a.json:
        with open(a.json, "w") as f:
            json.dump({"liquid": a.liquid, "settled_under": a.settle_under if a.settle else None,
                       "end_s": t_end, "floor_over_buoyant_weight": f_floor / buoyant_weight,
                       "pressure_error": worst, "max_mean_vy_m_s": vmean,
                       "max_displacement_d": drift / d, "liquid_max_U_m_s": umax,
                       "extraction": extracted, "passes": bool(ok)}, f, indent=1)
    if a.expect_fail:
        caught = not (floor_ok and p_ok)
        cc.check(caught, "negative control: the floor/pressure checks must reject this run")
        sys.exit(0 if caught else 1)
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
