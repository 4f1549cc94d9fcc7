#!/usr/bin/env python3
"""Allrun checks first, then moves a previous run aside, then runs: a wrong start never destroys a
finished run's outputs.

For a copy of each of a dry case (P-quick), a liquid case (W) and a mixture case (W+P-quick),
with a finished run's outputs made up in it (a time directory, postProcessing files, VTK/, dem/,
logs):
  - `./Allrun abc`, `./Allrun 0` (and for the mixture `./Allrun 1 no-such-dir`) exit non-zero with
    a message naming the argument (RANKS, SETTLED_DIR) and the allowed range, and leave every file
    of the case as it was (no file changed, removed or added);
  - an Allrun with one broken dictionary entry (dry: particles.diameter -0.024 in
    constant/sceneProperties; liquid: cellSize -0.03 in system/cfdDict; mixture:
    youngModulusFactor 2 in system/demDict, and, checked before any settling, exchangeEvery 0 or
    an unknown force model in constant/couplingProperties, a NaN liquid viscosity, cells smaller
    than a grain) exits non-zero, the message names file, entry, value and allowed range, and
    again nothing of the case changes;
  - the shipped mixture case starts without a warning (its cells of 2.5 d come with the reason,
    cfdDict coarseCellsReason);
  - a valid start whose run then fails (a program on PATH that stops with an error: mixflowDem
    for the dry and the mixture case, blockMesh for the liquid one) leaves the previous outputs
    byte for byte in the one previous-run.<date>-<time>/ directory the Allrun names; the dry
    Allrun also says that mixflowDem failed, with its exit status, and how to resume from the
    snapshot it wrote (the stand-in writes dem/resume.state at t = 0.25 s);
  - the mixture case given its own dem/ as SETTLED_DIR (a sample settled here, about 6 s) keeps the
    settled sample in dem/ (it is the new run's input) and moves the rest of the previous outputs
    aside.
Nothing else is simulated (the checks are the programs' check modes): seconds.

usage: test_allrun_checks.py REPO_ROOT MIXFLOWDEM MIXFLOWPREPARE WORKDIR"""
import os
import shutil
import subprocess
import sys

import inputcase  # beside this script
from inputcase import check, edit, tree

root, dem_exe, prepare_exe, work = (os.path.abspath(p) for p in sys.argv[1:5])


def write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(text)


def fresh_copy(name):
    return inputcase.copy_inputs(root, name, os.path.join(work, name))


def finished_outputs(case, kind, sample=True):
    """Outputs as a finished run leaves them (made up: only their survival is checked); without
    SAMPLE, a mixture's dem/settled.* are left as they are (a real settled sample)."""
    if kind == "particles":
        write(os.path.join(case, "postProcessing/dem/timeSeries.csv"), "time_s,particles\n0,10\n1.5,10\n")
        write(os.path.join(case, "postProcessing/dem/summary.json"), '{"runout_m": 0.9}\n')
        write(os.path.join(case, "dem/resume.state"), "step 1000;\n")
        write(os.path.join(case, "VTK/particles/particles_1000.vtk"), "# vtk DataFile\n")
        write(os.path.join(case, "log.mixflowDem"), "[mixflowDem] finished at t = 1.5 s\n")
        return
    write(os.path.join(case, "0.5/alpha.liquid"), "FoamFile {}\ninternalField uniform 1;\n")
    write(os.path.join(case, "0.5/uniform/functionObjects/functionObjectProperties"), "{}\n")
    write(os.path.join(case, "postProcessing/liquid/timeSeries.csv"), "time_s,front_x_m\n0,0.5\n0.5,1.2\n")
    write(os.path.join(case, "log.mixflowPrepare"), "[mixflowPrepare] mesh 10 x 2 x 1\n")
    if kind == "liquid":
        write(os.path.join(case, "log.mixflowFoam"), "Time = 0.5\nEnd\n")
        return
    write(os.path.join(case, "postProcessing/dem/timeSeries.csv"), "time_s,particles\n0,10\n")
    write(os.path.join(case, "postProcessing/coupling/exchange.csv"), "time_s,drag_N\n0,0\n")
    if sample:
        write(os.path.join(case, "dem/settled.state"), "settled { fingerprint \"0\"; }\n")
        write(os.path.join(case, "dem/settled.restart"), "restart bytes\n")
    write(os.path.join(case, "dem/coupled.resume.state"), "timeName \"0.5\";\n")
    write(os.path.join(case, "VTK/particles/particles_100.vtk"), "# vtk DataFile\n")
    write(os.path.join(case, "log.mixflowCoupled"), "Time = 0.5\nEnd\n")


def allrun(case, args, path_first=None):
    env = dict(os.environ)
    env["MIXFLOW_ROOT"] = root
    env["PATH"] = os.pathsep.join(([path_first] if path_first else []) + [bindir, env.get("PATH", "")])
    env.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")
    r = subprocess.run(["bash", os.path.join(case, "Allrun"), *args], cwd=case, env=env,
                       capture_output=True, text=True, timeout=120)
    return r.returncode, r.stdout + r.stderr


def refused(case, args, fragments, what):
    before = tree(case)
    rc, msg = allrun(case, args)
    missing = [f for f in fragments if f not in msg]
    after = tree(case)
    changed = sorted(k for k in set(before) | set(after) if before.get(k) != after.get(k))
    ok = check(rc != 0 and not missing and not changed,
               f"{os.path.basename(case)}: ./Allrun {' '.join(args)} ({what}): exit {rc}, "
               f"{msg.strip().splitlines()[-1] if msg.strip() else 'no message'}")
    if not ok:
        print(f"     missing fragments {missing}; changed files {changed[:10]}\n{msg}")


def moved_aside(case, args, fail_dir, kept_in_dem=()):
    """A valid start that fails after the checks: the previous outputs are in previous-run.*/."""
    before = tree(case)
    rc, msg = allrun(case, args, path_first=fail_dir)
    name = os.path.basename(case)
    aside = [d for d in os.listdir(case) if d.startswith("previous-run.")]
    check(rc != 0, f"{name}: ./Allrun {' '.join(args)} with a failing run: exit {rc}")
    if not check(len(aside) == 1 and os.path.join(case, aside[0]) in msg,
                 f"{name}: the Allrun names the one directory the outputs went to ({aside})"):
        print(msg)
        return
    kept = tree(os.path.join(case, aside[0]))
    outputs = {k: v for k, v in before.items()
               if not k.startswith(("constant/", "system/")) and k != "Allrun"}
    lost = sorted(k for k, v in outputs.items()
                  if kept.get(k) != v and not (k in kept_in_dem and tree(case).get(k) == v))
    check(not lost, f"{name}: every previous output is kept unchanged in {aside[0]}/ "
                    f"({len(kept)} files; lost or changed: {lost[:8]})")
    for k in kept_in_dem:
        check(tree(case).get(k) == before[k] and k not in kept,
              f"{name}: {k} stays in the case (the new run's settled sample)")
    inputs = {k: v for k, v in before.items() if k.startswith(("constant/", "system/"))
              and not k.startswith(("system/controlDict", "system/blockMeshDict"))}
    now = tree(case)
    check(all(now.get(k) == v for k, v in inputs.items()), f"{name}: the case's dictionaries are as they were")
    print(f"     {msg.strip().splitlines()[0] if msg.strip() else ''}")
    return msg


os.makedirs(work, exist_ok=True)
# The programs under their names (the Allrun scripts call them through PATH), and a directory of
# stand-ins that fail: mixflowDem runs its real -check and stops otherwise; blockMesh stops.
bindir = os.path.join(work, "bin")
fail_dir = os.path.join(work, "failing-bin")
for d in (bindir, fail_dir):
    shutil.rmtree(d, ignore_errors=True)
    os.makedirs(d)
os.symlink(dem_exe, os.path.join(bindir, "mixflowDem"))
os.symlink(prepare_exe, os.path.join(bindir, "mixflowPrepare"))
write(os.path.join(fail_dir, "mixflowDem"),
      "#!/usr/bin/env bash\nfor a in \"$@\"; do [ \"$a\" = -check ] && exec "
      f"'{dem_exe}' \"$@\"; done\nmkdir -p dem && echo 'time 0.25;' > dem/resume.state\n"
      "echo 'mixflowDem: run stopped: simulated failure' >&2\nexit 1\n")
write(os.path.join(fail_dir, "blockMesh"), "#!/usr/bin/env bash\necho 'simulated failure' >&2\nexit 1\n")
for f in ("mixflowDem", "blockMesh"):
    os.chmod(os.path.join(fail_dir, f), 0o755)

RANKS = ["RANKS", "1 to 100000", "nothing was run or removed"]
SCENES = [
    ("P-quick", "particles", ("constant/sceneProperties", r"diameter +0\.024;", "diameter -0.024;"),
     ["constant/sceneProperties", "particles.diameter", "-0.024", "(0, inf)", "nothing was run"]),
    ("W", "liquid", ("system/cfdDict", r"^cellSize +0\.03;", "cellSize -0.03;"),
     ["system/cfdDict", "cellSize", "-0.03", "(0, inf)", "nothing was run"]),
    ("W+P-quick", "mixture", ("system/demDict", r"youngModulusFactor +1e-3;", "youngModulusFactor 2;"),
     ["system/demDict", "youngModulusFactor", "2", "(0, 1]", "nothing was run"]),
]
for name, kind, (rel, pattern, repl), fragments in SCENES:
    case = fresh_copy(name)
    finished_outputs(case, kind)
    refused(case, ["abc"], RANKS + ["'abc'"], "not a number")
    refused(case, ["0"], RANKS + ["'0'"], "zero ranks")
    if kind == "mixture":
        refused(case, ["1", os.path.join(work, "no-such-dir")], ["SETTLED_DIR", "no-such-dir",
                                                                 "nothing was run"], "no sample there")
    original = edit(case, rel, pattern, repl)
    refused(case, ["1"], fragments, f"broken entry in {rel}")
    open(os.path.join(case, rel), "w").write(original)
    msg = moved_aside(case, ["1"], fail_dir)
    if kind == "particles":
        # A failed dry run says so, and how to resume from its last snapshot (dem/resume.state).
        check(msg is not None and "mixflowDem failed with exit status 1" in msg
              and "to continue from the last write (t = 0.25 s)" in msg
              and "resumeDemCase 1" in msg, f"{name}: the failed run says so and how to resume")
    if kind == "mixture":
        # W+P-quick's 0.06 m cells are 2.5 d, and its cfdDict says why (coarseCellsReason): the
        # shipped case starts without a warning.
        check(msg is not None and "warning" not in msg.lower(),
              f"{name}: the shipped case's checks give no warning")

# A mixture's liquid, fluid mesh and coupling entries are checked before the settling too
# (mixflowPrepare -check, without a settled sample): refused, nothing touched.
case = fresh_copy("W+P-quick")
finished_outputs(case, "mixture")
for rel, pattern, repl, fragments in [
        ("constant/couplingProperties", r"^exchangeEvery +25;", "exchangeEvery 0;",
         ["constant/couplingProperties", "exchangeEvery", "[1, 1e+09]"]),
        ("constant/couplingProperties", r"buoyancy viscousForce", "buoyancyy viscousForce",
         ["constant/couplingProperties", "forceModels", "'buoyancyy'"]),
        ("constant/sceneProperties", r"viscosity +0\.001;", "viscosity nan;",
         ["constant/sceneProperties", "liquid.viscosity", "nan", "(0, inf)"]),
        ("system/cfdDict", r"^cellSize +0\.06;", "cellSize 0.02;",
         ["system/cfdDict", "cellSize", "allowed range [0.024"])]:
    original = edit(case, rel, pattern, repl)
    refused(case, ["1"], fragments + ["nothing was run"], f"{fragments[1]} in {rel}, before settling")
    open(os.path.join(case, rel), "w").write(original)

# A mixture rerun on its own settled sample (a real one: the Allrun checks it before it moves
# anything): the sample stays in dem/, the rest goes aside.
case = fresh_copy("W+P-quick")
r = subprocess.run([dem_exe, "-case", case, "-settleOnly"], capture_output=True, text=True, timeout=120)
check(r.returncode == 0, f"W+P-quick settles its sample for the rerun (exit {r.returncode})")
finished_outputs(case, "mixture", sample=False)
moved_aside(case, ["1", "dem"], fail_dir,
            kept_in_dem=("dem/settled.state", "dem/settled.restart", "dem/settled.inputs",
                         "dem/settled.entries"))

print("PASS" if inputcase.failures == 0 else f"FAIL ({inputcase.failures} failed)")
sys.exit(1 if inputcase.failures else 0)
