#!/usr/bin/env python3
"""Verification of mixflowBulkFoam, the quasi two-phase bulk model (docs/bulk_model.md), on a
2-D 0.1 x 0.1 m column in a 0.6 x 0.15 m channel (5 mm cells). Scenarios (--scenario):

liquid-limit  solid fraction 0 with the Bingham pore liquid of the yield-slump test: the model is
              then the pore liquid alone, so the run must equal mixflowFoam's run of the same
              liquid (content liquid): front and kinetic energy at every row within 1e-6
              relative (solver tolerance; the viscosity is evaluated by another formula).
newtonian     lambda = 1, alpha_s 0.6, no yield stress (tanPhi 0, cohesion 0), nu_s 2e-3 m2/s:
              the reduced model (paper Eqs. 59-61) is a Newtonian liquid of density rho* and
              viscosity rho* (alpha_s nu_s + alpha_f nu_f): equal to mixflowFoam's run of that
              liquid within 1e-6 relative; liquid volume balance <= 1e-6.
cohesive-arrest  lambda = 1, alpha_s 0.6, tanPhi 0 and a cohesion tau_c: the mixture's stress is
              alpha_s tau_c rho*/rho_s (the paper's kinematic weighting), a Bingham slump of yield
              stress tau_eff = 50 Pa; its arrested length must be within 10 % of the shallow
              theory h(x) = sqrt(2 tau_eff (x_f - x) / (rho* g)) holding the column's area, and
              the kinetic energy must never exceed the potential energy released (no restart).
drifting      lambda_u = lambda_w = 1.3 on the newtonian mixture: the drift stress runs, the mixture
              volume balance stays <= 1e-6 and the front differs from lambda = 1's.
drift-fields  uniform drift fields constant/lambdaU, lambdaW, lambdaP (drifts { fields on; }) equal
              to constant drifts (1.3, 0.8, 0.6; the default solid, tanPhi 0.45): identical to the
              constant drifts' run bit for bit (time series and every written field file).
drift-field-range  a lambdaW field with 3 cells at -2 (allowed >= -1.475 at alpha_s 0.6):
              mixflowBulkFoam refuses it before the first step, naming constant/lambdaW, the
              field, the count of cells, the allowed range and the field's span.
closed-box    the newtonian mixture's column in a 0.3 x 0.15 m channel closed all round (outlet and
              top made walls, p_rgh fixed by a reference cell), 2 s: it collapses, runs up the
              end wall and sloshes. The mixture volume sum(alpha V) the solver logs every step
              equals the initial fields' within 1e-10 relative; alpha_s is constant (reduced
              model), so the solid volume is alpha_s times it: sum(alpha.solid V) of every write
              equals alpha_s V(0) within 1e-10, and so does the pore liquid's (1 - alpha_s) V.
              The alpha predictor (MULESCorr's implicit upwind step) is solved to 1e-13 instead
              of prepare's 1e-10: its residual is the only non-conservative term (1e-10 drifts
              ~1e-8 over the run; measured with 1e-13: 1.2e-11 over 585 steps).
pore-ratio-fields  uniform drift fields lambdaU, lambdaW, porePressureRatio (the default
              pressure closure; chi 0.3, tanPhi 0.45) equal to the constants: identical to the
              constants' run, whose front runs ahead of chi 0's (the ratio reaches the yield); a
              porePressureRatio field with 3 cells at 1.2 refused before the first step naming
              the file, the count and the range [-10, 1).
rest          a flat layer 0.05 m deep (10 cells, surface on a cell face) filling a 0.3 m channel
              (end wall closed, top open to the air) at rest for 2 s: the newtonian mixture and
              cohesive-arrest's (tau_eff 50 Pa). Pass: max |U| over the whole domain
              (air included) <= 1e-6 m/s at every write (0.5, 1, 1.5, 2 s; measured <= 6.6e-8 and
              3.2e-7 at 0.5 s falling to 1e-8). The force balance is exact on faces, so only the
              solver tolerance remains: p_rgh is solved to 1e-12 (cfdDict pressureTolerance); with
              prepare's auto 1e-7 the Newtonian layer creeps (1e-4 m/s in the mixture, 5e-4 in
              the air above, growing, and the surface smears into the air row). The pore
              pressure at the last write: p.fluid of every mixture cell against rho_f g (h - y)
              (the default pore-pressure ratio 0) within 2 %, and, in a third run of the
              Newtonian layer with drifts.porePressureRatio 0.5, against rho_f g (h - y) + 0.5
              alpha_s (rho_s - rho_f) g (h - y); control: lambdaP 2.75 (the total-pressure
              convention's value at rest) must miss rho_f g (h - y) by more than 50 %.
incline       steady uniform flow down a 10 degree incline: the newtonian mixture (nu = alpha_s nu_s
              + alpha_f nu_f = 1.2004e-3 m2/s) filling a layer h = 0.01 m deep on a no-slip bed,
              periodic in x (cyclic, 4 cells along 0.01 m), a stress-free top (slip wall: the
              domain is all mixture, no air; a free surface would need the air's own periodic
              flow to converge too), g = 9.81 (sin, -cos) theta. p = p_rgh + rho* g.x is periodic,
              so p_rgh carries the jump -rho* g_x L across the cycle (fixedJump): the solver is
              unchanged. 8, 16, 32 cells across the depth, steps of viscous number 2, to 2.4 s
              (29 h^2/nu). Exact u(y) = (g sin(theta) / nu) (h y - y^2 / 2), u_max 0.07096 m/s.
              Pass: steady (u at the last two writes within 1e-8 u_max); max error on 32 cells
              <= 5e-4 u_max (measured 2.441e-4); observed order of the L2 and max errors >= 1.8
              between successive meshes (measured 2.000, 2.000); the errors equal the scheme's
              exact discrete offset (g sin(theta)/nu) dy^2/8 = u_max / (4 n^2) within 1 %.
sliding-block a stiff mixture layer (the newtonian mixture with nu = 0.05 m2/s) 0.01 m deep,
              periodic in x (incline's machinery, horizontal), on the Coulomb bed mixflowPrepare
              writes for bulkProperties basal { law coulomb; tanDelta 0.3; }, free-slip top,
              sliding from u0 = 0.3 m/s. The bed stress tan(delta) p_m with p_m = (rho* -
              rho_air) g h decelerates it at g' tan(delta), g' = g (1 - rho_air/rho*): it stops at
              t_s = u0/(g' tan(delta)) = 0.102 s after u0^2/(2 g' tan(delta)) = 0.0153 m, E_k =
              E_k0 (1 - t/t_s)^2. Pass: deceleration (fit of the mean u between 0.9 and 0.1 u0)
              within 1 %, stop time (mean u <= 1e-3 u0) and distance (mean u integrated over the
              steps) within 2 %, at rest after 1.05 t_s, E_k/E_k0 of the 15 writes within 0.01
              of (1 - t/t_s)^2 (measured -0.15 %, +1.3 %, +0.13 %, 4.6e-4). The stop is late by
              the layer's viscous tail: the bed sticks while the shear across the depth, g
              tan(delta) h^2/(2 nu) = 1 % of u0, decays in ~h^2/nu. --case-basal runs the case
              with other basal entries against the same analytic solution (law noSlip; or
              tanDelta 0.28: both fail).
mui-incline   the mu(I) solid (solid { rheology muI; }, glass-bead defaults, d 1 mm) as a dry
              layer (pore gas of 1.2 kg/m3 without viscosity, lambda_p = 0: the gas carries no
              load) h = 0.01 m deep down a periodic 25 degree incline from rest (incline's
              machinery, p_m = 0 at the stress-free top), 8, 16, 32 cells, to 5 s. Exact: the
              Bagnold profile u(z) = (2/3)(I_theta/d) sqrt(phi g cos(theta)) [h^1.5 - (h - z)^1.5],
              I_theta = I_0 (tan(theta)/psi - mu_s)/(mu_2 - tan(theta)/psi), phi = (1 -
              rho_air/rho*)/alpha_s, psi = alpha_s phi (docs/bulk_model.md); u_surface 0.3413 m/s.
              Pass: steady (last two writes within 1e-3 u_surface); the top cell within 1 % of the
              exact value at its centre on 32 cells (measured -0.43 %); observed orders >= 1.8
              (L2) and >= 1.3 (max; the surface's (h - z)^1.5 makes it 1.5) on both refinements
              (measured 1.99, 2.00 and 1.49, 1.50).
mui-rest      the same layer (16 cells) at tan(theta) = 0.8 psi mu_s (16.99 degrees, below the
              static angle 20.90) for 1 s: the regularised law creeps at a uniform shear rate
              <= ln(mu_s/(mu_s - tan(theta)/psi))/m_y; pass: max |U| at every write <= h times it
              (1.61e-4 m/s; measured 0.959 of it, the top cell's centre lying dz/2 below h).
bad-input     constant/bulkProperties and cfdDict mixtureModel errors are refused by mixflowPrepare
              (exit 2, message naming file, entry and allowed range) before any file is written.
"""

import argparse
import math
import os
import re
import shutil
import subprocess
import sys

sys.dont_write_bytecode = True
import run_liquid_cases as lc  # noqa: E402
from mixflow import foamcase as fc  # noqa: E402
from mixflow import liquidcase  # noqa: E402

RHO_S = 2500.0
G = 9.81
BINGHAM = ("rheology Bingham; density 1000; yieldStress 17; plasticViscosity 1.5; "
           "viscosityCap 1e4; surfaceTension 0;")
WATER = "rheology Newtonian; density 1000; viscosity 0.001; surfaceTension 0;"
GEOMETRY = ("sample { length 0.1; height 0.1; width 0.1; solidFraction 0.6; }\n"
            "channel { length 0.6; height 0.15; }\n")
PARTICLES = f"particles {{ diameter 0.024; density {RHO_S:g}; }}\n"
CFD = "dimensions 2;\ncellSize 0.005;\n"


def bulk_case(work, name, liquid, bulk_props, end, write_interval=0.1, cfd=CFD):
    """A mixture scene run by the bulk model (cfdDict mixtureModel bulk)."""
    case = os.path.join(work, name)
    liquidcase.write_case(case, "content mixture;\n" + GEOMETRY + PARTICLES + f"liquid {{ {liquid} }}\n",
                  cfd + "mixtureModel bulk;\n", end, write_interval)
    hdr = "FoamFile { version 2.0; format ascii; class dictionary; object %s; }\n"
    with open(os.path.join(case, "system/demDict"), "w") as f:
        f.write(hdr % "demDict")
    with open(os.path.join(case, "constant/bulkProperties"), "w") as f:
        f.write(hdr % "bulkProperties" + bulk_props)
    return case


def liquid_case(work, name, liquid, end, write_interval=0.1):
    case = os.path.join(work, name)
    liquidcase.write_case(case, "content liquid;\n" + GEOMETRY + f"liquid {{ {liquid} }}\n", CFD, end,
                  write_interval)
    return case


def compare(bulk, ref, label, tol=1e-6):
    """Front and kinetic energy row by row (same adaptive steps if the runs agree)."""
    ok = lc.check(len(bulk) == len(ref), f"{label}: {len(bulk)} rows against {len(ref)}")
    worst = (0.0, "", 0.0)
    for b, r in zip(bulk, ref):
        for key in ("front_bed_m", "kinetic_energy_J"):
            floor = 1e-12 if key == "front_bed_m" else 1e-9 * ref[0]["potential_energy_J"]
            scale = max(abs(r[key]), floor)
            err = abs(b[key] - r[key]) / scale
            if err > worst[0]:
                worst = (err, key, r["time_s"])
    ok &= lc.check(worst[0] <= tol, f"{label}: largest relative difference {worst[0]:.2e} "
                   f"({worst[1]} at t = {worst[2]:g} s; <= {tol:g}); front at the end "
                   f"{bulk[-1]['front_bed_m']:.5f} m against {ref[-1]['front_bed_m']:.5f} m")
    return ok


# ------------------------------------------------------- cases edited after mixflowPrepare
NEWTONIAN_SOLID = "solid { viscosity 2e-3; tanPhi 0; cohesion 0; }\n"


def prepared(a, work, name, bulk_props, end, write_interval, scene_geometry=GEOMETRY, cfd=CFD,
             liquid=WATER):
    """A bulk case through mixflowPrepare (no mesh yet), to be edited: its transportProperties
    (the bulkMixture coefficients), fvSchemes and fvSolution are the ones a user gets."""
    case = os.path.join(work, name)
    liquidcase.write_case(case, "content mixture;\n" + scene_geometry + PARTICLES +
                  f"liquid {{ {liquid} }}\n", cfd + "mixtureModel bulk;\n", end, write_interval)
    hdr = "FoamFile { version 2.0; format ascii; class dictionary; object %s; }\n"
    with open(os.path.join(case, "system/demDict"), "w") as f:
        f.write(hdr % "demDict")
    with open(os.path.join(case, "constant/bulkProperties"), "w") as f:
        f.write(hdr % "bulkProperties" + bulk_props)
    fc.run([a.prepare, "-case", case, "-np", "1"], case, "log.mixflowPrepare")
    # Fields at full precision: the checks below go to 1e-10.
    with open(os.path.join(case, "system/controlDict"), "a") as f:
        f.write("writePrecision 17;\n")
    return case


def edit(case, rel, subs):
    """Regex substitutions in a case file; each must match."""
    path = os.path.join(case, rel)
    with open(path) as f:
        text = f.read()
    for pat, rep in subs:
        text, n = re.subn(pat, rep, text, flags=re.M)
        if n == 0:
            fc.fail(f"{path}: no match for {pat!r}")
    with open(path, "w") as f:
        f.write(text)


def close_patches(case, names):
    """Turn the open patches NAMES (outlet, atmosphere) into no-slip walls; the names stay, so
    liquidObservables still finds them (zero flux through a wall)."""
    for n in names:
        edit(case, "system/blockMeshDict", [(rf"^(\s*{n}\s*\{{\s*type )patch;", r"\1wall;")])
        edit(case, "0/U", [(rf"^(\s*{n}\s*)\{{.*\}}", r"\1{ type noSlip; }")])
        edit(case, "0/p_rgh", [(rf"^(\s*{n}\s*)\{{.*\}}",
                                r"\1{ type fixedFluxPressure; value uniform 0; }")])
        edit(case, "0/alpha.liquid", [(rf"^(\s*{n}\s*)\{{.*\}}", r"\1{ type zeroGradient; }")])
    if "atmosphere" in names:
        # No open boundary left: p_rgh is fixed by a reference cell.
        edit(case, "system/fvSolution", [(r"^PIMPLE\s*\{", "PIMPLE\n{\n    pRefCell 0;\n"
                                          "    pRefValue 0;")])


def mesh_size(case):
    """(nx, ny) of the 2-D block mixflowPrepare wrote into system/blockMeshDict."""
    with open(os.path.join(case, "system/blockMeshDict")) as f:
        return tuple(int(v) for v in re.search(r"hex \([^)]*\) \((\d+) (\d+) 1\)",
                                               f.read()).groups())


def flat_layer(case, depth):
    """Replace prepare's column by a layer filling the channel to DEPTH (a cell face)."""
    nx, ny = mesh_size(case)
    with open(os.path.join(case, "constant/sceneProperties")) as f:
        height = float(re.search(r"channel \{ length \S+; height ([^;]+);", f.read()).group(1))
    rows = round(depth / height * ny)
    values = "\n".join("1" if j < rows else "0" for j in range(ny) for i in range(nx))
    path = os.path.join(case, "0/alpha.liquid")
    with open(path) as f:
        text = f.read()
    text, n = re.subn(r"^internalField.*?^\)\s*;", f"internalField nonuniform List<scalar>\n"
                      f"{nx * ny}\n(\n{values}\n)\n;", text, flags=re.M | re.S)
    if n != 1:
        fc.fail(f"{path}: no internalField list")
    with open(path, "w") as f:
        f.write(text)

def run_bulk(a, case):
    """blockMesh and mixflowBulkFoam on an edited case; returns the solver log."""
    fc.run([a.blockmesh], case, "log.blockMesh")
    return fc.run([a.bulk_solver], case, "log.mixflowBulkFoam")


def field_times(case):
    return [name for t, name in fc.time_dirs(case) if t > 0]


def steady_end(case, scale):
    """The last written U, and how far it moved from the write before (max |du_x| / scale)."""
    times = field_times(case)
    last, prev = (fc.read_internal_field(os.path.join(case, t, "U")) for t in times[-1:-3:-1])
    change = max(abs(u[0] - v[0]) for u, v in zip(last, prev)) / scale
    return f"max |u({times[-1]}) - u({times[-2]})| {change:.1e}", last, change


def liquid_limit(a, work):
    bulk = bulk_case(work, "bulk_alpha0", BINGHAM, "solidFraction 0;\n", 0.5)
    ref = liquid_case(work, "liquid_bingham", BINGHAM, 0.5)
    return compare(liquidcase.run_case(a, bulk, solver=a.bulk_solver), liquidcase.run_case(a, ref),
                   "alpha_s = 0 vs mixflowFoam")


def newtonian(a, work):
    alpha, nu_s, nu_f, rho_f = 0.6, 2e-3, 1e-6, 1000.0
    rho = alpha * RHO_S + (1 - alpha) * rho_f
    mu = rho * (alpha * nu_s + (1 - alpha) * nu_f)
    bulk = bulk_case(work, "bulk_newtonian", WATER,
                     f"solid {{ viscosity {nu_s}; tanPhi 0; cohesion 0; }}\n", 0.5)
    ref = liquid_case(work, "liquid_newtonian",
                      f"rheology Newtonian; density {rho:.10g}; viscosity {mu:.10g}; "
                      "surfaceTension 0;", 0.5)
    sb = liquidcase.run_case(a, bulk, solver=a.bulk_solver)
    ok = compare(sb, liquidcase.run_case(a, ref), f"lambda = 1, Newtonian solid vs liquid of "
                 f"rho {rho:g} kg/m3, mu {mu:.4g} Pa s")
    bal = max(abs(r["volume_balance"]) for r in sb)
    ok &= lc.check(bal <= 1e-6, f"mixture volume balance max {bal:.2e} (<= 1e-6)")
    return ok


def cohesive_arrest(a, work):
    alpha, rho_f, tau_eff, mu_p, cap = 0.6, 1000.0, 50.0, 1.5, 1e4
    rho = alpha * RHO_S + (1 - alpha) * rho_f
    # Kinematic stress alpha_s nu_se |D| times rho*: tau_eff = rho* alpha_s tau_c / rho_s.
    tau_c = tau_eff * RHO_S / (rho * alpha)
    nu_s = mu_p / (rho * alpha)
    m_y = cap / tau_eff  # viscosity at rest rho* alpha_s (nu_s + m_y tau_c / rho_s) ~ cap
    case = bulk_case(work, "bulk_cohesive", WATER,
                     f"solid {{ viscosity {nu_s:.10g}; tanPhi 0; cohesion {tau_c:.10g}; "
                     f"regularisation {m_y:g}; }}\n", 4.0, 1.0)
    s = liquidcase.run_case(a, case, solver=a.bulk_solver)
    pe0 = s[0]["potential_energy_J"]
    excess = max(r["kinetic_energy_J"] - (pe0 - r["potential_energy_J"]) for r in s)
    ok = lc.check(excess <= 1e-4 * pe0, f"E_k - E_p released max {excess / pe0:+.2e} E_p0 (<= 1e-4)")
    end = s[-1]
    ok &= lc.check(end["kinetic_energy_J"] <= 1e-6 * pe0,
                   f"arrested at t = {end['time_s']:g} s: E_k {end['kinetic_energy_J'] / pe0:.2e} "
                   "E_p0 (<= 1e-6)")
    xf_theory = lc.arrest_length(tau_eff, rho)
    xf = end["front_bed_m"]
    err = (xf - xf_theory) / xf_theory
    ok &= lc.check(abs(err) <= 0.10, f"arrested front {xf:.4f} m against the shallow theory "
                   f"{xf_theory:.4f} m for tau_eff {tau_eff:g} Pa, rho* {rho:g}: {100 * err:+.1f} % "
                   "(<= 10 %)")
    return ok


BAD = [
    ("solid fraction above packing", "solidFraction 0.7;\n",
     ["constant/bulkProperties", "solidFraction", "[0, 0.64]"]),
    ("unknown solid entry", "solid { frictionAngle 30; }\n",
     ["constant/bulkProperties", "frictionAngle", "tanPhi"]),
    ("drift making alpha_s + lambda alpha_f vanish", "drifts { lambdaU -1.6; }\n",
     ["constant/bulkProperties", "drifts.lambdaU", "-1.475"]),
    ("yield pressure word", "solid { yieldPressure effective; }\n",
     ["constant/bulkProperties", "yieldPressure", "buoyancyReduced"]),
    ("basal friction above range", "basal { law coulomb; tanDelta 6; }\n",
     ["constant/bulkProperties", "basal.tanDelta", "[0, 5]"]),
    ("negative basal friction", "basal { law coulomb; tanDelta -0.1; }\n",
     ["constant/bulkProperties", "basal.tanDelta", "[0, 5]"]),
    ("basal law word", "basal { law slip; }\n",
     ["constant/bulkProperties", "basal.law", "coulomb"]),
    ("drift fields without their files", "drifts { fields on; }\n",
     ["constant/bulkProperties", "fields", "constant/lambdaU"]),
    ("time-varying drifts without fields", "drifts { timeVarying on; }\n",
     ["constant/bulkProperties", "timeVarying", "needs fields on"]),
    ("time-varying drift fields without windows", "drifts { fields on; timeVarying on; }\n",
     ["constant/bulkProperties", "timeVarying", "constant/drifts", "holds no window"]),
    ("drift interpolation without time-varying fields", "drifts { interpolation nearest; }\n",
     ["constant/bulkProperties", "interpolation", "timeVarying on"]),
    ("drift interpolation word", "drifts { interpolation cubic; }\n",
     ["constant/bulkProperties", "interpolation", "linear", "nearest"]),
    ("solid rheology word", "solid { rheology bagnold; }\n",
     ["constant/bulkProperties", "rheology", "coulombViscoplastic", "muI"]),
    ("Coulomb entry with muI", "solid { rheology muI; tanPhi 0.4; }\n",
     ["constant/bulkProperties", "tanPhi", "not a parameter of rheology muI"]),
    ("muI entry with the Coulomb law", "solid { muS 0.4; }\n",
     ["constant/bulkProperties", "muS", "not a parameter of rheology coulombViscoplastic"]),
    ("mu2 below muS", "solid { rheology muI; muS 0.5; mu2 0.4; }\n",
     ["constant/bulkProperties", "mu2", "[muS, 5]"]),
    ("muI without regularisation", "solid { rheology muI; regularisation 0; }\n",
     ["constant/bulkProperties", "regularisation", "(0, 1e5]"]),
    ("muI grain diameter above range", "solid { rheology muI; grainDiameter 2; }\n",
     ["constant/bulkProperties", "grainDiameter", "(0, 1]"]),
    ("pore-pressure ratio at 1 (liquefied: the end of the range is open)",
     "drifts { porePressureRatio 1; }\n",
     ["constant/bulkProperties", "drifts.porePressureRatio", "[-10, 1)"]),
    ("lambdaP with the pore-pressure ratio", "drifts { lambdaP 1.2; }\n",
     ["constant/bulkProperties", "lambdaP", "not a parameter of pressure porePressureRatio"]),
    ("pressure closure word", "drifts { pressure effective; }\n",
     ["constant/bulkProperties", "drifts.pressure", "porePressureRatio", "lambdaP"]),
]


def bad_input(a, work):
    ok = True
    for name, props, expected in BAD:
        case = bulk_case(work, "bad_" + re.sub(r"\W+", "_", name), WATER, props, 1.0)
        ok &= lc.refused(a.prepare, case, name, expected)
    # The bulk model needs a mixture.
    case = liquid_case(work, "bad_liquid_bulk", WATER, 1.0)
    with open(os.path.join(case, "system/cfdDict"), "a") as f:
        f.write("mixtureModel bulk;\n")
    ok &= lc.refused(a.prepare, case, "mixtureModel bulk for a liquid",
                     ["system/cfdDict", "mixtureModel", "content is liquid"])
    # The solver checks bulkMixtureCoeffs against its declaration before the first step: a value
    # edited out of range, and an undeclared entry.
    for name, edit, expected in (
            ("porePressureRatio 1.5", (r"porePressureRatio +[^;]+;", "porePressureRatio 1.5;"),
             ["porePressureRatio", "1.5", "[-10, 1)"]),
            ("unknown entry", (r"(relaxation +[^;]+;)", r"\1 frictionAngle 30;"),
             ["frictionAngle", "unknown entry"])):
        case = prepared(a, work, "bad_coeffs_" + re.sub(r"\W+", "_", name), "", 0.01, 0.01)
        path = os.path.join(case, "constant/transportProperties")
        with open(path) as f:
            text = re.sub(edit[0], edit[1], f.read())
        with open(path, "w") as f:
            f.write(text)
        fc.run([a.blockmesh], case, "log.blockMesh")
        r = subprocess.run([a.bulk_solver, "-case", case], capture_output=True, text=True)
        msg = r.stdout + r.stderr
        missing = [e for e in expected + ["bulkMixtureCoeffs"] if e not in msg]
        ok &= lc.check(r.returncode != 0 and not missing and "Time = " not in msg,
                       f"mixflowBulkFoam refuses bulkMixtureCoeffs {name} before the first step "
                       f"(exit {r.returncode}; missing {missing})")
    return ok


def drifting(a, work):
    """Drifts lambda_u = lambda_w = 1.3 (about W&P's calibrated ones) on the newtonian scenario's
    mixture: the drift stress runs end to end, keeps the mixture volume (a momentum source only)
    and changes the flow against lambda = 1."""
    solid = "solid { viscosity 2e-3; tanPhi 0; cohesion 0; }\n"
    ref = bulk_case(work, "bulk_no_drift", WATER, solid, 0.3)
    drift = bulk_case(work, "bulk_drift", WATER,
                      solid + "drifts { pressure lambdaP; lambdaU 1.3; lambdaW 1.3; lambdaP 1; }\n", 0.3)
    sr = liquidcase.run_case(a, ref, solver=a.bulk_solver)
    sd = liquidcase.run_case(a, drift, solver=a.bulk_solver)
    bal = max(abs(r["volume_balance"]) for r in sd)
    ok = lc.check(bal <= 1e-6, f"mixture volume balance with drifts max {bal:.2e} (<= 1e-6)")
    fr, fd = sr[-1]["front_bed_m"], sd[-1]["front_bed_m"]
    ok &= lc.check(abs(fd - fr) > 1e-3 * fr,
                   f"the drift stress changes the front at {sd[-1]['time_s']:.2f} s: {fd:.5f} m "
                   f"against {fr:.5f} m with lambda = 1")
    return ok


def drift_field_file(case, name, internal, window=None):
    """constant/NAME, a drift field (bulkProperties drifts { fields on; }), or with WINDOW (its
    time name) constant/drifts/WINDOW/NAME, a window of time-varying ones: INTERNAL is 'uniform V'
    or a list of cell values."""
    if not isinstance(internal, str):
        internal = fc.format_scalar_list(internal)
    rel = f"constant/drifts/{window}/{name}" if window else "constant/" + name
    os.makedirs(os.path.dirname(os.path.join(case, rel)), exist_ok=True)
    fc.write_foam_file(case, rel, "volScalarField", name,
                          f"dimensions [0 0 0 0 0 0 0];\ninternalField {internal};\n"
                          "boundaryField\n{\n    \".*\" { type zeroGradient; }\n"
                          "    #includeEtc \"caseDicts/setConstraintTypes\"\n}\n")


FIELD_DRIFTS = {"lambdaU": 1.3, "lambdaW": 0.8, "lambdaP": 0.6}
# The drift cases set lambda_p, the closure of the paper (bulkProperties drifts.pressure).
PRESSURE_LAMBDA_P = "pressure lambdaP; "


def field_drift_case(work, name, windows=(), end=0.3, write_interval=0.1, extra=""):
    """A bulk case with the drift constants FIELD_DRIFTS and drifts { fields on; }: the fixed
    fields or, with WINDOWS (time names), time-varying ones (EXTRA: more drifts entries), every
    file uniform at the constants."""
    consts = PRESSURE_LAMBDA_P + "".join(f"{k} {v:g}; " for k, v in FIELD_DRIFTS.items())
    varying = "timeVarying on; " if windows else ""
    case = bulk_case(work, name, WATER, f"drifts {{ {consts}fields on; {varying}{extra}}}\n", end,
                     write_interval)
    for window in windows or [None]:
        for k, v in FIELD_DRIFTS.items():
            drift_field_file(case, k, f"uniform {v:g}", window)
    return case


def drift_fields(a, work):
    """Uniform drift fields equal to constant drifts: the run is the constant drifts' run bit for
    bit (every time-series row and every written field file identical). The default solid (tanPhi
    0.45: the yield pressure's kappa_y and Lambda_p take lambda_p per cell) and
    lambda = (1.3, 0.8, 0.6), so each place the drifts enter is exercised."""
    consts = PRESSURE_LAMBDA_P + "".join(f"{k} {v:g}; " for k, v in FIELD_DRIFTS.items())
    ref = bulk_case(work, "bulk_drift_constants", WATER, f"drifts {{ {consts}}}\n", 0.3)
    fld = field_drift_case(work, "bulk_drift_fields")
    liquidcase.run_case(a, ref, solver=a.bulk_solver)
    liquidcase.run_case(a, fld, solver=a.bulk_solver)
    log = open(os.path.join(fld, "log.mixflowBulkFoam")).read()
    ok = lc.check("drifts the fields constant/lambdaU" in log and "drift field" in log,
                  "the fields run reads constant/lambdaU, lambdaW, lambdaP")
    return ok & identical_runs(ref, fld)


def series_rows(case, before=math.inf):
    """The rows of the case's time series (postProcessing/liquid/timeSeries.csv) as text, those
    of times before BEFORE."""
    with open(os.path.join(case, "postProcessing/liquid/timeSeries.csv")) as f:
        lines = f.read().splitlines()
    head = [ln for ln in lines if not ln[:1].isdigit()]
    return head + [ln for ln in lines if ln[:1].isdigit() and float(ln.split(",")[0]) < before]


def identical_runs(ref, run, before=math.inf):
    """RUN's time series rows and written field files byte for byte equal to REF's, those of
    times before BEFORE."""
    sr, sf = series_rows(ref, before), series_rows(run, before)
    upto = f" before t = {before:g} s" if before < math.inf else ""
    ok = lc.check(len(sr) > 10 and sr == sf,
                  f"time series{upto}: {len(sf)} lines against {len(sr)}, byte for byte "
                  f"identical: {sr == sf}")
    times = [t for t in field_times(ref) if float(t) < before]
    differ = []
    for t in times:
        for name in sorted(os.listdir(os.path.join(ref, t))):
            pr, pf = os.path.join(ref, t, name), os.path.join(run, t, name)
            if os.path.isfile(pr) and (not os.path.isfile(pf) or
                                       open(pr, "rb").read() != open(pf, "rb").read()):
                differ.append(f"{t}/{name}")
    ok &= lc.check(times and times == [t for t in field_times(run) if float(t) < before] and
                   not differ, f"written fields at {', '.join(times)} s byte for byte identical "
                   f"(differing: {differ[:5] or 'none'})")
    return ok


def drift_field_range(a, work, window=None):
    """A drift field with cells outside alpha_s + lambda alpha_f >= 0.01 is refused by
    mixflowBulkFoam before the first step, naming the file, the field, the count and the range;
    with WINDOW, that window of time-varying fields (the others in range)."""
    windows = SERIES_WINDOWS if window else ()
    case = field_drift_case(work, "bulk_drift_field_range", windows)  # prepare wants the files
    fc.run([a.prepare, "-case", case, "-np", "1"], case, "log.mixflowPrepare")
    nx, ny = mesh_size(case)
    values = [0.8] * (nx * ny)
    for c in (5, 77, 1000):
        values[c] = -2.0  # alpha_s 0.6: allowed lambda >= (0.01 - 0.6) / 0.4 = -1.475
    drift_field_file(case, "lambdaW", values, window)
    fc.run([a.blockmesh], case, "log.blockMesh")
    r = subprocess.run([a.bulk_solver, "-case", case], capture_output=True, text=True,
                          env=fc.run_env())
    msg = r.stdout + r.stderr
    file = f"constant/drifts/{window}/lambdaW" if window else "constant/lambdaW"
    want = [file, "field lambdaW", f"3 of {nx * ny} cells", "-1.475", "[-2, 0.8]"]
    missing = [w for w in want if w not in msg]
    line = next((ln for ln in msg.splitlines() if "lambdaW" in ln and "outside" in ln), "")
    ok = lc.check(r.returncode != 0 and not missing, f"refused (exit {r.returncode}): {line.strip()}"
                  + (f"; missing {missing}" if missing else ""))
    ok &= lc.check(not field_times(case) and "Time = " not in msg,
                   "before the first step: no time step taken, no time directory written")
    return ok


# The pore-pressure ratio as a drift field (the default closure): lambda_u, lambda_w as
# FIELD_DRIFTS, chi 0.3 (the yield (1 - chi)(1 - rho_f/rho_s) p_m with the default tanPhi 0.45).
RATIO_DRIFTS = {"lambdaU": 1.3, "lambdaW": 0.8, "porePressureRatio": 0.3}


def pore_ratio_fields(a, work):
    """Uniform fields lambdaU, lambdaW, porePressureRatio equal to the constants give the
    constants' run bit for bit (the closure takes chi per cell); a porePressureRatio field with 3
    cells at 1.2 is refused before the first step, naming the file, the count and [-10, 1)."""
    consts = "".join(f"{k} {v:g}; " for k, v in RATIO_DRIFTS.items())
    ref = bulk_case(work, "bulk_ratio_constants", WATER, f"drifts {{ {consts}}}\n", 0.3)
    fld = bulk_case(work, "bulk_ratio_fields", WATER, f"drifts {{ {consts}fields on; }}\n", 0.3)
    for k, v in RATIO_DRIFTS.items():
        drift_field_file(fld, k, f"uniform {v:g}")
    neutral = bulk_case(work, "bulk_ratio_neutral", WATER,
                        "drifts { lambdaU 1.3; lambdaW 0.8; porePressureRatio 0; }\n", 0.3)
    sr = liquidcase.run_case(a, ref, solver=a.bulk_solver)
    liquidcase.run_case(a, fld, solver=a.bulk_solver)
    sn = liquidcase.run_case(a, neutral, solver=a.bulk_solver)
    log = open(os.path.join(fld, "log.mixflowBulkFoam")).read()
    ok = lc.check("drift field" in log and "constant/porePressureRatio" in log,
                  "the fields run reads constant/porePressureRatio")
    ok &= identical_runs(ref, fld)
    # The ratio reaches the yield: chi 0.3 takes 30 % of the grains' friction, so the front runs
    # ahead of chi 0's.
    fr, fn = sr[-1]["front_bed_m"], sn[-1]["front_bed_m"]
    ok &= lc.check(fr > fn * (1 + 1e-3), f"chi 0.3 lowers the friction: front at "
                   f"{sr[-1]['time_s']:.2f} s {fr:.5f} m against {fn:.5f} m with chi 0")
    bad = bulk_case(work, "bulk_ratio_field_range", WATER, f"drifts {{ {consts}fields on; }}\n",
                    0.3)
    for k, v in RATIO_DRIFTS.items():
        drift_field_file(bad, k, f"uniform {v:g}")
    fc.run([a.prepare, "-case", bad, "-np", "1"], bad, "log.mixflowPrepare")
    nx, ny = mesh_size(bad)
    values = [0.3] * (nx * ny)
    for c in (5, 77, 1000):
        values[c] = 1.2
    drift_field_file(bad, "porePressureRatio", values)
    fc.run([a.blockmesh], bad, "log.blockMesh")
    r = subprocess.run([a.bulk_solver, "-case", bad], capture_output=True, text=True,
                       env=fc.run_env())
    msg = r.stdout + r.stderr
    want = ["constant/porePressureRatio", f"3 of {nx * ny} cells", "[-10, 1)", "[0.3, 1.2]"]
    missing = [w for w in want if w not in msg]
    ok &= lc.check(r.returncode != 0 and not missing and "Time = " not in msg,
                   f"a porePressureRatio field with 3 cells at 1.2 refused before the first step "
                   f"(exit {r.returncode})" + (f"; missing {missing}" if missing else ""))
    return ok


# ------------------------------------------------------------------ time-varying drift fields
SERIES_WINDOWS = ("0.05", "0.15", "0.25")


def drift_series(a, work):
    """Time-varying drift fields whose windows (0.05, 0.15, 0.25 s) all equal the constants
    (1.3, 0.8, 0.6): the run is the constant drifts' run bit for bit (time series and every
    written field file), the drifts being brought to the time at every step."""
    consts = PRESSURE_LAMBDA_P + "".join(f"{k} {v:g}; " for k, v in FIELD_DRIFTS.items())
    ref = bulk_case(work, "bulk_series_constants", WATER, f"drifts {{ {consts}}}\n", 0.3)
    series = field_drift_case(work, "bulk_series_uniform", SERIES_WINDOWS)
    liquidcase.run_case(a, ref, solver=a.bulk_solver)
    liquidcase.run_case(a, series, solver=a.bulk_solver)
    log = open(os.path.join(series, "log.mixflowBulkFoam")).read()
    read = len(re.findall(r"drift field \S*constant/drifts/", log))
    ok = lc.check("the fields of the 3 windows constant/drifts/<t>/" in log and read == 9,
                  f"the series run reads the 3 windows, {read} fields (9)")
    return ok & identical_runs(ref, series)


STEP = (0.1, 0.22)  # the two windows of drift-series-step (s)


def step_drifts(i):
    """The later window's drifts of cell I: inside the range, each unlike the constants."""
    return {"lambdaU": 1.1 + 0.05 * (i % 7), "lambdaW": 0.6 + 0.1 * (i % 5),
            "lambdaP": 0.4 + 0.1 * (i % 3)}


def drifts_used(case, t):
    """The drifts each mixture cell used at the write T, from the reconstruction written there
    (writeBulkFields.H): lambda_u = U.fluid_x / U.solid_x, lambda_w = U.fluid_y / U.solid_y,
    lambda_p = (p.fluid / p.solid) rho_s / rho_f; {name: {cell: value}} where the divisor is
    not 0."""
    field = {n: fc.read_internal_field(os.path.join(case, t, n))
             for n in ("U.solid", "U.fluid", "p.solid", "p.fluid")}
    out = {k: {} for k in FIELD_DRIFTS}
    for i, (us, uf) in enumerate(zip(field["U.solid"], field["U.fluid"])):
        for k, c in (("lambdaU", 0), ("lambdaW", 1)):
            if abs(us[c]) > 1e-12:
                out[k][i] = uf[c] / us[c]
        ps, pf = field["p.solid"][i], field["p.fluid"][i]
        if abs(ps) > 1e-9:
            out["lambdaP"][i] = pf / ps * RHO_S / 1000.0  # WATER's density
    return out


def check_drifts_used(case, t, weight, later):
    """The drifts used at the write T equal the constants + WEIGHT (LATER - constants) in every
    mixture cell within 1e-10 (the reconstruction's ratios are exact to a few ulp)."""
    used = drifts_used(case, t)
    err = 0.0
    for k, values in used.items():
        for i, v in values.items():
            want = FIELD_DRIFTS[k] + weight * (later[i][k] - FIELD_DRIFTS[k])
            err = max(err, abs(v - want))
    cells = min(len(values) for values in used.values())
    return lc.check(cells > 100 and err <= 1e-10,
                    f"{os.path.basename(case)}: t = {t} s: drifts used = first + {weight:.4f} "
                    f"(second - first) in {cells}+ mixture cells each: max |diff| {err:.1e} "
                    "(<= 1e-10)")


def step_series_case(a, work, name, how, end):
    """The step scenario's case: windows at STEP, the first at the constants, the second
    step_drifts of each cell (the cells of the mesh mixflowPrepare makes), interpolation HOW,
    writes every 0.05 s at full precision. Returns it and the second window's drifts."""
    case = field_drift_case(work, name, tuple(f"{t:g}" for t in STEP), end, 0.05,
                            f"interpolation {how}; ")
    fc.run([a.prepare, "-case", case, "-np", "1"], case, "log.mixflowPrepare")
    nx, ny = mesh_size(case)
    later = [step_drifts(i) for i in range(nx * ny)]
    for k in FIELD_DRIFTS:
        drift_field_file(case, k, [d[k] for d in later], f"{STEP[1]:g}")
    with open(os.path.join(case, "system/controlDict"), "a") as f:
        f.write("writePrecision 17;\n")
    return case, later


def step_weight(t, how):
    """The weight of the later window at t: linear in time between the windows, 0 or 1 for
    nearest, held outside."""
    w = min(max((t - STEP[0]) / (STEP[1] - STEP[0]), 0.0), 1.0)
    return w if how == "linear" else float(w >= 0.5)


def drift_series_step(a, work):
    """Two windows, at 0.1 s the constants (1.3, 0.8, 0.6) and at 0.22 s drifts varying cell by
    cell: up to 0.1 s the run is the fixed fields' run at the constants bit for bit; at every
    write from 0.1 s on the drifts each cell used, recovered from the reconstruction, are the
    linear interpolation in time (or with `interpolation nearest` the nearer window's), the later
    window's after 0.22 s, within 1e-10."""
    ref = field_drift_case(work, "bulk_step_fixed", (), 0.3, 0.05)
    with open(os.path.join(ref, "system/controlDict"), "a") as f:
        f.write("writePrecision 17;\n")
    liquidcase.run_case(a, ref, solver=a.bulk_solver)
    ok = True
    for how in ("linear", "nearest"):
        case, later = step_series_case(a, work, f"bulk_step_{how}", how, 0.3)
        liquidcase.run_case(a, case, solver=a.bulk_solver)
        ok &= identical_runs(ref, case, before=STEP[0] - 1e-9)
        for t in field_times(case):
            if float(t) >= STEP[0] - 1e-9:
                ok &= check_drifts_used(case, t, step_weight(float(t), how), later)
    return ok


def drift_series_parallel(a, work):
    """drift-series-step's linear case on 2 ranks to 0.15 s, decomposed by the Allruns' decompose
    (scripts/RunFunctions): every rank's windows hold its cells' values of the case's windows
    (by cellProcAddressing, exactly), and the drifts used at 0.15 s are the linear interpolation
    within 1e-10, as serially."""
    ranks = 2
    case, later = step_series_case(a, work, "bulk_series_parallel", "linear", 0.15)
    fc.run([a.prepare, "-case", case, "-np", str(ranks)], case, "log.mixflowPrepare")
    fc.run([a.blockmesh], case, "log.blockMesh")
    functions = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts",
                             "RunFunctions")
    fc.run(["bash", "-c", f'. "{functions}" && decompose {ranks}'], case, "log.decompose")
    worst, files = 0.0, 0
    for r in range(ranks):
        proc = os.path.join(case, f"processor{r}")
        cells = fc.read_label_list(os.path.join(proc, "constant/polyMesh/cellProcAddressing"))
        for t in STEP:
            for k in FIELD_DRIFTS:
                whole = fc.read_internal_field(os.path.join(case, f"constant/drifts/{t:g}/{k}"),
                                                  len(later))
                part = fc.read_internal_field(os.path.join(proc, f"constant/drifts/{t:g}/{k}"),
                                                 len(cells))
                worst = max(worst, max(abs(p - whole[c]) for p, c in zip(part, cells)))
                files += 1
    ok = lc.check(files == ranks * len(STEP) * 3 and worst == 0,
                  f"decompose {ranks}: {files} window files on the ranks, each cell equal to the "
                  f"case's: max |diff| {worst:g} (0)")
    log = fc.run(fc.launcher_tokens(a.mpiexec) + ["-x", "WM_PROJECT_DIR", "-np", str(ranks),
                                                        a.bulk_solver, "-parallel"],
                    case, "log.mixflowBulkFoam")
    ok &= lc.check(re.search(rf"^nProcs\s*:\s*{ranks}\s*$", log, re.M) is not None,
                   f"a parallel run on {ranks} ranks")
    fc.run([a.reconstructpar, "-latestTime"], case, "log.reconstructPar")
    t = field_times(case)[-1]
    return ok & check_drifts_used(case, t, step_weight(float(t), "linear"), later)


def prepared_bound(a, work, name, consts, fields, windows=None):
    """(viscosity at rest in Pa s, maxDeltaT in s) of mixflowPrepare for a bulk case with drift
    constants CONSTS and, if FIELDS, drift fields {name: 'uniform V' or a list of cell values};
    or with WINDOWS, time-varying ones {window: FIELDS}. The viscosity of `mixflowPrepare -check`
    must be the same."""
    text = PRESSURE_LAMBDA_P + "".join(f"{k} {v:g}; " for k, v in consts.items())
    text += "fields on; " if fields or windows else ""
    text += "timeVarying on; " if windows else ""
    case = bulk_case(work, name, WATER, f"drifts {{ {text}}}\n", 0.3)
    for window, values in (windows or {None: fields or {}}).items():
        for k, v in values.items():
            drift_field_file(case, k, v, window)
    check = fc.run([a.prepare, "-case", case, "-np", "1", "-check"], case, "log.check")
    log = fc.run([a.prepare, "-case", case, "-np", "1"], case, "log.mixflowPrepare")
    with open(os.path.join(case, "system/controlDict.generated")) as f:
        dt = float(re.search(r"^maxDeltaT\s+(\S+);", f.read(), re.M).group(1))
    mu, mu_check = (float(re.search(r"viscosity at rest up to (\S+) Pa s", t).group(1))
                    for t in (log, check))
    if mu_check != mu:
        fc.fail(f"{case}: mixflowPrepare -check's viscosity at rest {mu_check:g} Pa s, its "
                   f"run's {mu:g} Pa s")
    return mu, dt


def drift_field_step(a, work):
    """With drift fields, mixflowPrepare's time-step bound (the viscous number limit on the
    mixture's viscosity at rest, and the PISO correctors chosen from it) takes the stiffest cell:
    constant drifts (1.3, 0.8, 0.6) with one field cell at lambda_p = -1 give the viscosity and
    maxDeltaT of the constants (1.3, 0.8, -1); uniform fields equal to the constants give the
    constants' own; time-varying fields with that cell in their last window of three give the
    stiff constants', as `mixflowPrepare -check` says too."""
    stiff = dict(FIELD_DRIFTS, lambdaP=-1.0)
    base = prepared_bound(a, work, "bulk_step_constants", FIELD_DRIFTS, None)
    bound = prepared_bound(a, work, "bulk_step_stiff_constants", stiff, None)
    uniform = prepared_bound(a, work, "bulk_step_uniform_fields", FIELD_DRIFTS,
                             {k: f"uniform {v:g}" for k, v in FIELD_DRIFTS.items()})
    # One value per cell of the case's mesh: channel 0.6 x 0.15 m at 0.005 m, one cell across
    # (mixflowPrepare refuses a field of another length).
    n_cells = round(0.6 / 0.005) * round(0.15 / 0.005)
    cells = {k: [v] * n_cells for k, v in FIELD_DRIFTS.items()}
    cells["lambdaP"][17] = -1.0
    one = prepared_bound(a, work, "bulk_step_one_cell", FIELD_DRIFTS, cells)
    uniform_fields = {k: f"uniform {v:g}" for k, v in FIELD_DRIFTS.items()}
    windows = dict.fromkeys(SERIES_WINDOWS, uniform_fields)
    windows[SERIES_WINDOWS[-1]] = cells
    late = prepared_bound(a, work, "bulk_step_late_window", FIELD_DRIFTS, None, windows)
    ok = lc.check(bound[0] > 1.1 * base[0], f"lambda_p -1 raises the viscosity at rest: "
                  f"{bound[0]:.4g} Pa s against {base[0]:.4g} Pa s")
    ok &= lc.check(uniform == base, f"uniform fields equal to the constants: {uniform} against "
                   f"{base} (Pa s, s)")
    ok &= lc.check(one == bound, f"one cell at lambda_p -1: {one} against the stiff constants' "
                   f"{bound} (Pa s, s)")
    ok &= lc.check(late == bound, f"time-varying fields, that cell in the window "
                   f"{SERIES_WINDOWS[-1]} s: {late} against the stiff constants' {bound} (Pa s, "
                   "s; -check the same)")
    return ok


def closed_box(a, work):
    """The newtonian scenario's column collapsing and sloshing in a 0.3 m channel closed all
    round (outlet and top made walls): the mixture volume sum(alpha V) of every step equals the first,
    and the solid volume sum(alpha.solid V) of every write is alpha_s times it."""
    alpha_s, cell = 0.6, 0.005
    box = 0.3  # channel length: the viscous mixture reaches the end wall within 1 s
    geometry = GEOMETRY.replace("length 0.6;", f"length {box};")
    case = prepared(a, work, "bulk_closed_box", NEWTONIAN_SOLID, 2.0, 0.25, geometry)
    close_patches(case, ["outlet", "atmosphere"])
    # The implicit upwind alpha predictor (MULESCorr) is the one step not conservative by
    # construction: its linear-solver residual is the drift (prepare's 1e-10 gives ~1e-8 here).
    edit(case, "system/fvSolution", [(r'("alpha\.liquid\.\*"\s*\{[^}]*tolerance\s+)1e-10;',
                                      r"\g<1>1e-13;")])
    log = run_bulk(a, case)
    vols = [float(v) for v in re.findall(r"^Liquid volume sum\(voidfraction\*alpha\*V\) = (\S+)",
                                         log, re.M)]
    ok = lc.check(len(vols) > 100, f"{len(vols)} steps logged the mixture volume")
    s = liquidcase.read_series(case)
    v0 = s[0]["volume_domain_m3"]  # the initial fields, 12 digits
    drift = max(abs(v - v0) / v0 for v in vols)
    ok &= lc.check(drift <= 1e-10, f"mixture volume |V(t) - V(0)| / V(0) max {drift:.2e} over "
                   f"{len(vols)} steps to t = {s[-1]['time_s']:g} s (<= 1e-10)")
    worst = 0.0
    for t in field_times(case):
        vs = sum(fc.read_internal_field(os.path.join(case, t, "alpha.solid"))) * cell * cell * 0.1
        worst = max(worst, abs(vs - alpha_s * v0) / (alpha_s * v0))
    ok &= lc.check(worst <= 1e-10, f"solid volume sum(alpha.solid V) = alpha_s V(0) at the "
                   f"{len(field_times(case))} writes: max relative deviation {worst:.2e} (<= 1e-10)")
    # The collapse reaches the end wall and runs up it: not a trivial run.
    xmax = max(r["front_bed_m"] for r in s)
    ok &= lc.check(xmax >= 0.95 * box, f"front reached {xmax:.3f} m (>= {0.95 * box:.3f} m: the "
                   "end wall)")
    return ok


def cohesive_solid(tau_eff=50.0, mu_p=1.5, cap=1e4, alpha=0.6, rho_f=1000.0):
    """The cohesive-arrest scenario's solid entry: the mixture a Bingham material of yield stress
    tau_eff, plastic viscosity mu_p and viscosity at rest ~cap."""
    rho = alpha * RHO_S + (1 - alpha) * rho_f
    # Kinematic stress alpha_s nu_se |D| times rho*: tau_eff = rho* alpha_s tau_c / rho_s.
    tau_c = tau_eff * RHO_S / (rho * alpha)
    nu_s = mu_p / (rho * alpha)
    m_y = cap / tau_eff  # viscosity at rest rho* alpha_s (nu_s + m_y tau_c / rho_s) ~ cap
    return (f"solid {{ viscosity {nu_s:.10g}; tanPhi 0; cohesion {tau_c:.10g}; "
            f"regularisation {m_y:g}; }}\n")


def rest(a, work):
    """A flat mixture layer 0.05 m deep filling a 0.3 m channel (end wall closed, top open to the
    air), at rest: it must stay at rest, Newtonian and cohesive, and its pore pressure is the
    pressure closure's: P_f = rho_f g (h - y) for the default pore-pressure ratio chi = 0, and
    rho_f g (h - y) + chi alpha_s (rho_s - rho_f) g (h - y) for chi 0.5 (the Newtonian layer)."""
    ok, bound, depth = True, 1e-6, 0.05
    geometry = GEOMETRY.replace("length 0.6;", "length 0.3;")
    for label, solid, chi in (("newtonian", NEWTONIAN_SOLID, 0.0),
                              ("cohesive", cohesive_solid(), 0.0),
                              ("newtonian_chi", NEWTONIAN_SOLID + "drifts { porePressureRatio 0.5; }\n",
                               0.5)):
        # p_rgh to 1e-12: the auto 1e-7 (the Newtonian layer's, D < 20) leaves face-force residues
        # that the light air turns into currents (1e-4 m/s in the mixture after 2 s, growing).
        case = prepared(a, work, "bulk_rest_" + label, solid, 2.0, 0.5, geometry,
                        CFD + "pressureTolerance 1e-12;\n")
        close_patches(case, ["outlet"])
        flat_layer(case, depth)
        run_bulk(a, case)
        times = field_times(case)
        umax = [max(math.sqrt(sum(c * c for c in u)) for u in
                    fc.read_internal_field(os.path.join(case, t, "U"))) for t in times]
        ok &= lc.check(max(umax) <= bound, f"{label} layer at rest: max |U| over the writes "
                       f"{', '.join(times)} s: {', '.join(f'{u:.1e}' for u in umax)} m/s "
                       f"(<= {bound:g})")
        ok &= pore_pressure_at_rest(case, times[-1], depth, chi, label)
    # Control: the paper's closure at lambda_p 2.75, the value the total-pressure convention
    # extracts from a saturated column at rest (the lower end of W&P's 2.75-4.1), puts
    # P_f = rho_f lambda_p / Lambda_p p_m = 1.62 rho_f g (h - y): not the liquid at rest.
    case = prepared(a, work, "bulk_rest_lambda_p_control",
                    NEWTONIAN_SOLID + "drifts { pressure lambdaP; lambdaP 2.75; }\n", 0.5, 0.5,
                    geometry, CFD + "pressureTolerance 1e-12;\n")
    close_patches(case, ["outlet"])
    flat_layer(case, depth)
    run_bulk(a, case)
    worst = pore_pressure_error(case, field_times(case)[-1], depth, 0.0)[0]
    ok &= lc.check(worst > 0.5, f"control: lambdaP 2.75 at rest gives p.fluid {100 * worst:.1f} % "
                   "off rho_f g (h - y) (> 50 %: expected 2.75 / (0.6 + 2.75 0.4) - 1 = 62 %)")
    return ok


def pore_pressure_error(case, t, depth, chi):
    """(largest |p.fluid / want - 1| over the mixture cells at time T, their count), want = (rho_f
    + chi alpha_s (rho_s - rho_f)) g (h - y) at the cell centre."""
    nx, ny = mesh_size(case)
    dy = float(re.search(r"cellSize ([^;]+);", CFD).group(1))
    alpha_s, rho_f = 0.6, 1000.0  # GEOMETRY's sample.solidFraction, WATER's density
    pf = fc.read_internal_field(os.path.join(case, t, "p.fluid"))
    worst, cells = 0.0, 0
    for j in range(ny):
        y = (j + 0.5) * dy
        if y > depth:
            break
        want = (rho_f + chi * alpha_s * (RHO_S - rho_f)) * G * (depth - y)
        for i in range(nx):
            worst = max(worst, abs(pf[i + nx * j] / want - 1))
            cells += 1
    return worst, cells


def pore_pressure_at_rest(case, t, depth, chi, label):
    """p.fluid of the mixture cells at time T against rho_f g (h - y) + chi alpha_s (rho_s -
    rho_f) g (h - y), relative per cell, within 2 %: the mixture pressure p_m = (1 - rho_air /
    rho*) g (h - y) of a layer at rest (the air's share, 5e-4 here, is inside the tolerance)."""
    worst, cells = pore_pressure_error(case, t, depth, chi)
    return lc.check(cells > 0 and worst <= 0.02,
                    f"{label} layer at rest (pore-pressure ratio {chi:g}): p.fluid of the "
                    f"{cells} mixture cells against (rho_f + chi alpha_s (rho_s - rho_f)) g (h - y): "
                    f"worst {100 * worst:.3f} % (tolerance 2 %)")


def periodic_layer(a, work, name, bulk_props, n, h, length, nx, theta, end, rho, max_dt,
                   u0=0.0, p_ref=(0, 0.0), writes=4, functions="", top="type slip;",
                   liquid=WATER):
    """A mixture (BULK_PROPS, pore LIQUID) filling a layer of depth h, periodic in x (cyclic
    left/right), stress-free top (slip, closed), g tilted by theta, n cells across the depth,
    initial velocity (u0, 0): the bed keeps the bottom condition mixflowPrepare wrote (no-slip, or
    the basal law). P_REF = (cell, value) fixes p (no open boundary)."""
    case = prepared(a, work, name, bulk_props, end, end / writes, liquid=liquid)
    with open(os.path.join(case, "0/U")) as f:
        bed = re.search(r"^\s*bottom\s*\{\s*(.*?)\s*\}\s*$", f.read(), re.M).group(1)
    g = (G * math.sin(theta), -G * math.cos(theta), 0.0)
    dz = h / n
    fc.write_foam_file(case, "system/blockMeshDict", "dictionary", "blockMeshDict", f"""\
scale 1;
vertices ((0 0 0) ({length} 0 0) ({length} {h} 0) (0 {h} 0)
          (0 0 {dz}) ({length} 0 {dz}) ({length} {h} {dz}) (0 {h} {dz}));
blocks (hex (0 1 2 3 4 5 6 7) ({nx} {n} 1) simpleGrading (1 1 1));
edges ();
boundary
(
    left   {{ type cyclic; neighbourPatch right; faces ((0 4 7 3)); }}
    right  {{ type cyclic; neighbourPatch left;  faces ((1 2 6 5)); }}
    bottom {{ type wall;  faces ((0 1 5 4)); }}
    top    {{ type patch; faces ((3 7 6 2)); }}
    frontAndBack {{ type empty; faces ((0 3 2 1) (4 5 6 7)); }}
);
mergePatchPairs ();
""")
    fc.write_foam_file(case, "constant/g", "uniformDimensionedVectorField", "g",
                          "dimensions [0 1 -2 0 0 0 0];\nvalue (%.17g %.17g %.17g);\n" % g)

    def field(name, cls, dims, internal, patches):
        fc.write_foam_file(case, "0/" + name, cls, name,
                              f"dimensions {dims};\ninternalField uniform {internal};\n"
                              "boundaryField\n{\n" + "".join(f"    {k} {{ {v} }}\n"
                                                              for k, v in patches.items()) + "}\n")
    cyc = {"left": "type cyclic;", "right": "type cyclic;", "frontAndBack": "type empty;"}
    field("U", "volVectorField", "[0 1 -1 0 0 0 0]", f"({u0:.17g} 0 0)",
          dict(cyc, bottom=bed, top=top))
    field("alpha.liquid", "volScalarField", "[0 0 0 0 0 0 0]", "1",
          dict(cyc, bottom="type zeroGradient;", top="type zeroGradient;"))
    # p = p_rgh + rho g.x is periodic, so p_rgh jumps by -rho g_x L across the cycle (owner
    # side left: the value seen from the left face is the right cell's minus the jump).
    jump = -rho * g[0] * length
    field("p_rgh", "volScalarField", "[1 -1 -2 0 0 0 0]", "0",
          dict(cyc, left=f"type fixedJump; patchType cyclic; jump uniform {jump:.17g}; "
               "value uniform 0;", right="type fixedJump; patchType cyclic; value uniform 0;",
               bottom="type fixedFluxPressure; value uniform 0;",
               top="type fixedFluxPressure; value uniform 0;"))
    edit(case, "system/fvSolution", [(r"^PIMPLE\s*\{", f"PIMPLE\n{{\n    pRefCell {p_ref[0]};\n"
                                      f"    pRefValue {p_ref[1]:.17g};")])
    # No dam-break channel: the liquidObservables of prepare's controlDict do not apply.
    fc.write_foam_file(case, "system/controlDict", "dictionary", "controlDict", f"""\
application mixflowBulkFoam;
startFrom startTime; startTime 0; stopAt endTime; endTime {end};
deltaT 1e-4; writeControl adjustable; writeInterval {end / writes}; purgeWrite 0;
writeFormat ascii; writePrecision 17; writeCompression off; timeFormat general;
timePrecision 8; runTimeModifiable no;
adjustTimeStep yes; maxCo 0.5; maxAlphaCo 0.5; maxDeltaT {max_dt:.6g};
""" + functions)
    return case


def incline_case(a, work, n, h, length, nx, theta, end, rho, max_dt):
    """The newtonian mixture on a no-slip bed down an incline of angle theta."""
    return periodic_layer(a, work, f"bulk_incline_{n}", NEWTONIAN_SOLID, n, h, length, nx, theta,
                          end, rho, max_dt)


def incline(a, work):
    """Steady uniform flow down an incline against u(y) = (g sin(theta) / nu) (h y - y^2 / 2)
    on 8, 16, 32 cells across the depth."""
    alpha, nu_s, nu_f, rho_f = 0.6, 2e-3, 1e-6, 1000.0
    rho = alpha * RHO_S + (1 - alpha) * rho_f
    nu = alpha * nu_s + (1 - alpha) * nu_f
    h, theta = 0.01, math.radians(10)
    # The slowest mode decays as exp(-pi^2 nu t / (4 h^2)), but the solver's transient lags its
    # implicit-Euler rate by ~15 steps (e-folding 1/lambda + 15 dt) and a viscous number
    # nu dt / dy^2 of ~100 diverges (32 cells at 0.01 s): steps of viscous number 2, 29 h^2/nu.
    end = 2.4
    amp = G * math.sin(theta) / nu
    umax = amp * h * h / 2
    ok, errs = True, {}
    for n in (8, 16, 32):
        case = incline_case(a, work, n, h, h, 4, theta, end, rho, 2 * (h / n) ** 2 / nu)
        run_bulk(a, case)
        moved, last, change = steady_end(case, umax)
        ok &= lc.check(change <= 1e-8, f"n = {n}: steady, {moved} u_max (<= 1e-8)")
        dy, err2, errmax, side = h / n, 0.0, 0.0, 0.0
        for c, u in enumerate(last):
            y = (c // 4 + 0.5) * dy
            e = u[0] - amp * (h * y - y * y / 2)
            err2 += e * e / len(last)
            errmax = max(errmax, abs(e))
            side = max(side, abs(u[1]))
        errs[n] = (math.sqrt(err2) / umax, errmax / umax)
        print(f"  n = {n}: L2 error {errs[n][0]:.3e} u_max, max {errs[n][1]:.3e} u_max "
              f"(u_max {umax:.5f} m/s; max |v| {side:.1e} m/s)", flush=True)
    ok &= lc.check(errs[32][1] <= 5e-4, f"max error on 32 cells {errs[32][1]:.3e} u_max (<= 5e-4)")
    # The cell-centred scheme's steady solution is the exact one plus (g sin(theta)/nu) dy^2/8
    # (the half-cell wall gradient), i.e. 1/(4 n^2) u_max in every cell.
    dev = max(abs(errs[n][1] * 4 * n * n - 1) for n in errs)
    ok &= lc.check(dev <= 0.01, f"errors against the scheme's 1/(4 n^2) u_max: within {dev:.1e} "
                   "(<= 1 %)")
    for c, f in ((8, 16), (16, 32)):
        for k, name in enumerate(("L2", "max")):
            order = math.log(errs[c][k] / errs[f][k], 2)
            ok &= lc.check(order >= 1.8, f"{name} order {c} -> {f} cells: {order:.3f} (>= 1.8)")
    return ok

def air_density(case):
    """rho of the air phase in the transportProperties mixflowPrepare wrote."""
    with open(os.path.join(case, "constant/transportProperties")) as f:
        return float(re.search(r"^air\s*\{.*?^\s*rho\s+([^;\s]+)", f.read(), re.M | re.S).group(1))


def sliding_block(a, work):
    """A stiff mixture layer sliding on a horizontal Coulomb bed from u0: it must stop at
    t_s = u0 / (g' tan(delta)) after u0^2 / (2 g' tan(delta)), E_k falling as (1 - t/t_s)^2."""
    alpha, nu_f, rho_f, nu = 0.6, 1e-6, 1000.0, 0.05
    rho = alpha * RHO_S + (1 - alpha) * rho_f
    nu_s = (nu - (1 - alpha) * nu_f) / alpha  # mixture nu = alpha_s nu_s + alpha_f nu_f
    tan_delta, u0, h, n, nx = 0.3, 0.3, 0.01, 8, 4
    basal = a.case_basal or f"law coulomb; tanDelta {tan_delta};"
    props = f"solid {{ viscosity {nu_s:.17g}; tanPhi 0; cohesion 0; }}\nbasal {{ {basal} }}\n"
    dy = h / n
    # sigma_n is p_m = p - rho_air g.x (the yield law's mixture pressure, 0 at the surface), so the
    # layer's weight on the bed is (rho* - rho_air) g h: p_m = 0 at y = h fixes p in the top cell.
    rho_air = 1.0  # checked against the prepared case below
    decel = G * tan_delta * (1 - rho_air / rho)
    t_stop, x_stop = u0 / decel, u0 * u0 / (2 * decel)
    end = 1.5 * t_stop
    top = (n - 1) * nx
    p_top = rho * G * dy / 2 - rho_air * G * h
    functions = """functions { mean { type volFieldValue; libs ("libfieldFunctionObjects.so");
  regionType all; operation volAverage; fields (U); writeFields false; log false;
  writeControl timeStep; writeInterval 1; } }
"""
    # Viscous number nu dt / dy^2 = 2 (as the incline); the layer's shear across the depth,
    # g tan(delta) h^2 / (2 nu) = 1 % of u0, is what keeps it a block. The free-slip top is the
    # Coulomb condition with tanDelta 0: the stock slip's implicit normal coefficient mu/d (8 rho/dt
    # here) enters the matrix's relax() and lags the top cell's deceleration (measured: 2/3 of the
    # Coulomb rate, 0.89 with dt / 4).
    free_slip = "type bulkCoulombSlip; tanDelta 0; value uniform (0 0 0);"
    case = periodic_layer(a, work, "bulk_sliding_block", props, n, h, h, nx, 0.0, end, rho,
                          2 * dy * dy / nu, u0=u0, p_ref=(top, p_top), writes=15,
                          functions=functions, top=free_slip)
    ok = lc.check(air_density(case) == rho_air, f"air density {air_density(case):g} kg/m3")
    run_bulk(a, case)
    t, u = [0.0], [u0]
    with open(os.path.join(case, "postProcessing/mean/0/volFieldValue.dat")) as f:
        for line in f:
            if not line.startswith("#"):
                v = line.replace("(", " ").replace(")", " ").split()
                t.append(float(v[0]))
                u.append(float(v[1]))
    # Distance: the mean velocity integrated over the steps (trapezoid, dt <= 4e-5 s).
    x = sum(0.5 * (u[i] + u[i - 1]) * (t[i] - t[i - 1]) for i in range(1, len(t)))
    stopped = next((ti for ti, ui in zip(t, u) if ui <= 1e-3 * u0), None)
    tol = 0.02
    if stopped is None:
        return lc.check(False, f"still moving at t = {t[-1]:.4f} s: mean u {u[-1]:.3e} m/s "
                        f"(t_stop {t_stop:.4f} s)")
    ok &= lc.check(abs(stopped - t_stop) <= tol * t_stop,
                   f"stopped (mean u <= 1e-3 u0) at t = {stopped:.5f} s against u0/(g' tan delta) "
                   f"= {t_stop:.5f} s: {100 * (stopped / t_stop - 1):+.2f} % (<= {100 * tol:g} %)")
    ok &= lc.check(abs(x - x_stop) <= tol * x_stop,
                   f"distance {x:.6f} m against u0^2/(2 g' tan delta) = {x_stop:.6f} m: "
                   f"{100 * (x / x_stop - 1):+.2f} % (<= {100 * tol:g} %)")
    # Deceleration while sliding (u between 0.9 and 0.1 u0): least-squares slope of u(t).
    pts = [(ti, ui) for ti, ui in zip(t, u) if 0.1 * u0 <= ui <= 0.9 * u0]
    tm = sum(p[0] for p in pts) / len(pts)
    um = sum(p[1] for p in pts) / len(pts)
    slope = (sum((p[0] - tm) * (p[1] - um) for p in pts) /
             sum((p[0] - tm) ** 2 for p in pts))
    ok &= lc.check(abs(-slope - decel) <= 0.01 * decel,
                   f"deceleration {-slope:.5f} m/s2 against g' tan delta = {decel:.5f} m/s2 "
                   f"({len(pts)} steps): {100 * (-slope / decel - 1):+.3f} % (<= 1 %)")
    after = [ui for ti, ui in zip(t, u) if ti >= 1.05 * t_stop]
    ok &= lc.check(max(abs(v) for v in after) <= 1e-3 * u0,
                   f"at rest after 1.05 t_stop: max |mean u| {max(abs(v) for v in after):.1e} m/s "
                   f"(<= 1e-3 u0)")
    # Kinetic energy of the written fields against E_k0 (1 - t/t_s)^2 (0 after t_s).
    worst, rows = 0.0, 0
    for tname in field_times(case):
        tt = float(tname)
        cells = fc.read_internal_field(os.path.join(case, tname, "U"))
        ek = sum(c[0] ** 2 + c[1] ** 2 for c in cells) / (len(cells) * u0 * u0)
        exact = max(1 - tt / t_stop, 0.0) ** 2
        worst = max(worst, abs(ek - exact))
        rows += 1
        print(f"  t = {tt:.5f} s: E_k/E_k0 {ek:.5f}, (1 - t/t_s)^2 {exact:.5f}", flush=True)
    ok &= lc.check(worst <= 0.01, f"E_k/E_k0 against (1 - t/t_stop)^2 at {rows} writes: max "
                   f"difference {worst:.2e} (<= 0.01)")
    return ok


# ------------------------------------------------------------- the mu(I) solid on an incline
# A dry layer: the pore fluid a gas of air's density without viscosity (1e-12 Pa s, so that the
# solid's stress is the only one) under an ambient air of 0.01 kg/m3 (its hydrostatic pressure,
# which p_m removes, varies along the periodic slope by rho_air g sin(theta) L: 1e-6 of p_m here).
# lambda_p = 0: the pore gas carries no load, so p_s = p_m / alpha_s holds the grains' weight.
DRY = ("rheology Newtonian; density 1.2; viscosity 1e-12; surfaceTension 0; "
       "air { density 0.01; viscosity 1.48e-5; }")
MUI = ("drifts { pressure lambdaP; lambdaP 0; }\n"
       "solid { rheology muI; grainDiameter 0.001; }\n")
MU_S, MU_2, I_0, M_Y = math.tan(math.radians(20.9)), math.tan(math.radians(32.76)), 0.279, 100.0


MUI_ALPHA, MUI_RHO_F, MUI_RHO_AIR, MUI_H = 0.6, 1.2, 0.01, 0.01
MUI_RHO = MUI_ALPHA * RHO_S + (1 - MUI_ALPHA) * MUI_RHO_F
# The pressure factor phi (kappa_y p_s = phi g cos(theta) (h - z)) and the friction factor psi =
# alpha_s phi (tan(theta) = psi mu(I)) of the dry layer (docs/bulk_model.md): kappa_y = 1 -
# rho_f lambda_p / rho_s = 1 and Lambda_p = alpha_s + lambda_p alpha_f = alpha_s.
MUI_PHI = (1 - MUI_RHO_AIR / MUI_RHO) / MUI_ALPHA
MUI_PSI = MUI_ALPHA * MUI_PHI


def mui_layer(a, work, name, n, theta, end, max_dt, writes):
    """The dry mu(I) layer (alpha_s 0.6, rho_s 2500, d 1 mm, h 0.01 m, 4 cells along 0.01 m) on a
    no-slip bed down theta, from rest; p fixed in the top cell so that p_m = 0 at the surface."""
    rho, rho_air, h, nx = MUI_RHO, MUI_RHO_AIR, MUI_H, 4
    dz, dx = h / n, h / nx
    top = (n - 1) * nx
    # p = rho* p_m + rho_air g.x in the top cell (x = dx/2, z = h - dz/2), p_m = phi alpha g cos dz/2.
    gx = G * math.sin(theta) * dx / 2 - G * math.cos(theta) * (h - dz / 2)
    p_top = (rho - rho_air) * G * math.cos(theta) * dz / 2 + rho_air * gx
    return periodic_layer(a, work, name, MUI, n, h, h, nx, theta, end, rho, max_dt,
                          p_ref=(top, p_top), writes=writes, liquid=DRY)


def mui_incline(a, work):
    """The Bagnold profile of the mu(I) law down a 25 degree incline on 8, 16, 32 cells."""
    h, d, theta = MUI_H, 0.001, math.radians(25)
    # From rest the layer's transient decays by ~0.4 every 0.5 s (e-folding 0.5 s): after 5 s
    # (10 writes) it is below 1e-3 of the surface velocity. Steps of viscous number 4 at the bed's
    # flowing viscosity (the Courant number 0.5 limits 8 cells).
    end, vn, writes = 5.0, 4.0, 10
    ok, errs = True, {}
    for n in (8, 16, 32):
        phi, mu = MUI_PHI, math.tan(theta) / MUI_PSI
        i_theta = I_0 * (mu - MU_S) / (MU_2 - mu)
        amp = 2 / 3 * i_theta / d * math.sqrt(phi * G * math.cos(theta))
        u_surf = amp * h ** 1.5
        # Steps of viscous number a.mui_vn at the bed's flowing viscosity g sin(theta) h / u'(0).
        nu_bed = G * math.sin(theta) * h / (1.5 * amp * math.sqrt(h))
        case = mui_layer(a, work, f"bulk_mui_incline_{n}", n, theta, end, vn * (h / n) ** 2 / nu_bed,
                         writes)
        run_bulk(a, case)
        moved, last, change = steady_end(case, u_surf)
        ok &= lc.check(change <= 1e-3, f"n = {n}: steady, {moved} u_surface (<= 1e-3)")
        dz, err2, errmax = h / n, 0.0, 0.0
        for c, u in enumerate(last):
            z = (c // 4 + 0.5) * dz
            e = u[0] - amp * (h ** 1.5 - (h - z) ** 1.5)
            err2 += e * e / len(last)
            errmax = max(errmax, abs(e))
        # Surface velocity: the top cell's, extrapolated to z = h with the exact profile's slope
        # difference (the cell centre lies dz/2 below the surface).
        top = [u[0] for c, u in enumerate(last) if c // 4 == n - 1]
        u_top = sum(top) / len(top)
        surf_err = (u_top - amp * (h ** 1.5 - (dz / 2) ** 1.5)) / u_surf
        errs[n] = (math.sqrt(err2) / u_surf, errmax / u_surf, surf_err)
        print(f"  n = {n}: I_theta {i_theta:.5f}, u_surface {u_surf:.5f} m/s; top cell "
              f"{u_top:.5f} m/s ({100 * surf_err:+.3f} % of u_surface against the exact value "
              f"there); L2 error {errs[n][0]:.3e}, max {errs[n][1]:.3e} u_surface", flush=True)
    ok &= lc.check(abs(errs[32][2]) <= 0.01,
                   f"top-cell velocity on 32 cells within {100 * abs(errs[32][2]):.3f} % of the "
                   f"exact profile's (<= 1 %)")
    # u'' ~ (h - z)^(-1/2) at the free surface: the top cell's error falls as dz^1.5 (the max),
    # the smooth rest as dz^2 (which the L2 norm sees).
    for c, f in ((8, 16), (16, 32)):
        for k, name, least in ((0, "L2", 1.8), (1, "max", 1.3)):
            order = math.log(errs[c][k] / errs[f][k], 2)
            ok &= lc.check(order >= least, f"{name} order {c} -> {f} cells: {order:.3f} "
                           f"(>= {least:g})")
    return ok


def mui_rest(a, work):
    """Below the static angle (tan(theta) = 0.8 psi mu_s) the mu(I) layer stays at rest up to
    the regularisation's creep: mu(I) (1 - exp(-m_y |gamma|)) = tan(theta)/psi with mu(I) >= mu_s
    bounds the shear rate by ln(mu_s / (mu_s - tan(theta)/psi)) / m_y, uniform in depth."""
    h, n, psi = MUI_H, 16, MUI_PSI
    theta = math.atan(0.8 * psi * MU_S)
    case = mui_layer(a, work, "bulk_mui_rest", n, theta, 1.0, 1e-3, 4)
    rate = math.log(MU_S / (MU_S - math.tan(theta) / psi)) / M_Y
    bound = rate * h
    run_bulk(a, case)
    ok = True
    for t in field_times(case):
        umax = max(math.hypot(u[0], u[1]) for u in
                   fc.read_internal_field(os.path.join(case, t, "U")))
        ok &= lc.check(umax <= bound, f"theta {math.degrees(theta):.3f} deg (atan mu_s "
                       f"{math.degrees(math.atan(psi * MU_S)):.3f}): t = {t} s, max |U| "
                       f"{umax:.4e} m/s (<= h ln(mu_s/(mu_s - tan(theta)/psi))/m_y = "
                       f"{bound:.4e}: {umax / bound:.5f} of it)")
    return ok


SCENARIOS = {"liquid-limit": liquid_limit, "newtonian": newtonian, "drifting": drifting,
             "drift-fields": drift_fields, "drift-field-range": drift_field_range,
             "pore-ratio-fields": pore_ratio_fields,
             "drift-field-step": drift_field_step, "drift-series": drift_series,
             "drift-series-step": drift_series_step,
             "drift-series-range": lambda a, work: drift_field_range(a, work, SERIES_WINDOWS[1]),
             "drift-series-parallel": drift_series_parallel,
             "cohesive-arrest": cohesive_arrest, "bad-input": bad_input,
             "closed-box": closed_box, "rest": rest,
             "incline": incline, "sliding-block": sliding_block,
             "mui-incline": mui_incline, "mui-rest": mui_rest}


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--scenario", required=True, choices=sorted(SCENARIOS))
    p.add_argument("--prepare", required=True)
    p.add_argument("--solver", required=True, help="mixflowFoam (the reference runs)")
    p.add_argument("--bulk-solver", required=True, help="mixflowBulkFoam")
    p.add_argument("--blockmesh", default="blockMesh")
    p.add_argument("--decomposepar", default="decomposePar")
    p.add_argument("--reconstructpar", default="reconstructPar")
    p.add_argument("--mpiexec", default="mpirun --allow-run-as-root --oversubscribe")
    p.add_argument("--workdir", required=True)
    p.add_argument("--case-basal", help="sliding-block: the case's basal entries instead of the "
                   "Coulomb law the analytic solution is for (to see the check fail, e.g. "
                   "'law noSlip;' or 'law coulomb; tanDelta 0.25;')")
    a = p.parse_args()
    work = os.path.join(os.path.abspath(a.workdir), a.scenario)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    ok = SCENARIOS[a.scenario](a, work)
    print("PASS" if ok else "FAIL", flush=True)
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
