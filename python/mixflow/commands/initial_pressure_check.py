"""Does the start's pressure decide a yield-stress mixture's pore pressure? The quick HB+P
(cases/W+P-quick with case HB+P's liquid) run twice from one settled sample to 0.3 s: from the
cases' initial p_rgh = 0 (p = -rho g y: the solver finds the pressure), and from hydrostatic
p_rgh = rho_l g h_s in the liquid. Printed, and written to OUT: the liquid pressure p of the back
wall's cell column at the first write and at 0.3 s against hydrostatic rho_l g (h_s - y), and
the grains' released potential energy.

usage: mixflow initial-pressure-check [--work runs/initial_pressure]
                                                         [--out results/yield_stress/initial_pressure.json]
"""

import argparse
import os
import re
import shutil
import subprocess
import sys

from mixflow.commands import reproducibility
from mixflow import foamcase as fc
from mixflow import ROOT, outputs

G = 9.81




def back_wall_column(case):
    """Cell indices of the first cell column, bottom to top, and the cell height."""
    c = fc.read_internal_field(os.path.join(case, "0", "C"))
    col = sorted((i for i, p in enumerate(c) if abs(p[0] - c[0][0]) < 1e-9), key=lambda i: c[i][1])
    return c, col, c[col[1]][1] - c[col[0]][1]


def profile(case, time_dir, rho):
    c, col, dy = back_wall_column(case)
    p = fc.read_internal_field(os.path.join(case, time_dir, "p"))
    a = fc.read_internal_field(os.path.join(case, time_dir, "alpha.liquid"), len(c))
    hs = sum(a[i] for i in col) * dy
    return [{"y_m": c[i][1], "p_Pa": p[i], "hydrostatic_Pa": rho * G * (hs - c[i][1])}
            for i in col if c[i][1] < hs]


def released(case):
    with open(os.path.join(case, "postProcessing", "dem", "timeSeries.csv")) as f:
        rows = [ln.strip().split(",") for ln in f if ln.strip() and not ln.startswith("#")]
    k = rows[0].index("pe_J")
    return float(rows[1][k]) - float(rows[-1][k])


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--work", default=os.path.join(ROOT, "runs", "initial_pressure"))
    ap.add_argument("--out", default=os.path.join(ROOT, "results", "yield_stress",
                                                  "initial_pressure.json"))
    a = ap.parse_args()
    base = reproducibility.make_case(a.work, "HB+P", "solved")
    cd = os.path.join(base, "system", "controlDict")
    text = re.sub(r"^endTime\s+[^;]+;", "endTime 0.3;", open(cd).read(), flags=re.M)
    open(cd, "w").write(text)
    reproducibility.allrun(base, 1)
    rho = 1000.0  # case HB+P's liquid density
    # The same prepared case, meshed and settled, from a hydrostatic start.
    hyd = os.path.join(a.work, "HB+P", "hydrostatic")
    shutil.rmtree(hyd, ignore_errors=True)
    # The settled sample (dem/, without the solved run's resume state) and the logs of how the
    # case was prepared come along; the mesh and 0/ are inputs.
    outputs.copy_inputs(base, hyd, keep=("dem", "log.*"))
    c, col, dy = back_wall_column(hyd)
    alpha = fc.read_internal_field(os.path.join(hyd, "0", "alpha.liquid"), len(c))
    hs = sum(alpha[i] for i in col) * dy
    values = [al * rho * G * hs + (1 - al) * 1.0 * G * c[i][1] for i, al in enumerate(alpha)]
    path = os.path.join(hyd, "0", "p_rgh")
    text = open(path).read()
    field = "nonuniform List<scalar>\n%d\n(\n%s\n)\n" % (len(values), "\n".join(map(repr, values)))
    text, n = re.subn(r"internalField\s+uniform\s+0\s*;", "internalField   " + field + ";", text)
    if n != 1:
        sys.exit(f"{path}: expected 'internalField uniform 0;'")
    open(path, "w").write(text)
    with open(os.path.join(hyd, "log.mixflowCoupled"), "w") as log:
        r = subprocess.run(["mixflowCoupled", "-case", "."], cwd=hyd, env=fc.run_env(), stdout=log,
                           stderr=subprocess.STDOUT)
    if r.returncode != 0 or "End" not in open(os.path.join(hyd, "log.mixflowCoupled")).read():
        sys.exit(f"{hyd}: mixflowCoupled failed (log.mixflowCoupled)")
    out = {"command": "mixflow initial-pressure-check", "runs": {}}
    for label, case in (("solved", base), ("hydrostatic", hyd)):
        t = [name for value, name in fc.time_dirs(case) if value > 0]
        out["runs"][label] = {"first_write": {"time_s": float(t[0]), "column": profile(case, t[0], rho)},
                              "end": {"time_s": float(t[-1]), "column": profile(case, t[-1], rho)},
                              "grain_pe_released_J": released(case)}
        for when in ("first_write", "end"):
            w = out["runs"][label][when]
            print(f"{label:11s} t = {w['time_s']:.3f} s: p / hydrostatic at the back wall " +
                  ", ".join(f"y {r['y_m']:.2f} m {r['p_Pa']:.0f}/{r['hydrostatic_Pa']:.0f} Pa"
                            for r in w["column"]))
        print(f"{label:11s} grains' potential energy released by 0.3 s: "
              f"{out['runs'][label]['grain_pe_released_J']:.4f} J")
    outputs.write_json(a.out, out)
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
