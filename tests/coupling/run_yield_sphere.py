#!/usr/bin/env python3
"""A lone grain of the paper (d 24 mm, rho_p 2500 kg/m3) released at rest in a closed box of a
yield-stress liquid, with each drag-viscosity closure (coupling/models/dragViscosity/DragViscosity.h): is it held or
does it settle, and how fast, against the published single-sphere results.

Case: the settling test's (run_settling.py): box 8 x 24 x 8 cells of 5 d, liquid everywhere,
DiFeliceDrag + buoyancy + viscousForce, implicit drag, exchange every 10 DEM steps of 1e-4 s,
0.6 s; the settling speed is the mean over the last 0.1 s.

Yield number Y = 3 tau_y / (g d (rho_p - rho_f)); Beris et al. (1985): a sphere is held for
Y > Y_crit = 0.143 (tests/reference/bingham_sphere.csv).

Scenarios (--liquid):
  bingham   the paper's Bingham liquid (rho 1400, mu_p 4 Pa s, tau_y 2.1 Pa, cap 1e4 Pa s),
            Y = 0.024, and the same liquid with tau_y raised to Y = 0.05 and 0.08: the grain
            settles, at Bingham numbers Bi = tau_y d / (mu_p V) of about 0.2, 0.5 and 1.0.
            Reference speed V: the published creeping-flow Bingham drag F = 3 pi mu_p d V
            (1 + k Bi) (Ansley & Smith's k = 7 pi / 24) times the Newtonian law's own finite-Re
            factor Cd Re / 24 (Di Felice, at Re = rho V d / mu_p), so that the check isolates the
            yield-stress part of the drag: F = (rho_p - rho_f) g pi d^3 / 6. Pass: within 10 % of
            V for the paper's liquid, within 15 % at the raised yield stresses (the correlation's
            own scatter grows with Bi: its plastic limit lies 21 % below the Beris onset,
            tests/reference/bingham_sphere.csv).
  hb        the paper's Herschel-Bulkley liquid (rho 1000, K 4.279 Pa s^n, n 0.479, tau_y
            30.002 Pa, cap 1e4 Pa s), Y = 0.255 > Y_crit: held. Pass: speed below 1e-3 of the
            speed the same grain has in a Newtonian liquid of the HB law's viscosity at V/d
            (i.e. without the yield stress).
  threshold Bingham liquids (rho 1400, mu_p 4 Pa s) at Y = 0.12 and 0.20, either side of Beris'
            0.143: the first settles (speed >= 0.1 of the tau_y = 0 speed), the second is held
            (below 1e-3 of it). The speed at Y = 0.12 (Bi about 2.7) is also held to the
            Ansley & Smith speed within 15 %, as in bingham.
  powerlaw  the paper's HB liquid without its yield stress (rho 1000, K 4.279 Pa s^n, n 0.479,
            cap 1e4 Pa s). Reference speed: the creeping power-law sphere drag F = 3 pi K V^n
            d^(2-n) X(n) (tests/reference/powerlaw_sphere_drag_correction.csv, X interpolated in n)
            times Di Felice's finite-Re factor at Re_PL = rho V^(2-n) d^n / K, as for bingham.
            Asserted with --assert-reference: within 10 % of it. Also asserted (slip): within
            10 % of the closure's own prediction, the same drag with the closure's shape factor
            at the grain's void fraction (X(n) weighted against the bed factor by the pore's
            share of the rate, about 5 % here); without powerLawShape the closure has X = 1 and
            its grain falls X^(1/n), about 2 times, too fast.
For each scenario the closure under test is --closure (default slip); the resolved closure is also
run with --also-resolved and its numbers printed (not judged: docs/parameters.md records them).
"""

import argparse
import math
import os
import sys

sys.dont_write_bytecode = True
from mixflow import coupledcase as cc  # noqa: E402

G = 9.81
D, RHO_P = 0.024, 2500.0


def difelice_factor(re):
    """Cd Re / 24 of Di Felice's Cd = (0.63 + 4.8 / sqrt(Re))^2."""
    return (0.63 * math.sqrt(re) + 4.8) ** 2 / 24.0


def terminal_speed(rho, drag):
    """The speed V at which drag(V) (increasing in V) equals the grain's buoyant weight."""
    w = (RHO_P - rho) * G * math.pi * D ** 3 / 6
    lo, hi = 1e-9, 10.0
    for _ in range(200):
        v = 0.5 * (lo + hi)
        lo, hi = (v, hi) if drag(v) < w else (lo, v)
    return 0.5 * (lo + hi)


def bingham_reference(rho, mu_p, tau, k):
    """Settling speed of the published creeping Bingham drag times Di Felice's finite-Re factor."""
    return terminal_speed(rho, lambda v: 3 * math.pi * mu_p * D * v *
                          (1 + k * tau * D / (mu_p * v)) * difelice_factor(rho * v * D / mu_p))


def newtonian_speed(rho, mu):
    """Settling speed with Di Felice's drag alone (Newtonian mu, unbounded)."""
    return terminal_speed(rho, lambda v: 3 * math.pi * mu * D * v *
                          difelice_factor(rho * v * D / mu))


def powerlaw_speed(rho, k, n, x):
    """Settling speed with the creeping power-law drag times X times Di Felice's finite-Re factor
    at Re_PL = rho V^(2-n) d^n / K (x = 1: the slip closure's own lone-grain drag)."""
    return terminal_speed(rho, lambda v: 3 * math.pi * k * v ** n * D ** (2 - n) * x *
                          difelice_factor(rho * v ** (2 - n) * D ** n / k))


def x_kawase_moo_young(n):
    return 3 ** ((3 * n - 3) / 2) * (33 * n ** 5 - 64 * n ** 4 - 11 * n ** 3 + 97 * n ** 2 +
                                     16 * n) / (4 * n * n * (n + 1) * (n + 2) * (2 * n + 1))


def settle(a, name, rho, tau, k, n, closure):
    """Runs the grain in the liquid with the closure; returns its mean settling speed (m/s)."""
    h = 5 * D
    box = cc.Box((8 * h, 24 * h, 8 * h), (8, 24, 8))
    x0 = (0.5 * box.L[0] + 0.1 * h, box.L[1] - 1.5 * h, 0.5 * box.L[2] + 0.13 * h)
    dt_dem, every = 1e-4, 10
    dem = cc.liggghts_header(box, dt_dem, skin=0.5 * D) + f"""fix integr all nve/sphere
create_atoms 1 single {x0[0]!r} {x0[1]!r} {x0[2]!r} units box
set atom 1 diameter {D!r} density {RHO_P!r}
"""
    coupling = f"""demScript "system/in.liggghts";
exchangeEvery {every};
forceModels (DiFeliceDrag buoyancy viscousForce);
dragIntegration implicit;
DiFeliceDragCoeffs {{ dragViscosity {closure}; }}
"""
    case = os.path.join(a.workdir, f"{name}_{closure}")
    cc.write_case(case, box, a.end, every * dt_dem, dem, coupling,
                  transport_text=cc.transport_herschel_bulkley(rho, tau, k, n, 1e4))
    cc.run(case, a.solver, a.blockmesh)
    rows = cc.read_exchange_log(case)
    win = [r for r in rows if r["time"] >= rows[-1]["time"] - 0.1]
    v = -sum(r["meanVy"] for r in win) / len(win)
    print(f"  {name}, dragViscosity {closure}: settling speed {v:.6g} m/s "
          f"(fell {1000 * (x0[1] - rows[-1]['meanY']):.3f} mm in {rows[-1]['time']:g} s)",
          flush=True)
    return v


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--solver", required=True)
    ap.add_argument("--blockmesh", required=True)
    ap.add_argument("--reference", required=True, help="tests/reference")
    ap.add_argument("--workdir", required=True)
    ap.add_argument("--liquid", required=True, choices=("bingham", "hb", "threshold", "powerlaw"))
    ap.add_argument("--assert-reference", action="store_true",
                    help="powerlaw: fail outside 10 %% of the X(n) speed")
    ap.add_argument("--closure", default="slip")
    ap.add_argument("--also-resolved", action="store_true")
    ap.add_argument("--end", type=float, default=0.6)
    a = ap.parse_args()
    ref = {}
    with open(os.path.join(a.reference, "bingham_sphere.csv")) as f:
        for line in f:
            if line.startswith("#") or line.startswith("quantity"):
                continue
            q, v = line.strip().split(",")
            ref[q] = float(v)
    ycrit, kx = ref["Y_crit"], ref["X_coefficient"]

    def yield_number(rho, tau):
        return 3 * tau / (G * D * (RHO_P - rho))

    ok = True
    closures = [a.closure] + (["resolved"] if a.also_resolved and a.closure != "resolved" else [])
    if a.liquid == "bingham":
        rho, mu = 1400.0, 4.0
        # (name, tau_y, tolerance): the paper's liquid, then tau_y raised to Y = 0.05 and 0.08.
        liquids = [("bingham", 2.1, 0.10)] + [
            (f"bingham_Y{y:g}", y * G * D * (RHO_P - rho) / 3, 0.15) for y in (0.05, 0.08)]
        for name, tau, tol in liquids:
            vref = bingham_reference(rho, mu, tau, kx)
            print(f"{name}: Y = {yield_number(rho, tau):.4f} (< {ycrit}: settles); reference "
                  f"speed {vref:.6g} m/s, Bi {tau * D / (mu * vref):.3g} (tau_y = 0: "
                  f"{newtonian_speed(rho, mu):.6g} m/s)")
            for cl in closures:
                v = settle(a, name, rho, tau, mu, 1.0, cl)
                err = v / vref - 1
                print(f"RESULT bingham_sphere name={name} closure={cl} Y={yield_number(rho, tau)!r} "
                      f"Bi={tau * D / (mu * vref)!r} measured={v!r} reference={vref!r} "
                      f"error={err!r} tolerance={tol!r}", flush=True)
                if cl == a.closure:
                    ok &= cc.check(abs(err) <= tol, f"{cl}, {name}: {v:.6g} m/s vs {vref:.6g} m/s "
                                   f"({100 * err:+.1f} %, within {100 * tol:g} %)")
    elif a.liquid == "hb":
        rho, k, n, tau = 1000.0, 4.279, 0.479, 30.002
        # Without the yield stress: the power-law viscosity at V/d, iterated to its fixed point.
        v0 = 0.05
        for _ in range(100):
            v0 = newtonian_speed(rho, k * (v0 / D) ** (n - 1))
        print(f"HB: Y = {yield_number(rho, tau):.4f} (> {ycrit}: held); without the yield stress "
              f"the grain settles at {v0:.4g} m/s")
        for cl in closures:
            v = settle(a, "hb", rho, tau, k, n, cl)
            if cl == a.closure:
                ok &= cc.check(abs(v) <= 1e-3 * v0, f"{cl}: held, {v:.3g} m/s "
                               f"(<= 1e-3 x {v0:.4g} m/s)")
    elif a.liquid == "powerlaw":
        rho, k, n = 1000.0, 4.279, 0.479
        x = cc.powerlaw_sphere_factor(a.reference, n)
        # The grain's void fraction in its 5 d cell (centre void fraction: one grain per cell).
        eps = 1 - (D / (5 * D)) ** 3 * math.pi / 6
        shape = cc.powerlaw_shape_factor(a.reference, n, eps)
        vref, vclosure = powerlaw_speed(rho, k, n, x), powerlaw_speed(rho, k, n, shape)
        xk = x_kawase_moo_young(n)
        print(f"power law n = {n}: X(n) = {x:.4f} (Kawase & Moo-Young {xk:.4f}); reference speed "
              f"{vref:.6g} m/s (with Kawase & Moo-Young's X {powerlaw_speed(rho, k, n, xk):.6g}); "
              f"the slip closure's own prediction (shape factor {shape:.4f} at eps_f {eps:.4f}) "
              f"{vclosure:.6g} m/s, Re_PL "
              f"{rho * vclosure ** (2 - n) * D ** n / k:.3g}")
        for cl in closures:
            v = settle(a, "powerlaw", rho, 0.0, k, n, cl)
            err = v / vref - 1
            print(f"RESULT powerlaw_sphere closure={cl} measured={v!r} reference={vref!r} "
                  f"error={err!r} closure_prediction={vclosure!r}", flush=True)
            if cl != a.closure:
                continue
            line = f"{cl}: {v:.6g} m/s vs X(n) speed {vref:.6g} m/s ({100 * err:+.1f} %, tol 10 %)"
            if a.assert_reference:
                ok &= cc.check(abs(err) <= 0.1, line)
            else:
                print(("  (reported) within " if abs(err) <= 0.1 else "  (reported) OUTSIDE ") +
                      line)
            if cl == "slip":
                ok &= cc.check(abs(v / vclosure - 1) <= 0.1,
                               f"slip: {v:.6g} m/s vs its own prediction {vclosure:.6g} m/s "
                               f"({100 * (v / vclosure - 1):+.1f} %, within 10 %)")
    else:
        rho, mu = 1400.0, 4.0
        v0 = newtonian_speed(rho, mu)
        for y in (0.12, 0.20):
            tau = y * G * D * (RHO_P - rho) / 3
            print(f"Y = {y} (tau_y {tau:.4g} Pa; Beris: {'held' if y > ycrit else 'settles'}); "
                  f"tau_y = 0 speed {v0:.6g} m/s")
            for cl in closures:
                v = settle(a, f"Y{y:g}", rho, tau, mu, 1.0, cl)
                if y < ycrit:
                    vref = bingham_reference(rho, mu, tau, kx)
                    err = v / vref - 1
                    print(f"RESULT bingham_sphere name=bingham_Y{y:g} closure={cl} Y={y!r} "
                          f"Bi={tau * D / (mu * vref)!r} measured={v!r} reference={vref!r} "
                          f"error={err!r} tolerance=0.15", flush=True)
                if cl != a.closure:
                    continue
                if y > ycrit:
                    ok &= cc.check(abs(v) <= 1e-3 * v0, f"{cl}, Y = {y}: held, {v:.3g} m/s "
                                   f"(<= 1e-3 x {v0:.4g})")
                else:
                    ok &= cc.check(v >= 0.1 * v0, f"{cl}, Y = {y}: settles at {v:.4g} m/s "
                                   f"(>= 0.1 x {v0:.4g})")
                    ok &= cc.check(abs(err) <= 0.15, f"{cl}, Y = {y}: {v:.4g} m/s vs Ansley & "
                                   f"Smith {vref:.4g} m/s ({100 * err:+.1f} %, within 15 %)")
    print("PASS" if ok else "FAIL")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
