#!/usr/bin/env python3
"""A single sphere settling in a box of still liquid reaches the terminal velocity
of the Di Felice single-particle drag law.

Reference: tests/reference/terminal_velocity_single_sphere.csv, row --row (default 'glass 0.5 mm
in water': d 0.5 mm, rho_p 2500, water rho 1000 kg/m3, mu 1e-3 Pa s, u_DallaValle = 0.068219 m/s,
Re 34; Cd = (0.63 + 4.8/sqrt(Re))^2, unbounded fluid).

Case: closed box W x H x W, liquid everywhere (no free surface), cubic cells of --cell-dp
particle diameters (unresolved coupling needs cells several dp wide; the particle's own momentum
source also drives the fluid of its cell, and the larger the cell the less that self-induced
velocity matters), the sphere released at rest on the box axis near the top. Coupling: DiFeliceDrag
+ buoyancy (+ viscousForce), voidFractionModel divided, exchange every 100 DEM steps.
Pass: the particle's mean vertical velocity over the last --window seconds equals -u_ref within
--tol (3 %); it must have reached a steady state (change over the window <= 0.5 %).

--min-stiffness S (the stiff-drag test): the exchange interval T is so long that beta T / m >= S;
with S = 2 a drag held over the interval (dragIntegration held, dragRelaxationLimit 0) diverges
(it does beyond n s = 2, n = d ln F / d ln u = 1.43 here: s = 1.40; results/stability),
and the implicit drag (DemLink.h) must still give the terminal velocity within --tol.
"""

import argparse
import os
import sys

sys.dont_write_bytecode = True
from mixflow import coupledcase as cc  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--solver", required=True)
    ap.add_argument("--blockmesh", required=True)
    ap.add_argument("--reference", required=True, help="directory of the reference tables "
                    "(tests/reference)")
    ap.add_argument("--workdir", required=True)
    ap.add_argument("--row", default="glass 0.5 mm in water")
    ap.add_argument("--cell-dp", type=float, default=5.0)
    ap.add_argument("--width-cells", type=int, default=8)
    ap.add_argument("--height-cells", type=int, default=24)
    ap.add_argument("--dt-dem", type=float, default=1e-5)
    ap.add_argument("--exchange-every", type=int, default=100)
    ap.add_argument("--end", type=float, default=0.6)
    ap.add_argument("--window", type=float, default=0.1)
    ap.add_argument("--tol", type=float, default=0.03)
    ap.add_argument("--models", default="DiFeliceDrag buoyancy viscousForce")
    ap.add_argument("--voidfraction", default="divided")
    ap.add_argument("--interpolation", default="cell")
    ap.add_argument("--drag-integration", default="implicit", choices=("implicit", "held"))
    ap.add_argument("--relaxation-limit", type=float, default=0.5,
                    help="dragRelaxationLimit (held drag only; 0 = off)")
    ap.add_argument("--min-stiffness", type=float, default=0.0,
                    help="require beta T / m >= this (T the exchange interval): a stiff case")
    cc.add_parallel_args(ap)
    cc.add_fluid_response_arg(ap)
    a = ap.parse_args()

    ref = cc.read_reference(os.path.join(a.reference, "terminal_velocity_single_sphere.csv"),
                           "case", a.row)
    d, rho_p, rho_f, mu = (float(ref[k]) for k in ("d_m", "rho_p", "rho_f", "mu_Pa_s"))
    u_ref = float(ref["u_DallaValle"])
    print(f"reference '{a.row}': d {d} m, rho_p {rho_p}, rho_f {rho_f}, mu {mu} -> "
          f"u_t {u_ref} m/s (Re {ref['Re_DallaValle']})")

    h = a.cell_dp * d
    box = cc.Box((a.width_cells * h, a.height_cells * h, a.width_cells * h),
                 (a.width_cells, a.height_cells, a.width_cells))
    dt_cfd = a.exchange_every * a.dt_dem
    # Released at rest on the axis, 1.5 cells below the lid, slightly off the cell-face planes.
    x0 = (0.5 * box.L[0] + 0.1 * h, box.L[1] - 1.5 * h, 0.5 * box.L[2] + 0.13 * h)
    dem = cc.liggghts_header(box, a.dt_dem, skin=0.5 * d) + f"""fix integr all nve/sphere
create_atoms 1 single {x0[0]!r} {x0[1]!r} {x0[2]!r} units box
set atom 1 diameter {d!r} density {rho_p!r}
"""
    def settle(name, every, integration):
        """Runs the case with this exchange interval and drag integration; the exchange log."""
        case = os.path.join(a.workdir, name)
        coupling = f"""demScript "system/in.liggghts";
exchangeEvery {every};
forceModels ({a.models});
voidFractionModel {a.voidfraction};
interpolation {a.interpolation};
dragIntegration {integration};
dragRelaxationLimit {a.relaxation_limit!r};
""" + cc.fluid_response_entry(a)
        cc.write_case(case, box, a.end, every * a.dt_dem, dem, coupling, rho_l=rho_f,
                      nu_l=mu / rho_f)
        cc.run(case, a.solver, a.blockmesh, np=a.np, mpiexec=a.mpiexec,
               decomposepar=a.decomposepar, reconstructpar=a.reconstructpar)
        return cc.read_exchange_log(case)

    ok = True
    if a.min_stiffness:
        # beta at the terminal velocity: (m - m_f) g = beta u_t, so beta T / m = (1 - rho_f /
        # rho_p) g T / u_t.
        stiff = (1 - rho_f / rho_p) * 9.81 * dt_cfd / u_ref
        ok &= cc.check(stiff >= a.min_stiffness,
                       f"stiff case: beta T / m = {stiff:.3g} (>= {a.min_stiffness:g}; a drag held "
                       "over the interval without limit is unstable beyond 2 / n, n the drag's "
                       "log-slope d ln F / d ln u: 1.40 here at Re 34)")
    rows = settle("case", a.exchange_every, a.drag_integration)
    t_end = rows[-1]["time"]
    win = [r for r in rows if r["time"] >= t_end - a.window]
    half = len(win) // 2
    v = -sum(r["meanVy"] for r in win) / len(win)
    v1 = -sum(r["meanVy"] for r in win[:half]) / half
    v2 = -sum(r["meanVy"] for r in win[half:]) / (len(win) - half)
    fall = x0[1] - rows[-1]["meanY"]
    print(f"cells {h * 1e3:.3g} mm = {a.cell_dp} dp; fell {fall * 1e3:.2f} mm in {t_end} s; "
          f"settling velocity over the last {a.window} s: {v:.6g} m/s "
          f"(first half {v1:.6g}, second half {v2:.6g})")
    ok &= cc.check(abs(v - u_ref) <= a.tol * u_ref,
                   f"terminal velocity {v:.6g} m/s vs Di Felice {u_ref} m/s: "
                   f"{100 * (v - u_ref) / u_ref:+.3f} % (tol +-{100 * a.tol:g} %)")
    ok &= cc.check(abs(v2 - v1) <= 0.005 * u_ref,
                   f"steady over the window: change {100 * (v2 - v1) / u_ref:+.3f} % (tol 0.5 %)")
    ok &= cc.check(rows[-1]["particles"] == 1 and rows[-1]["particlesOutside"] == 0,
                   "particle still in the mesh")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
