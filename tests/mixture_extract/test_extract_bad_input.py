#!/usr/bin/env python3
"""Bad input stops mixflowExtract with exit status 2 and a message naming the file,
the entry and the allowed range (or the available data), before anything is written (the output
directory is compared before and after each case). Each case breaks one thing in a copy of a
valid synthetic case (particles only, snapshots every 0.01 s up to 0.09 s, finished): among
them bins finer than a grain or a fluid cell (allowed bin counts named), and a finished run
whose fluid wrote only its initial state (refused as missing fluid fields).

usage: test_extract_bad_input.py MIXFLOWEXTRACT WORKDIR"""
import hashlib
import os
import re
import shutil
import subprocess
import sys

import numpy as np

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
from mixflow import synthcase as sc  # noqa: E402

exe, work = sys.argv[1], sys.argv[2]
valid = os.path.join(work, "valid")
if os.path.exists(work):
    shutil.rmtree(work)
os.makedirs(valid)
L, H, W, d = 0.3, 0.12, 0.06, 0.012
sc.scene(valid, L=L, H=H, W=W, d=d)
DICT = ("grid { x (0 0.3 6); y (0 0.12 3); }\n"
        "windows { list ((0 0.05) (0.05 0.1)); }\n")
sc.write(os.path.join(valid, "system/extractDict"), DICT)
x = sc.jittered_lattice(L, H, W, d)
n = len(x)
m = 2500 * np.pi / 6 * d**3 * np.ones(n)
entries = []
for k in range(10):
    name = f"particles/particles_{100 * k}.vtk"
    sc.vtk(os.path.join(valid, "VTK", name), x, np.zeros((n, 3)), m, np.full(n, d / 2), np.zeros((n, 6)))
    entries.append((name, round(0.01 * k, 10)))
sc.series(valid, entries)
sc.finish(valid)


def edit_dict(pattern, repl):
    def f(case):
        p = os.path.join(case, "system/extractDict")
        t = open(p).read()
        new = re.sub(pattern, repl, t, count=1)
        assert new != t, pattern
        open(p, "w").write(new)
    return f


def remove(rel):
    return lambda case: os.remove(os.path.join(case, rel))


def drop_array(case):
    sc.vtk(os.path.join(case, "VTK/particles/particles_300.vtk"), x, np.zeros((n, 3)), m, np.full(n, d / 2),
           np.zeros((n, 6)), drop=("c_pstress[4-6]",))


def initial_fluid_only(case):
    """The fluid's initial write (0/) alone, as a run that wrote no fluid fields leaves it."""
    c = np.array([[0.05, 0.05, 0.03], [0.15, 0.05, 0.03]])
    sc.foam_time(case, "0", c, [1e-3, 1e-3], np.zeros((2, 3)), [0, 0], [1, 1], [1, 1])
    edit_dict(r"windows", "liquidDensity 1000;\nwindows")(case)


def with_cfd_dict(case):
    """A fluid mesh of 0.1 m cells (system/cfdDict): bins of 0.05 m would split its cells."""
    sc.write(os.path.join(case, "system/cfdDict"), "cellSize 0.1;\n")
    initial_fluid_only(case)
    sc.foam_time(case, "0.05", np.array([[0.05, 0.05, 0.03]]), [1e-3], np.zeros((1, 3)), [0], [1], [1])


def run_then_regrid(case):
    r = subprocess.run([exe, "-case", case], capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
    edit_dict(r"x \(0 0.3 6\)", "x (0 0.3 5)")(case)


# (name, change to the copy, extra arguments, expected fragments)
CASES = [
    ("no such case", None, ["-case", os.path.join(work, "does_not_exist")], ["does_not_exist", "does not exist"]),
    ("grid outside the domain", edit_dict(r"x \(0 0.3 6\)", "x (0 5 6)"), [],
     ["system/extractDict", "grid.x", "[0, 5]", "outside the domain [-0.006, 0.806]", "channel.length", "one particle radius"]),
    ("grid below the floor", edit_dict(r"y \(0 0.12 3\)", "y (-0.1 0.12 3)"), [],
     ["system/extractDict", "grid.y", "outside the domain [-0.006, 0.406]"]),
    ("fractional bin count", edit_dict(r"x \(0 0.3 6\)", "x (0 0.3 2.5)"), [],
     ["grid.x", "2.5", "whole number in [1, 100000]"]),
    # 1 mm bins: finer than a grain (d 0.012 m); 25 bins of 0.012 m fit into 0.3 m.
    ("bins finer than a grain", edit_dict(r"x \(0 0.3 6\)", "x (0 0.3 300)"), [],
     ["system/extractDict", "grid.x", "bins of 0.001 m", "finer than a grain", "particles.diameter",
      "0.012", "allowed bin count [1, 25]"]),
    ("bins finer than a grain in y", edit_dict(r"y \(0 0.12 3\)", "y (0 0.12 20)"), [],
     ["system/extractDict", "grid.y", "bins of 0.006 m", "allowed bin count [1, 10]"]),
    # 0.1 m fluid cells (8 over the 0.8 m channel, 4 over its 0.4 m height): bins of 0.05 m in x
    # split them; at most 3 bins of 0.1 m over the 0.3 m grid.
    ("bins finer than a fluid cell", with_cfd_dict, [],
     ["system/extractDict", "grid.x", "bins of 0.05 m", "finer than a fluid cell", "cellSize",
      "allowed bin count [1, 3]"]),
    ("finished run without fluid fields", initial_fluid_only, [],
     ["the fluid fields are missing", "only fluid write is the initial state at t = 0",
      "reconstructPar", "fluid { source none; }"]),
    ("empty window", edit_dict(r"\(0.05 0.1\)", "(0.052 0.058)"), [],
     ["system/extractDict", "windows.list", "2nd pair", "[0.052, 0.058)", "holds no particle snapshot",
      "t = 0.05 and 0.06", "[0, 0.09]"]),
    ("window after the end", edit_dict(r"\(0.05 0.1\)", "(0.5 0.6)"), [],
     ["windows.list", "2nd pair", "starts after the last snapshot", "0.09"]),
    ("t1 before t0", edit_dict(r"\(0.05 0.1\)", "(0.1 0.05)"), [], ["windows.list", "2nd pair", "t1 > t0"]),
    ("list and width", edit_dict(r"list", "width 0.05; list"), [], ["windows.width", "either 'list' or"]),
    ("missing extractDict", remove("system/extractDict"), [],
     ["system/extractDict", "cannot open file", "mixture_extract/README.md"]),
    ("unknown entry", edit_dict(r"windows", "tresholds { minVelocity 1; }\nwindows"), [],
     ["tresholds", "unknown entry", "thresholds"]),
    ("threshold out of range", edit_dict(r"windows", "thresholds { minSaturation 1.5; }\nwindows"), [],
     ["thresholds.minSaturation", "1.5", "[0, 1]"]),
    ("unknown pressure convention", edit_dict(r"windows", "pressureConvention kinematic;\nwindows"), [],
     ["pressureConvention", "kinematic", "raw, density, both"]),
    ("region without a bin", edit_dict(r"windows", "regions { thin { x (0.01 0.02); y (0 0.1); } }\nwindows"), [],
     ["regions.thin.x", "no bin centre"]),
    ("openfoam fluid requested but absent", edit_dict(r"windows", "fluid { source openfoam; }\nwindows"), [],
     ["fluid.source", "no time directory", "U"]),
    ("snapshot lacks the stress", drop_array, [], ["particles_300.vtk", "missing array", "c_pstress[4-6]"]),
    ("listed snapshot missing", remove("VTK/particles/particles_200.vtk"), [],
     ["particles_200.vtk", "cannot open file"]),
    ("no snapshot index", remove("VTK/particles.vtk.series"), [], ["particles.vtk.series", "cannot open file"]),
    ("settings changed since the file was made", run_then_regrid, [],
     ["mixture.h5", "other extractor settings", "-overwrite"]),
    ("unknown option", None, ["-bogus"], ["unknown option '-bogus'"]),
    ("contact stress without contact files", edit_dict(r"windows", "particles { stress contacts; }\nwindows"), [],
     ["system/extractDict", "particles.stress", "contacts", "VTK/contacts/pairs_<step>.txt",
      "contactSnapshots on", "virial or auto"]),
    ("kernel width out of range", edit_dict(r"windows", "kernel { shape lucy; width 20; }\nwindows"), [],
     ["system/extractDict", "kernel.width", "20", "[0.5, 10]"]),
    ("unknown kernel", edit_dict(r"windows", "kernel { shape tophat; }\nwindows"), [],
     ["kernel.shape", "tophat", "bins, lucy, gaussian"]),
    ("pair tolerance above half the write interval", edit_dict(r"windows", "pairTolerance 0.006;\nwindows"), [],
     ["system/extractDict", "pairTolerance", "0.006", "[0, 0.005]"]),
    ("liquid share out of range", edit_dict(r"windows", "thresholds { minLiquidShare 1.5; }\nwindows"), [],
     ["system/extractDict", "thresholds.minLiquidShare", "1.5", "[0, 1]"]),
    ("window width changed since the file was made", lambda case: (
        subprocess.run([exe, "-case", case], capture_output=True, check=True),
        sc.write(os.path.join(case, "system/extractDict"),
                 "grid { x (0 0.3 6); y (0 0.12 3); }\nwindows { start 0; width 0.05; }\n"),
        subprocess.run([exe, "-case", case, "-overwrite"], capture_output=True, check=True),
        edit_dict(r"width 0.05", "width 0.03")(case)), [],
     ["mixture.h5", "width 0.05 s", "windows.width", "now 0.03 s", "-overwrite"]),
]


def outputs(case):
    """Digest of every file under the case's output directory (None when there is none)."""
    d = os.path.join(case, "postProcessing/mixture")
    if not os.path.isdir(d):
        return None
    return {n: hashlib.sha256(open(os.path.join(d, n), "rb").read()).hexdigest() for n in sorted(os.listdir(d))}


failures = 0
for name, change, extra, expected in CASES:
    case = os.path.join(work, re.sub(r"\W+", "_", name))
    if "-case" not in extra:
        shutil.copytree(valid, case)
    if change:
        change(case)
    before = outputs(case)
    args = extra if "-case" in extra else ["-case", case, *extra]
    res = subprocess.run([exe, *args], capture_output=True, text=True)
    msg = res.stdout + res.stderr
    missing = [f for f in expected if f not in msg]
    if outputs(case) != before:
        missing.append("(the outputs changed: bad input must stop before anything is written)")
    ok = res.returncode == 2 and not missing
    last = [ln for ln in msg.strip().splitlines() if "error" in ln or "unknown" in ln]
    print(f"{'ok  ' if ok else 'FAIL'} {name}: exit {res.returncode}; {last[0] if last else msg.strip()[:200]}")
    if not ok:
        failures += 1
        print(f"     missing fragments: {missing}\n     full output:\n{msg}")
    if ok and os.path.exists(case):
        shutil.rmtree(case)
# The valid case itself extracts.
res = subprocess.run([exe, "-case", valid], capture_output=True, text=True)
print(f"{'ok  ' if res.returncode == 0 else 'FAIL'} valid case: exit {res.returncode}")
failures += res.returncode != 0
print(f"{failures} failure(s) in {len(CASES) + 1} cases")
sys.exit(1 if failures else 0)
