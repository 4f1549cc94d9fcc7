#!/usr/bin/env python3
"""One command checks every dictionary of a case of any content before anything runs:
`mixflowPrepare -check` (and `mixflowDem -check` for the DEM half).

For copies of the committed cases (W+P-quick: mixture, P-quick: dry, W: liquid), inputs only:
  - the valid mixture passes `mixflowPrepare -check` without its settled sample (the
    nominal sample height and packing), says which checks wait for the sample, and writes
    nothing: no dem/ directory, no file changed or added; a stale sample in dem/ (settled from
    other inputs) does not matter to it; the valid dry and liquid cases pass too;
  - the force models are built with the case's liquid law: a Herschel-Bulkley mixture takes the
    slip drag closure's settings, a water one refuses them;
  - each broken entry exits with status 2 and a message naming file, entry, value and allowed
    range (or the reason): a mixture's unknown force model, empty force model list, NaN viscosity,
    exchangeEvery 0, liquid lighter than air and a DEM entry; cells smaller than a grain;
    a coupled step whose Courant number estimate dt 2 sqrt(g H) / dx exceeds 1; writeInterval >
    endTime (mixture, dry and liquid); particles.density 1e300 (mixture and dry); a sample
    narrower than a grain reported against sample.width;
  - unit slips (outside an entry's plausible range, docs/parameters.md) are refused naming the
    plausible range and the unit that explains the value: E = 70 (GPa typed as Pa) in a dry case and
    a mixture, a wall modulus of 0.7, liquid density 1.26 (g/cm³), a kinematic viscosity typed for
    the dynamic one, grain density 2.5, a diameter of 24 (mm), a sample length of 450 (mm); the air
    pore fluid of P-bulk (density 1.2) passes;
  - the warnings exit 0 and give the reason: cells of 2.1 d (below 3 d; a note giving the case's
    reason instead when cfdDict coarseCellsReason states one), a Courant number estimate
    of 0.67 (above maxCo 0.5).
Nothing is simulated: well under a minute in all.

usage: test_case_check.py REPO_ROOT MIXFLOWDEM MIXFLOWPREPARE WORKDIR"""
import os
import re
import subprocess
import sys

import inputcase  # beside this script
from inputcase import check, edit, last_line, tree

root, dem_exe, prepare_exe, work = (os.path.abspath(p) for p in sys.argv[1:5])


def copy(name, dest):
    return inputcase.copy_inputs(root, name, os.path.join(work, dest))


def run(exe, case):
    r = subprocess.run([exe, "-case", case, "-check"], capture_output=True, text=True, timeout=60)
    return r.returncode, r.stdout + r.stderr


os.makedirs(work, exist_ok=True)

# The valid cases.
case = copy("W+P-quick", "valid-mixture")
before = tree(case)
rc, msg = run(prepare_exe, case)
check(rc == 0, f"W+P-quick passes mixflowPrepare -check without a settled sample (exit {rc})")
check("checked without the settled sample" in msg and "nominal sample height" in msg,
      "it says it used the nominal sample and which checks wait for the settled one")
check(not os.path.exists(os.path.join(case, "dem")), "no dem/ directory is created")
check(tree(case) == before, "no file of the case is changed or added")
# A sample settled from other inputs (the previous run's, before an edit): not read by -check.
os.makedirs(os.path.join(case, "dem"))
with open(os.path.join(case, "dem", "settled.state"), "w") as f:
    f.write('settled { fingerprint "0"; particles 10; height 5; }\n')
before = tree(case)
rc, msg = run(prepare_exe, case)
check(rc == 0 and tree(case) == before, f"a stale dem/settled.state does not affect -check (exit {rc})")
for name, kind in (("P-quick", "dry"), ("W", "liquid"), ("P-bulk", "bulk model, air as the pore fluid")):
    case = copy(name, f"valid-{kind}")
    before = tree(case)
    rc, msg = run(prepare_exe, case)
    check(rc == 0 and tree(case) == before,
          f"{name} ({kind}) passes mixflowPrepare -check, writing nothing (exit {rc}): {last_line(msg)}")

SP, CP, CFD, CTL, DEM = ("constant/sceneProperties", "constant/couplingProperties", "system/cfdDict",
                         "system/controlDict", "system/demDict")
# (what, case, exe, file, pattern, replacement, exit status, expected fragments): refused with exit
# status 2, nothing written, or warned with exit status 0.
CASES = [
    ("unknown force model", "W+P-quick", prepare_exe, CP, r"buoyancy viscousForce", "buoyancyy viscousForce", 2,
     [CP, "forceModels", "'buoyancyy'", "available: DiFeliceDrag GidaspowDrag buoyancy viscousForce"]),
    ("no force model", "W+P-quick", prepare_exe, CP, r"^forceModels .*$", "forceModels ();", 2,
     [CP, "forceModels", "lists no model"]),
    ("NaN viscosity", "W+P-quick", prepare_exe, SP, r"viscosity +0\.001;", "viscosity nan;", 2,
     [SP, "liquid.viscosity", "nan", "(0, inf)"]),
    ("exchangeEvery 0", "W+P-quick", prepare_exe, CP, r"^exchangeEvery +25;", "exchangeEvery 0;", 2,
     [CP, "exchangeEvery", "value 0", "[1, 1e+09]"]),
    ("liquid lighter than air", "W+P-quick", prepare_exe, SP, r"density +1000;", "density 0.5;", 2,
     [SP, "liquid.density", "0.5", "air density"]),
    ("DEM entry of a mixture", "W+P-quick", prepare_exe, DEM, r"^youngModulusFactor +1e-3;",
     "youngModulusFactor 2;", 2, [DEM, "youngModulusFactor", "2", "(0, 1]"]),
    # The drag viscosity closures see the case's liquid as mixflowCoupled does: slip settings are
    # read for a yield-stress liquid (dragViscosity auto = slip), refused for water.
    ("slip drag settings, yield-stress liquid", "HB+P", prepare_exe, CP, r"^(voidFractionModel.*)$",
     r"\1\nDiFeliceDragCoeffs { slipCoeffs { shearRateFactor 1; } }", 0, ["mixture before settling"]),
    ("slip drag settings, water", "W+P-quick", prepare_exe, CP, r"^(voidFractionModel.*)$",
     r"\1\nDiFeliceDragCoeffs { slipCoeffs { shearRateFactor 1; } }", 2,
     [CP, "DiFeliceDragCoeffs.slipCoeffs", "dragViscosity slip"]),
    ("cells smaller than a grain", "W+P-quick", prepare_exe, CFD, r"^cellSize +0\.06;", "cellSize 0.02;", 2,
     [CFD, "cellSize", "0.02 m", "0.833 particle diameters", "at least 1 d", "allowed range [0.024, 0.075]"]),
    # Unit slips (docs/parameters.md, "Plausible ranges"): refused before the run, naming the
    # plausible range and the unit that explains the value. E = 70 typed for 70 GPa, in a dry case
    # (mixflowDem, and mixflowPrepare -check of it) and in a mixture.
    ("E in GPa, dry", "P-quick", dem_exe, SP, r"youngModulus +70e9;", "youngModulus 70;", 2,
     [SP, "particles.youngModulus", "value 70 Pa", "plausible range [1e5, 1.2e12] Pa",
      "typed in GPa, it is 7e10 Pa"]),
    ("E in GPa, dry, mixflowPrepare", "P-quick", prepare_exe, SP, r"youngModulus +70e9;", "youngModulus 70;", 2,
     [SP, "particles.youngModulus", "value 70 Pa", "typed in GPa, it is 7e10 Pa"]),
    ("E in GPa, mixture", "W+P-quick", prepare_exe, SP, r"youngModulus +70e9;", "youngModulus 70;", 2,
     [SP, "particles.youngModulus", "value 70 Pa", "typed in GPa, it is 7e10 Pa"]),
    ("wall E in MPa", "P-quick", dem_exe, SP, r"wallYoungModulus +700e9;", "wallYoungModulus 0.7;", 2,
     [SP, "particles.wallYoungModulus", "value 0.7 Pa", "plausible range"]),
    ("liquid density in g/cm3", "W+P-quick", prepare_exe, SP, r"density +1000;", "density 1.26;", 2,
     [SP, "liquid.density", "1.26 kg/m3", "gas's density", "viscosity 0.001 Pa s is a liquid's",
      "typed in g/cm³, it is 1260 kg/m3", "[50, 25000]"]),
    ("liquid density in g/cm3, liquid case", "W", prepare_exe, SP, r"density +1000;", "density 1.26;", 2,
     [SP, "liquid.density", "typed in g/cm³, it is 1260 kg/m3"]),
    ("kinematic viscosity for the dynamic one", "W", prepare_exe, SP, r"viscosity +0\.001;", "viscosity 1e-6;", 2,
     [SP, "liquid.viscosity", "plausible range [1e-05, 1e8] Pa s", "kinematic viscosity", "0.001 Pa s"]),
    ("grain density in g/cm3", "W+P-quick", prepare_exe, SP, r"density +2500;", "density 2.5;", 2,
     [SP, "particles.density", "2.5", "[10, 25000]", "typed in g/cm³, it is 2500 kg/m3"]),
    ("diameter in mm", "P-quick", dem_exe, SP, r"diameter +0\.024;", "diameter 24;", 2,
     [SP, "particles.diameter", "value 24 m", "plausible range [1e-5, 0.5] m", "typed in mm, it is 0.024 m"]),
    ("sample length in mm", "P-quick", dem_exe, SP, r"length +0\.45;", "length 450;", 2,
     [SP, "sample.length", "value 450 m", "typed in mm, it is 0.45 m"]),
    # W+P-quick says why its cells are 2.5 d (coarseCellsReason): a note then; without the reason
    # the same cells are warned.
    ("cells of 2.1 d", "W+P-quick", prepare_exe, CFD, r"^cellSize +0\.06;.*\n^coarseCellsReason .*$",
     "cellSize 0.05;", 0,
     [CFD, "warning", "cellSize", "2.08 particle diameters", "at least 3 d", "cellSize >= 0.072 m"]),
    ("cells of 2.1 d with the case's reason", "W+P-quick", prepare_exe, CFD, r"^cellSize +0\.06;",
     "cellSize 0.05;", 0,
     [CFD, "note: ", "cellSize", "2.08 particle diameters", "below the 3 d advised", "coarseCellsReason",
      "the quick case keeps 5 cells"]),
    ("Courant estimate above 1", "W+P-quick", prepare_exe, CP, r"^exchangeEvery +25;", "exchangeEvery 1500;", 2,
     [CP, "exchangeEvery", "value 1500", "Courant number estimate", "3.37", "2 sqrt(g H) = 3.43 m/s",
      "H = 0.3 m", "exceeds 1", "allowed range [1, 445]"]),
    ("Courant estimate above maxCo", "W+P-quick", prepare_exe, CP, r"^exchangeEvery +25;", "exchangeEvery 300;", 0,
     [CP, "warning", "exchangeEvery", "Courant number estimate", "0.673", "maxCo 0.5", "exchangeEvery <= 222"]),
    ("writeInterval > endTime, mixture", "W+P-quick", prepare_exe, CTL, r"^endTime +1\.5;", "endTime 0.04;", 2,
     [CTL, "writeInterval", "exceeds endTime", "resume state", "allowed range (0, 0.04]"]),
    ("writeInterval > endTime, dry", "P-quick", dem_exe, CTL, r"^endTime +[0-9.]+;", "endTime 0.01;", 2,
     [CTL, "writeInterval", "exceeds endTime", "allowed range (0, 0.01]"]),
    ("writeInterval > endTime, liquid", "W", prepare_exe, CTL, r"^endTime +[0-9.]+;", "endTime 0.01;", 2,
     [CTL, "writeInterval", "exceeds endTime", "allowed range (0, 0.01]"]),
    ("grain density 1e300, mixture", "W+P-quick", prepare_exe, SP, r"density +2500;", "density 1e300;", 2,
     [SP, "particles.density", "1e300", "[10, 25000]"]),
    ("grain density 1e300, dry", "P-quick", dem_exe, SP, r"density +2500;", "density 1e300;", 2,
     [SP, "particles.density", "1e300", "[10, 25000]"]),
    ("sample narrower than a grain", "P-quick", dem_exe, SP, r"width +0\.12;", "width 0.02;", 2,
     [SP, "sample.width", "0.02", "below one particle diameter", "[0.024, inf)"]),
]
for what, name, exe, rel, pattern, repl, want, fragments in CASES:
    case = copy(name, re.sub(r"\W+", "_", what))
    edit(case, rel, pattern, repl)
    before = tree(case)
    rc, msg = run(exe, case)
    missing = [f for f in fragments if f not in msg]
    if "sample.width" in fragments and "sample.length" in msg:
        missing.append("(names sample.length)")
    if not check(rc == want and not missing and tree(case) == before,
                 f"{what}: {os.path.basename(exe)} -check exit {rc} ({'refused' if want else 'passes'}): "
                 f"{last_line(msg)}"):
        print(f"     missing fragments {missing}\n{msg}")

print("PASS" if inputcase.failures == 0 else f"FAIL ({inputcase.failures} failed)")
sys.exit(1 if inputcase.failures else 0)
