#!/usr/bin/env python3
"""Action equals reaction, and the particle volume the fluid sees equals
the particles' volume, at every exchange of a coupled run.

Case: a box 3 x 6 x 3 cm of 6 mm cells (3 dp) open to the atmosphere at the top (so that the
fluid can give way to the particle volume entering the mesh), water up to 4 cm, air above; a cloud of
224 glass spheres (d 2 mm, 2500 kg/m3) on a jittered lattice between y = 4.5 and 8.4 cm. The
DEM box reaches y = 9 cm, above the fluid mesh, so the cloud starts partly outside the mesh
(centres above it: no fluid force, volume reported as outside; spheres straddling the lid:
split). The spheres fall through the air, cross the free surface and settle on the floor.
couplingProperties sets voidfractionMin 0.9 so that the eps_f floor clips the bed's cells
(reported as clipped volume). Forces: DiFeliceDrag, buoyancy, viscousForce.

Checks, at every exchange (postProcessing/coupling/exchange.csv):
  test 3: |sum_i F_i + sum_c V_c [Ksl (Us - U_c) + fSource]| / sum_i |F_i| <= 1e-10
          (the fluid receives exactly minus the particles' force; round-off only);
  test 4: |sum_c (1 - eps_f) V_c - (sum V_p - V_outside - V_clipped)| / sum V_p <= 1e-9;
and that the run exercised both corrections: outside volume > 0 at the start, clipped
volume > 0 at the end, all particles inside the mesh at the end, and the fluid forces were
not trivially zero (sum |F_i| at the end >= 0.9 x the cloud's buoyancy in water; the bed at
rest feels about its buoyancy, less the part of cells above the liquid).
With --np N the case runs on N ranks (OpenFOAM simple decomposition along x; 5 cells on 2 ranks
split 3 + 2 while LIGGGHTS halves the box, so some particles' cells are on the other rank than
their DEM owner): same checks, plus that such particles occurred.
With --rebalance S (and --np N) the DEM's x slabs are re-balanced by particles every S s
(system/demDict balanceInterval, `processors * 1 1` in the DEM script) and the cloud fills only the
box's first three lattice columns, so that the slabs move away from the fluid's: same checks, plus
that the run re-balanced and kept every particle.
"""

import argparse
import math
import os
import random
import sys

sys.dont_write_bytecode = True
from mixflow import coupledcase as cc  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--solver", required=True)
    ap.add_argument("--blockmesh", required=True)
    ap.add_argument("--workdir", required=True)
    ap.add_argument("--voidfraction", default="divided")
    ap.add_argument("--interpolation", default="cellPoint")
    ap.add_argument("--distribution", default="volume")
    ap.add_argument("--end", type=float, default=0.4)
    ap.add_argument("--tol-force", type=float, default=1e-10)
    ap.add_argument("--tol-volume", type=float, default=1e-9)
    ap.add_argument("--rebalance", type=float, default=0.0,
                    help="demDict balanceInterval (s) with x slabs; 0: LIGGGHTS' own grid")
    cc.add_parallel_args(ap)
    cc.add_fluid_response_arg(ap)
    a = ap.parse_args()

    d, rho_p, rho_l = 2e-3, 2500.0, 1000.0
    box = cc.Box((0.03, 0.06, 0.03), (5, 10, 5))
    dt_dem, every = 1e-5, 100
    rnd = random.Random(4242)
    atoms = []
    for j in range(14):
        for i in range(3 if a.rebalance > 0 else 4):
            for k in range(4):
                atoms.append((0.0045 + 0.007 * i + rnd.uniform(-5e-4, 5e-4),
                              0.045 + 0.003 * j + rnd.uniform(-3e-4, 3e-4),
                              0.0045 + 0.007 * k + rnd.uniform(-5e-4, 5e-4)))
    Lx, Ly, Lz = box.L
    dem_box = cc.Box((Lx, 0.09, Lz), (1, 1, 1))
    header = cc.liggghts_header(dem_box, dt_dem, skin=0.25 * d)
    if a.rebalance > 0:
        header = header.replace("region domain", "processors * 1 1\nregion domain", 1)
    dem = header + f"""fix wylo all wall/gran model hertz tangential history primitive type 1 yplane 0.0
fix wxlo all wall/gran model hertz tangential history primitive type 1 xplane 0.0
fix wxhi all wall/gran model hertz tangential history primitive type 1 xplane {Lx!r}
fix wzlo all wall/gran model hertz tangential history primitive type 1 zplane 0.0
fix wzhi all wall/gran model hertz tangential history primitive type 1 zplane {Lz!r}
fix integr all nve/sphere
""" + "".join(f"create_atoms 1 single {x!r} {y!r} {z!r} units box\n" for x, y, z in atoms) + \
        f"set group all diameter {d!r} density {rho_p!r}\n"
    coupling = f"""demScript "system/in.liggghts";
exchangeEvery {every};
forceModels (DiFeliceDrag buoyancy viscousForce);
voidFractionModel {a.voidfraction};
interpolation {a.interpolation};
sourceDistribution {a.distribution};
voidfractionMin 0.9;
""" + cc.fluid_response_entry(a)
    case = os.path.join(a.workdir, "case")
    cc.write_case(case, box, a.end, every * dt_dem, dem, coupling, rho_l=rho_l, nu_l=1e-6,
                  liquid_height=0.04, open_top=True)
    if a.rebalance > 0:
        with open(os.path.join(case, "system", "demDict"), "w") as f:
            f.write("FoamFile { version 2.0; format ascii; class dictionary; object demDict; }\n"
                    f"balanceInterval {a.rebalance!r};\n")
    log = cc.run(case, a.solver, a.blockmesh, np=a.np, mpiexec=a.mpiexec,
                 decomposepar=a.decomposepar)

    rows = cc.read_exchange_log(case)
    worst_f = max(r["actionReaction"] for r in rows)
    worst_v = max(abs(r["volumeError"]) for r in rows)
    first, last = rows[0], rows[-1]
    vp = last["particleVolume"]
    buoyancy = len(atoms) * rho_l * cc.G * math.pi * d ** 3 / 6
    print(f"{len(rows)} exchanges, {int(last['particles'])} particles; start: outside volume "
          f"{first['outsideVolume'] / vp:.3f} of the total, {int(first['particlesOutside'])} "
          f"centres outside; end: clipped {last['clippedVolume'] / vp:.3f}, mean y "
          f"{last['meanY'] * 1e3:.2f} mm, sum |F_i| {last['forceScale']:.4g} N "
          f"(buoyancy of the cloud in water {buoyancy:.4g} N)")
    ok = True
    ok &= cc.check(worst_f <= a.tol_force,
                   f"test 3, action = reaction at every exchange: worst |Fp + Ff| / sum |F| = "
                   f"{worst_f:.3g} (tol {a.tol_force:g})")
    ok &= cc.check(worst_v <= a.tol_volume,
                   f"test 4, fluid-seen volume = particle volume - outside - clipped at every "
                   f"exchange: worst relative error {worst_v:.3g} (tol {a.tol_volume:g})")
    ok &= cc.check(first["outsideVolume"] > 0 and first["particlesOutside"] > 0,
                   "outside-mesh accounting exercised at the start")
    ok &= cc.check(last["clippedVolume"] > 0, "eps_f floor (clipping) exercised at the end")
    ok &= cc.check(last["particlesOutside"] == 0 and last["outsideVolume"] < 1e-3 * vp,
                   "all particles inside the mesh at the end")
    if a.np > 1:
        remote = max(r["remote"] for r in rows)
        ok &= cc.check(remote > 0, f"{a.np} ranks: particles whose fluid cell is on another rank "
                       f"than their DEM owner went through the point-to-point exchange (up to "
                       f"{int(remote)} per exchange)")
    if a.rebalance > 0:
        ok &= cc.check("re-balanced by particles" in log and
                       int(last["particles"]) == len(atoms),
                       f"DEM slabs re-balanced every {a.rebalance:g} s, all {len(atoms)} particles "
                       f"kept ({int(last['particles'])} at the end)")
    ok &= cc.check(last["forceScale"] >= 0.9 * buoyancy,
                   "fluid forces not trivially zero (sum |F_i| >= 0.9 x the cloud's buoyancy)")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
