#!/usr/bin/env python3
"""Writes the packed-bed references of the non-Newtonian bed tests (tests/coupling/run_ergun.py
--liquid powerlaw|bingham) from the published capillary-bundle model, so that every number in
the tables comes from this command:

  python3 tests/reference/make_nonnewtonian_bed.py [--out tests/reference]

Christopher & Middleman (1965), Ind. Eng. Chem. Fundam. 4, 422-426 (Blake-Kozeny for a power-law
liquid): -dp/dx = H V^n / k, k = d^2 eps^3 / (150 (1 - eps)^2),
H = (K / 12) (9 + 3 / n)^n (150 k eps)^((1 - n) / 2). With 9 + 3/n = 12 (3n + 1) / (4n) this is
Ergun's viscous term 150 (1 - eps)^2 mu_e V / (eps^3 d^2) at mu_e = K ((3n + 1) / (4n))^n
rate^(n - 1), rate = 12 (1 - eps) V / (eps^2 d) (the pore-wall rate): both forms are evaluated
and must agree to 1e-12. The model's pore-wall stress is tau_w = (-dp/dx) eps d / (12.5 (1 - eps))
(the same relation at n = 1: tau_w = mu rate); a yield-stress liquid starts to flow when tau_w
reaches tau_y, i.e. at the threshold -dp/dx_c = 12.5 (1 - eps) tau_y / (eps d).
"""

import argparse
import os

# The bed of run_ergun.py (CFDEMcoupling's ErgunTestMPI: d 1 mm, eps 0.451335).
D, EPS = 1e-3, 0.451335
# The paper's HB liquid without its yield stress (K 4.279 Pa s^n, n 0.479), and its Bingham one.
POWERLAW = {"K": 4.279, "n": 0.479, "U": (0.002, 0.006, 0.01)}
BINGHAM_TAU = 2.1


def christopher_middleman(K, n, eps, d, U):
    k = d * d * eps ** 3 / (150 * (1 - eps) ** 2)
    H = K / 12 * (9 + 3 / n) ** n * (150 * k * eps) ** ((1 - n) / 2)
    return H * U ** n / k


def christopher_middleman_ergun_form(K, n, eps, d, U):
    rate = 12 * (1 - eps) * U / (eps * eps * d)
    mu_e = K * ((3 * n + 1) / (4 * n)) ** n * rate ** (n - 1)
    return 150 * (1 - eps) ** 2 * mu_e * U / (eps ** 3 * d * d)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", default=os.path.dirname(os.path.abspath(__file__)))
    a = ap.parse_args()
    with open(os.path.join(a.out, "powerlaw_bed_christopher_middleman.csv"), "w") as f:
        f.write(
            "# Creeping flow of a power-law liquid (tau = K rate^n) through a packed bed of spheres:\n"
            "# Christopher & Middleman (1965), Ind. Eng. Chem. Fundam. 4, 422-426, Blake-Kozeny form\n"
            "#   -dp/dx = H V^n / k, k = d^2 eps^3 / (150 (1-eps)^2), "
            "H = (K/12) (9 + 3/n)^n (150 k eps)^((1-n)/2)\n"
            "# = 150 (1-eps)^2 mu_e V / (eps^3 d^2), mu_e = K ((3n+1)/(4n))^n rate^(n-1), "
            "rate = 12 (1-eps) V / (eps^2 d).\n"
            "# V superficial velocity. Trust: the form as quoted in the secondary literature "
            "(Chhabra & Richardson,\n"
            "#   'Non-Newtonian Flow and Applied Rheology', and the spec); the paper's text was not "
            "reachable here.\n"
            "#   Kemblowski & Mertl (1974, Chem. Eng. Sci. 29, 213-223) generalise Ergun for power-law "
            "liquids: not used.\n"
            "# Liquid: the paper's HB liquid without its yield stress; bed: run_ergun.py's "
            "(CFDEM ErgunTestMPI d, eps).\n"
            "# Written by tests/reference/make_nonnewtonian_bed.py.\n")
        f.write("n,K_Pa_sn,eps,d_m,U_superficial_m_s,dpdx_CM_Pa_m\n")
        for U in POWERLAW["U"]:
            g1 = christopher_middleman(POWERLAW["K"], POWERLAW["n"], EPS, D, U)
            g2 = christopher_middleman_ergun_form(POWERLAW["K"], POWERLAW["n"], EPS, D, U)
            assert abs(g1 / g2 - 1) < 1e-12, (g1, g2)
            f.write(f"{POWERLAW['n']!r},{POWERLAW['K']!r},{EPS!r},{D!r},{U!r},{g1:.9g}\n")
    with open(os.path.join(a.out, "yield_stress_bed_threshold.csv"), "w") as f:
        alpha = 12.5 * (1 - EPS) / EPS
        f.write(
            "# Threshold pressure gradient of a yield-stress liquid in a packed bed of spheres, "
            "-dp/dx_c = alpha tau_y / d.\n"
            "# Chevalier, Chevalier, Clain, Dupla, Canou, Rodts & Coussot (2013), J. Non-Newtonian "
            "Fluid Mech. 195, 57-66\n"
            "#   (HAL hal-00946083): measured in bead packings, a threshold of this form followed by "
            "a Herschel-Bulkley-like\n"
            "#   Darcy law. Their alpha could not be read here (only the title page was reachable): "
            "NOT used.\n"
            "# alpha_capillary: the capillary-bundle (Blake-Kozeny) model of Christopher & Middleman "
            "(1965) with the pore-wall\n"
            "#   stress tau_w = (-dp/dx) eps d / (12.5 (1-eps)) reaching tau_y: alpha = 12.5 (1-eps)/eps. "
            "DERIVED; it is the\n"
            "#   same model the slip drag closure is built on, so a check against it verifies the "
            "coupled implementation of\n"
            "#   the closure's plastic limit, not the closure against experiments.\n"
            "# Written by tests/reference/make_nonnewtonian_bed.py.\n")
        f.write("eps,d_m,tau_y_Pa,alpha_capillary,dpdx_threshold_Pa_m\n")
        f.write(f"{EPS!r},{D!r},{BINGHAM_TAU!r},{alpha:.9g},{alpha * BINGHAM_TAU / D:.9g}\n")


if __name__ == "__main__":
    main()
