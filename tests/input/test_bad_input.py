#!/usr/bin/env python3
"""Bad input stops before the run with a message naming the file, the entry and the
allowed range (or the allowed words). Each case breaks one thing in a copy of a valid case and runs
`mixflowDem -check`, which must exit with status 2 and print all the expected fragments.

usage: test_bad_input.py MIXFLOWDEM VALID_CASE WORKDIR"""
import os
import re
import shutil
import subprocess
import sys

exe, valid, work = sys.argv[1], sys.argv[2], sys.argv[3]

# (name, file, regex replacement (pattern, repl) or None to delete the file, expected fragments)
CASES = [
    ("unknown entry", "constant/sceneProperties", (r"diameter 0.012;", "diameter 0.012; diamter 0.01;"),
     ["constant/sceneProperties", "particles.diamter", "unknown entry", "allowed entries here", "diameter"]),
    ("negative diameter", "constant/sceneProperties", (r"diameter 0.012;", "diameter -0.012;"),
     ["constant/sceneProperties", "particles.diameter", "-0.012", "(0, inf)"]),
    ("restitution above one", "constant/sceneProperties", (r"diameter 0.012;", "diameter 0.012; restitution 1.5;"),
     ["particles.restitution", "1.5", "(0, 1]"]),
    ("impossible solid fraction", "constant/sceneProperties", (r"solidFraction 0.6056;", "solidFraction 0.9;"),
     ["sample.solidFraction", "0.9", "(0, 0.64]"]),
    ("unknown rolling model", "constant/sceneProperties", (r"diameter 0.012;", "diameter 0.012; rollingModel sticky;"),
     ["particles.rollingModel", "sticky", "cdt, epsd2, off"]),
    ("channel shorter than sample", "constant/sceneProperties", (r"channel \{ length 0.8;", "channel { length 0.2;"),
     ["channel.length", "0.2", "sample length"]),
    ("unsafe time step", "system/demDict", (r"youngModulusFactor 1e-4;", "youngModulusFactor 1e-4; timeStep 1e-3;"),
     ["system/demDict", "timeStep", "0.001", "stability limit", "allowed range (0, "]),
    ("softening out of range", "system/demDict", (r"youngModulusFactor 1e-4;", "youngModulusFactor 2;"),
     ["system/demDict", "youngModulusFactor", "(0, 1]"]),
    ("stiffening from a stiffer sample", "system/demDict", (r"settle \{ maxTime 2; packingControl off; \}", "settle { maxTime 2; stiffenFrom 1e-3; }"),
     ["system/demDict", "settle.stiffenFrom", "0.001", "must be below youngModulusFactor (0.0001)", "allowed range 0 (no stiffening) or (0, 0.0001)"]),
    ("negative stiffening factor", "system/demDict", (r"settle \{ maxTime 2; packingControl off; \}", "settle { maxTime 2; stiffenFrom -1e-5; }"),
     ["system/demDict", "settle.stiffenFrom", "-1e-5", "[0, 1]"]),
    ("no stiffening steps", "system/demDict", (r"settle \{ maxTime 2; packingControl off; \}", "settle { maxTime 2; stiffenFrom 1e-5; stiffenSteps 0; }"),
     ["system/demDict", "settle.stiffenSteps", "[1, 100]"]),
    ("settling friction range reversed", "system/demDict", (r"settle \{ maxTime 2; packingControl off; \}", "settle { minFriction 0.5; maxFriction 0.2; }"),
     ["system/demDict", "settle.maxFriction", "0.2", "must be above minFriction (0.5)", "allowed range (0.5, 2]"]),
    ("first settling friction outside the control's range", "system/demDict", (r"settle \{ maxTime 2; packingControl off; \}", "settle { friction 0.1; minFriction 0.2; }"),
     ["system/demDict", "settle.friction", "0.1", "[minFriction, maxFriction]", "allowed range [0.2, 1]", "packingControl off"]),
    ("unknown packing control", "system/demDict", (r"packingControl off;", "packingControl density;"),
     ["system/demDict", "settle.packingControl", "density", "friction, off"]),
    ("packing tolerance out of range", "system/demDict", (r"packingControl off;", "packingTolerance 0.2;"),
     ["system/demDict", "settle.packingTolerance", "0.2", "[0.0001, 0.05]"]),
    ("not a number", "system/controlDict", (r"endTime 1.5;", "endTime soon;"),
     ["system/controlDict", "endTime", "'soon' is not a number"]),
    ("missing file", "system/demDict", None, ["system/demDict", "cannot open file"]),
    ("missing required entry", "constant/sceneProperties", (r"content particles;", ""),
     ["constant/sceneProperties", "content", "missing"]),
    ("syntax error", "system/controlDict", (r"endTime 1.5;", "endTime 1.5"), ["system/controlDict", "endTime", "missing ';'"]),
]

failures = 0
for name, rel, edit, expected in CASES:
    case = os.path.join(work, re.sub(r"\W+", "_", name))
    if os.path.exists(case):
        shutil.rmtree(case)
    shutil.copytree(valid, case)
    path = os.path.join(case, rel)
    if edit is None:
        os.remove(path)
    else:
        text = open(path).read()
        new = re.sub(edit[0], edit[1], text, count=1)
        assert new != text, f"{name}: the edit did not apply to {rel}"
        open(path, "w").write(new)
    res = subprocess.run([exe, "-case", case, "-check"], capture_output=True, text=True)
    msg = res.stdout + res.stderr
    missing = [f for f in expected if f not in msg]
    ok = res.returncode == 2 and not missing
    print(f"{'ok  ' if ok else 'FAIL'} {name}: exit {res.returncode}; {msg.strip().splitlines()[-1] if msg.strip() else ''}")
    if not ok:
        failures += 1
        print(f"     expected exit 2 and fragments {missing}")
# The valid case itself must pass the check (else every case above would trivially fail).
res = subprocess.run([exe, "-case", valid, "-check"], capture_output=True, text=True)
if res.returncode != 0:
    failures += 1
    print("FAIL valid case rejected:", res.stdout, res.stderr)
print(f"{len(CASES) + 1 - failures} passed, {failures} failed")
sys.exit(1 if failures else 0)
