#!/usr/bin/env python3
"""The measured stability limits (results/stability) as the input checks enforce them: a setting
just inside passes `-check`, one just outside is refused (exit 2) naming file, entry and allowed
range, or warned with the limit.

  - DEM step against stiffness (P-quick, mixflowDem -check): system/demDict maxHertzFraction 0.25
    passes and 0.26 is refused with its range (0, 0.25] (a settling pile at E x 1e-4 holds at
    0.28 t_Hertz and is lost at 0.39); an explicit timeStep at 0.999 x the printed stability
    limit passes and at 1.01 x is refused, at the cases' softening 1e-3 (where 0.2 T_R binds) and
    at 1e-4 with maxRayleighFraction 1 (where 0.25 t_Hertz binds);
  - the held drag's relaxation number s = beta T / m (W+P-quick with a 1000 Pa s liquid,
    mixflowPrepare -check): dragIntegration held without dragRelaxationLimit is refused above
    s = 2 with the largest exchangeEvery that passes; that value passes and one more is refused;
    with dragRelaxationLimit 0.5 the same interval is warned (the drag is clamped); the implicit
    drag passes without a drag warning.
  - an auto step asked above the limit (rayleighFraction 0.3 at E x 1e-3) runs at the limit and
    warns naming demDict, the entry and the limit in T_R;
Nothing is simulated: seconds in all.

usage: test_stability_limits.py REPO_ROOT MIXFLOWDEM MIXFLOWPREPARE WORKDIR"""
import os
import re
import subprocess
import sys

import inputcase  # beside this script
from inputcase import check, edit, last_line

root, dem_exe, prepare_exe, work = (os.path.abspath(p) for p in sys.argv[1:5])
DEM, SP, CP = "system/demDict", "constant/sceneProperties", "constant/couplingProperties"
os.makedirs(work, exist_ok=True)


def case_with(name, dest, edits):
    case = inputcase.copy_inputs(root, name, os.path.join(work, dest))
    for rel, pattern, repl in edits:
        edit(case, rel, pattern, repl)
    return case


def run(exe, case):
    r = subprocess.run([exe, "-case", case, "-check"], capture_output=True, text=True, timeout=60)
    return r.returncode, r.stdout + r.stderr


def expect(what, exe, case, want, fragments, absent=()):
    rc, msg = run(exe, case)
    missing = [f for f in fragments if f not in msg] + [f"(not) {f}" for f in absent if f in msg]
    if not check(rc == want and not missing, f"{what}: exit {rc} (want {want}): {last_line(msg)}"):
        print(f"     missing fragments {missing}\n{msg}")
    return msg


def add_entry(text):
    return (DEM, r"^(youngModulusFactor\s+[^;]+;)", r"\1 " + text)


# DEM: the range of maxHertzFraction.
soft = (DEM, r"^youngModulusFactor\s+[^;]+;", "youngModulusFactor 1e-4;")
expect("maxHertzFraction 0.25 (the largest allowed)", dem_exe,
       case_with("P-quick", "hertz_inside", [soft, add_entry("maxHertzFraction 0.25;")]), 0, [])
expect("maxHertzFraction 0.26", dem_exe,
       case_with("P-quick", "hertz_outside", [soft, add_entry("maxHertzFraction 0.26;")]), 2,
       [DEM, "maxHertzFraction", "0.26", "(0, 0.25]"])

# DEM: an auto step asked above the limit runs at the limit and says so; the cases' 0.1 does not.
expect("rayleighFraction 0.3 (above the limit 0.2 T_R)", dem_exe,
       case_with("P-quick", "auto_above",
                 [(DEM, r"^rayleighFraction\s+[^;]+;", "rayleighFraction 0.3;")]), 0,
       ["warning:", DEM, "rayleighFraction 0.3", "above the stability limit", "0.2 T_R"])
expect("rayleighFraction 0.1 (inside)", dem_exe, case_with("P-quick", "auto_inside", []), 0, [],
       absent=["rayleighFraction 0.1 asks"])

# DEM: an explicit timeStep on both sides of the limit the check prints.
for label, edits in (("E x 1e-3, 0.2 T_R binds", []),
                     ("E x 1e-4, maxRayleighFraction 1, 0.25 t_Hertz binds",
                      [soft, add_entry("maxRayleighFraction 1; maxHertzFraction 0.25;")])):
    msg = expect(f"{label}: auto step", dem_exe,
                 case_with("P-quick", re.sub(r"\W+", "_", label), edits), 0, ["stability limit"])
    m = re.search(r"stability limit ([0-9.eE+-]+) s", msg)
    if not check(m is not None, f"{label}: the check prints the stability limit"):
        continue
    limit = float(m.group(1))
    for factor, want in ((0.999, 0), (1.01, 2)):
        dt = factor * limit
        case = case_with("P-quick", re.sub(r"\W+", "_", label) + f"_{factor}",
                         edits + [(DEM, r"^timeStep\s+[^;]+;", f"timeStep {dt!r};")])
        expect(f"{label}: timeStep {factor} x limit {limit:g} s", dem_exe, case, want,
               [] if want == 0 else [DEM, "timeStep", "stability limit", "allowed range (0, "])

# Held drag: relaxation number of a lone grain in a 1000 Pa s liquid.
viscous = (SP, r"viscosity +0\.001;", "viscosity 1000;")
held = (CP, r"^(exchangeEvery\s+[0-9]+;)", r"\1 dragIntegration held; dragRelaxationLimit 0;")
msg = expect("held drag, no limit, exchangeEvery 25 (s about 12)", prepare_exe,
             case_with("W+P-quick", "held_25", [viscous, held]), 2,
             [CP, "exchangeEvery", "drag relaxation number", "> 2", "allowed range [1, "])
m = re.search(r"allowed range \[1, ([0-9]+)\]", msg)
if check(m is not None, "the refusal gives the largest exchangeEvery"):
    most = int(m.group(1))
    for n, want in ((most, 0), (most + 1, 2)):
        every = (CP, r"^exchangeEvery\s+[0-9]+;", f"exchangeEvery {n};")
        expect(f"held drag, no limit, exchangeEvery {n}", prepare_exe,
               case_with("W+P-quick", f"held_{n}", [viscous, held, every]), want,
               [] if want == 0 else [CP, "exchangeEvery", f"value {n}", "drag relaxation number"])
limited = (CP, r"^(exchangeEvery\s+[0-9]+;)", r"\1 dragIntegration held; dragRelaxationLimit 0.5;")
expect("held drag, dragRelaxationLimit 0.5, exchangeEvery 25: warned", prepare_exe,
       case_with("W+P-quick", "held_limited", [viscous, limited]), 0,
       ["warning", CP, "exchangeEvery", "dragRelaxationLimit 0.5", "clamped"])
expect("implicit drag, exchangeEvery 25: no drag warning", prepare_exe,
       case_with("W+P-quick", "implicit", [viscous]), 0, ["drag relaxation beta T / m = "],
       absent=["clamped", "oscillate"])

print("PASS" if inputcase.failures == 0 else f"FAIL ({inputcase.failures} failed)")
sys.exit(1 if inputcase.failures else 0)
