#!/usr/bin/env python3
"""Issue 4 test 2: pressure drop of a fixed packed bed vs Ergun, three velocities below minimum
fluidisation (tests/reference/ergun_cfdem_ErgunTestMPI.csv: CFDEMcoupling's ErgunTestMPI bed,
d 1 mm, eps 0.451335, rho_f 10 kg/m3, nu 1.5e-4 m2/s; U_mf = 0.0145 m/s).

Case: a column of 3 x 12 x 3 cells; the bed is a simple-cubic lattice of 9 x 15 x 9 fixed spheres
(no DEM integrator) with spacing s = d (pi / (6 (1 - eps)))^(1/3) = 0.9845 d, so that eps_f =
1 - V_p / s^3 = 0.451335 exactly; cells are 3 s wide and the lattice is aligned with them, so
every bed cell holds 27 centres (voidFractionModel centre, reaction in the centre cell).
Liquid enters at the bottom with the superficial velocity U (fixed value), leaves at the top
(p_rgh = 0); side walls slip. Forces: --drag (default GidaspowDrag: Ergun below eps_f 0.8)
+ buoyancy. Steady after a few steps; run 0.05 s.

Measured: the dynamic pressure gradient in the bed, G = -dp/dy - rho_f g, from the cell pressures
of the three middle bed-cell rows (away from the bed's ends), averaged over the column.
Pass (GidaspowDrag): G = dP_Ergun / L within 5 % for each U (the law's bed limit is Ergun, so the
remaining error is the coupling's). With --drag DiFeliceDrag the test compares G with the
Di Felice bed prediction n beta(U/eps) U/eps (same 5 %) and reports the deviation from Ergun:
Di Felice's correlation gives ~17-20 % less than Ergun at eps = 0.45 (not a coupling error).
"""

import argparse
import math
import os
import sys

sys.dont_write_bytecode = True
import coupledcase as cc  # noqa: E402
import foamcase as fc  # noqa: E402

D, EPS, L_REF, RHO, NU = 1e-3, 0.451335, 0.0156, 10.0, 1.5e-4


def difelice_beta_b(d, rho, mu, eps, slip):
    re = rho * d * eps * slip / mu
    chi = 3.7 - 0.65 * math.exp(-0.5 * (1.5 - math.log10(re)) ** 2)
    cd_slip = (0.63 * math.sqrt(slip) + 4.8 * math.sqrt(mu / (rho * d * eps))) ** 2
    return 0.125 * cd_slip * rho * math.pi * d * d * eps ** (2 - chi) / eps


def write_bed_case(case, U, drag, dt_dem=1e-5, every=100, end=0.05):
    s = D * (math.pi / (6 * (1 - EPS))) ** (1.0 / 3.0)
    h = 3 * s
    nx, ny, nz = 3, 12, 3
    box = cc.Box((nx * h, ny * h, nz * h), (nx, ny, nz))
    Lx, Ly, Lz = box.L
    y0 = 3 * h  # bed from 3 h to 8 h
    atoms = [((i + 0.5) * s, y0 + (j + 0.5) * s, (k + 0.5) * s)
             for j in range(15) for i in range(9) for k in range(9)]
    dem = cc.liggghts_header(box, dt_dem, skin=0.1 * D) + \
        "".join(f"create_atoms 1 single {x!r} {y!r} {z!r} units box\n" for x, y, z in atoms) + \
        f"set group all diameter {D!r} density 2000\n"  # no integrator: the bed is fixed
    coupling = f"""demScript "system/in.liggghts";
exchangeEvery {every};
dragIntegration held;  // the bed is not integrated by LIGGGHTS (DemLink.h)
forceModels ({drag} buoyancy);
voidFractionModel centre;
interpolation cell;
sourceDistribution centre;
"""
    cc.write_case(case, box, end, every * dt_dem, dem, coupling, rho_l=RHO, nu_l=NU)
    # Column boundaries instead of the closed box: inlet (bottom), outlet (top), slip sides.
    fc.write_foam_file(case, "system/blockMeshDict", "dictionary", "blockMeshDict", f"""convertToMeters 1;
vertices
(
    (0 0 0) ({Lx!r} 0 0) ({Lx!r} {Ly!r} 0) (0 {Ly!r} 0)
    (0 0 {Lz!r}) ({Lx!r} 0 {Lz!r}) ({Lx!r} {Ly!r} {Lz!r}) (0 {Ly!r} {Lz!r})
);
blocks ( hex (0 1 2 3 4 5 6 7) ({nx} {ny} {nz}) simpleGrading (1 1 1) );
edges ();
boundary
(
    inlet {{ type patch; faces ( (0 1 5 4) ); }}
    outlet {{ type patch; faces ( (3 7 6 2) ); }}
    sides {{ type wall; faces ( (0 4 7 3) (1 2 6 5) (0 3 2 1) (4 5 6 7) ); }}
);
mergePatchPairs ();
""")

    def bf(inlet, outlet, sides):
        return (f"boundaryField\n{{\n    inlet {{ {inlet} }}\n    outlet {{ {outlet} }}\n"
                f"    sides {{ {sides} }}\n}}\n")
    fc.write_foam_file(case, "0/alpha.water", "volScalarField", "alpha.water",
                       "dimensions [0 0 0 0 0 0 0];\ninternalField uniform 1;\n" +
                       bf("type fixedValue; value uniform 1;",
                          "type inletOutlet; inletValue uniform 1; value uniform 1;",
                          "type zeroGradient;"))
    fc.write_foam_file(case, "0/U", "volVectorField", "U",
                       "dimensions [0 1 -1 0 0 0 0];\ninternalField uniform (0 0 0);\n" +
                       bf(f"type fixedValue; value uniform (0 {U!r} 0);",
                          "type zeroGradient;", "type slip;"))
    fc.write_foam_file(case, "0/p_rgh", "volScalarField", "p_rgh",
                       "dimensions [1 -1 -2 0 0 0 0];\ninternalField uniform 0;\n" +
                       bf("type fixedFluxPressure; value uniform 0;",
                          "type fixedValue; value uniform 0;",
                          "type fixedFluxPressure; value uniform 0;"))
    return box, s, len(atoms)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--solver", required=True)
    ap.add_argument("--blockmesh", required=True)
    ap.add_argument("--reference", required=True, help="directory of the reference tables "
                    "(tests/reference)")
    ap.add_argument("--workdir", required=True)
    ap.add_argument("--drag", default="GidaspowDrag", choices=["GidaspowDrag", "DiFeliceDrag"])
    ap.add_argument("--velocities", default="0.002,0.006,0.01")
    ap.add_argument("--tol", type=float, default=0.05)
    a = ap.parse_args()

    ref_path = os.path.join(a.reference, "ergun_cfdem_ErgunTestMPI.csv")
    ok = True
    for u_txt in a.velocities.split(","):
        U = float(u_txt)
        ref = cc.read_reference(ref_path, "U_superficial_m_s", u_txt)
        ergun = float(ref["dP_Ergun_Pa"]) / L_REF  # Pa/m
        case = os.path.join(a.workdir, f"U{u_txt}")
        box, s, n_atoms = write_bed_case(case, U, a.drag)
        cc.run(case, a.solver, a.blockmesh)
        rows = cc.read_exchange_log(case)
        eps_min = rows[-1]["minVoidfraction"]
        tdir = fc.latest_time(case)
        p = fc.read_internal_field(os.path.join(case, tdir, "p"), box.ncells)
        nx, ny, nz = box.n
        grads = []
        for k in range(nz):
            for i in range(nx):
                for j in (4, 5):  # pairs (4,5), (5,6): bed rows 3..7, away from its ends
                    c0, c1 = i + nx * (j + ny * k), i + nx * (j + 1 + ny * k)
                    grads.append(-(p[c1] - p[c0]) / box.h[1] - RHO * cc.G)
        G = sum(grads) / len(grads)
        spread = (max(grads) - min(grads)) / abs(G)
        if a.drag == "GidaspowDrag":
            expected, what = ergun, "Ergun"
        else:
            vp = math.pi * D ** 3 / 6
            ur = U / EPS
            expected = (1 - EPS) / vp * difelice_beta_b(D, RHO, RHO * NU, EPS, ur) * ur
            what = "Di Felice bed prediction"
        print(f"U = {U} m/s: {n_atoms} fixed spheres, min eps_f {eps_min:.6f}; dynamic gradient "
              f"{G:.6g} Pa/m (spread over the column {spread:.2g}); Ergun {ergun:.6g} Pa/m "
              f"({100 * (G / ergun - 1):+.2f} %)")
        ok &= cc.check(abs(G - expected) <= a.tol * expected,
                       f"U = {U}: {G:.6g} vs {what} {expected:.6g} Pa/m, "
                       f"{100 * (G / expected - 1):+.3f} % (tol {100 * a.tol:g} %)")
        ok &= cc.check(abs(eps_min - EPS) <= 1e-9, f"bed eps_f {eps_min:.9f} = {EPS}")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
