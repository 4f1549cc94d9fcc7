#!/usr/bin/env python3
"""A bed settled dry, then filled with a yield-stress liquid: the pore suction it keeps, whether
the liquid's yield stress holds it, and how long it takes to drain where it does not.

Estimates (results/convergence/README.md, "Static saturated beds"):
- contacts that keep the dry weight leave the pore liquid carrying only its own weight,
  dp/dy = -eps rho_l g: a pressure gradient (1 - eps) rho_l g below hydrostatic, and a floor
  load rho_s / (rho_s - rho_l) times the buoyant weight;
- the drag holds a pore-pressure gradient up to n_p F_y, F_y the slip drag closure's plastic
  limit (Di Felice's Stokes part 3 pi mu d eps^-chi, chi 3.7, in formulation B, at the pore
  shear rate 12 (1 - eps) slip / (eps d)): n_p F_y = 18 (1 - eps) eps^(1 - chi) / (12 (1 - eps))
  tau_y / d = 1.5 eps^(1 - chi) tau_y / d;
- where the suction gradient exceeds it, the liquid flows into the pores at the slip that the
  viscous part of the drag (plastic viscosity; the cap where the yield stress holds) gives the
  excess, and the suction drains once the skeleton has rebounded by its Hertz unloading
  (contacts in simple-cubic columns, load (1 - eps) rho g z d^2): t = rebound / (eps slip).

usage: suction_estimate.py   (prints a table; no inputs)
"""
import math

G, RHO_S, NU, CHI = 9.81, 2500.0, 0.3, 3.7
# name: (rho_l, tau_y, plastic viscosity at the pore rate [Pa s], cap [Pa s])
LIQUIDS = {"HB": (1000.0, 30.002, None, 1e4), "Bingham": (1400.0, 2.1, 4.0, 1e4)}


def hertz_rebound(d, height, young, rho_l, eps, n=400):
    """Height the skeleton gains when its contacts unload from dry to buoyant weight."""
    e_star, r_star, dz = young / (2 * (1 - NU ** 2)), d / 4, height / n
    total = 0.0
    for i in range(n):
        z = (i + 0.5) * dz
        for rho, sign in ((RHO_S, 1.0), (RHO_S - rho_l, -1.0)):
            force = (1 - eps) * rho * G * z * d * d
            total += sign * (9 * force ** 2 / (16 * r_star * e_star ** 2)) ** (1 / 3) / d * dz
    return total


def threshold_gradient(tau_y, d, eps):
    return 1.5 * eps ** (1 - CHI) * tau_y / d


def drain_time(d, height, young, liquid, eps):
    rho_l, tau_y, mu_p, cap = LIQUIDS[liquid]
    suction = (1 - eps) * rho_l * G
    held = threshold_gradient(tau_y, d, eps)
    excess, mu = (suction - held, mu_p) if suction > held else (suction, cap)
    n_p = (1 - eps) / (math.pi * d ** 3 / 6)
    slip = excess / (n_p * 3 * math.pi * mu * d * eps ** -CHI)
    rebound = hertz_rebound(d, height, young, rho_l, eps)
    return suction, held, rebound, rebound / (eps * slip)


def main():
    print("bed                      liquid   E [Pa]   suction [Pa/m]  held [Pa/m]  rebound [m]  "
          "drains in [s]")
    beds = [("static bed 2 mm, 8 mm", 0.002, 0.008, 0.476, (5e6,)),
            ("scene 24 mm, 0.6 m", 0.024, 0.6, 0.4, (7e7, 7e8, 7e10))]
    for name, d, height, eps, youngs in beds:
        for liquid in LIQUIDS:
            for young in youngs:
                s, h, r, t = drain_time(d, height, young, liquid, eps)
                how = "" if s > h else "  (held by the yield stress: creep at the cap)"
                print(f"{name:24s} {liquid:8s} {young:8.1e} {s:14.0f} {h:12.0f} {r:12.2e} "
                      f"{t:12.3g}{how}")
    for liquid, (rho_l, *_rest) in LIQUIDS.items():
        print(f"{liquid}: floor load of a dry-settled bed / buoyant weight = "
              f"{RHO_S / (RHO_S - rho_l):.3f}")


if __name__ == "__main__":
    main()
