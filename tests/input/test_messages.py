#!/usr/bin/env python3
"""Messages point at the real cause, before anything runs or is moved, or the case is handled.

On copies of the committed cases (their Allrun scripts with the programs of the build on PATH):
  1. a bulk-model mixture without system/demDict (W+P-quick with cfdDict mixtureModel bulk, no
     demDict or couplingProperties) refused for its own error, never "system/demDict": solid
     fraction 0.9, lambda_p nan and -5, an unknown entry lambdaUU, tanPhi -1, mixtureModel bulky,
     drift fields of 329 cells for the 330 of the mesh; each message names file, entry, value and
     allowed range, and no file of the case changes;
  2. SETTLED_DIR unusable: a sample settled with another grain density (particles.density 2600
     against the sample's 2500, named as such) and a sample without settled.restart are refused
     by the Allrun before the previous run is moved aside (no file of the case changes);
  3. a copy of a case outside the checkout, without MIXFLOW_ROOT, finds scripts/RunFunctions
     beside the programs on PATH (its check then runs: the message is the dictionary's, exit 2, not
     bash's 127); without the programs on PATH it says how to set MIXFLOW_ROOT (exit 2);
  4. the shipped W+P-quick starts without a warning and says once why its cells are 2.5 d (the
     note of cfdDict coarseCellsReason); without that reason the warning is given once, not again
     by the run's log; the run creates <case>.foam for ParaView (also a liquid case);
  5. a disk with less than MIXFLOW_MIN_FREE_MB free (a stand-in df reporting 5 MB) is refused
     before anything is moved, saying "no space left on device" and naming the directory; a disk
     that fills during the run (a real 4 MB tmpfs when mounting is allowed, else a stand-in solver
     that leaves a half-written time directory and says ENOSPC's text) ends with "no space left on
     device", the directory, no half-written time directory left, and the command to resume; on
     the real disk the solver itself stops before the write that would not fit (RunTime.H: the
     free space against the last write's size), naming the directory and the last complete write;
  6. bulk-model drift fields clipped to the admissible bound alpha_s + lambda alpha_f >= 0.01
     (lambda_u = -1.5101419878296147 at alpha_s 0.6056, 17 digits as calibrate_drifts.py writes
     them) keep their value through decomposePar on 2 ranks (each rank's value within the bound;
     with 10 digits, -1.510141988, it would not be) and mixflowBulkFoam accepts them on 2 ranks.
The settling (W+P-quick, about 6 s), the filled disk (about 10 s) and the 2-rank step are the only
runs.

usage: test_messages.py REPO_ROOT BUILD_BIN WORKDIR"""
import os
import re
import shutil
import subprocess
import sys

import inputcase  # beside this script
from inputcase import check, edit, tree

root, build_bin, work = (os.path.abspath(p) for p in sys.argv[1:4])
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
bindir = os.path.join(work, "bin")
os.makedirs(bindir)
for exe in ("mixflowDem", "mixflowPrepare", "mixflowFoam", "mixflowBulkFoam"):
    os.symlink(os.path.join(build_bin, exe), os.path.join(bindir, exe))


def write(path, text, mode=None):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(text)
    if mode:
        os.chmod(path, mode)


def standin(name, body, **more):
    """A directory of executable stand-ins, NAME with BODY and the others of MORE (put first on
    PATH)."""
    d = os.path.join(work, "standin-" + name)
    for n, b in {name: body, **more}.items():
        write(os.path.join(d, n), "#!/usr/bin/env bash\n" + b, 0o755)
    return d


def env(path_first=(), mixflow_root=True, programs=True, **extra):
    e = dict(os.environ)
    e.pop("MIXFLOW_ROOT", None)
    if mixflow_root:
        e["MIXFLOW_ROOT"] = root
    parts = list(path_first) + ([bindir] if programs else []) + ["/usr/bin", "/bin"]
    e["PATH"] = os.pathsep.join(parts)
    e.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")
    e.update(extra)
    return e


def allrun(case, args=(), **kw):
    r = subprocess.run(["bash", os.path.join(case, "Allrun"), *args], cwd=case, env=env(**kw),
                       capture_output=True, text=True, timeout=240)
    return r.returncode, r.stdout + r.stderr


def copy(name, dest):
    return inputcase.copy_inputs(root, name, os.path.join(work, dest))


def outputs(case):
    """A finished run's outputs, made up (only their survival is checked)."""
    write(os.path.join(case, "0.5/alpha.liquid"), "internalField uniform 1;\n")
    write(os.path.join(case, "postProcessing/liquid/timeSeries.csv"), "time_s,front_x_m\n0,0.5\n")
    write(os.path.join(case, "log.mixflowPrepare"), "[mixflowPrepare] earlier run\n")


def refused(case, args, fragments, what, absent=(), status=2, **kw):
    """Allrun ARGS exits with STATUS, its message holds FRAGMENTS (and none of ABSENT), and no file
    of the case changes."""
    before = tree(case)
    rc, msg = allrun(case, args, **kw)
    missing = [f for f in fragments if f not in msg] + [f"(has {a!r})" for a in absent if a in msg]
    after = tree(case)
    changed = sorted(k for k in set(before) | set(after) if before.get(k) != after.get(k))
    ok = check(rc == status and not missing and not changed,
               f"{what}: exit {rc}: {inputcase.last_line(msg)[:300]}")
    if not ok:
        print(f"     missing {missing}; changed {changed[:8]}\n{msg}")
    return msg


# 1. A bulk-model mixture without demDict: every input error is its own.
bulk = copy("W+P-quick", "bulk")
for f in ("system/demDict", "constant/couplingProperties"):
    os.remove(os.path.join(bulk, f))
with open(os.path.join(bulk, "system/cfdDict"), "a") as f:
    f.write("mixtureModel bulk;\n")
outputs(bulk)
SP, CFD, BP = "constant/sceneProperties", "system/cfdDict", "constant/bulkProperties"
BULK_CASES = [
    ("solid fraction 0.9", SP, r"solidFraction +0\.6056;", "solidFraction 0.9;",
     [SP, "sample.solidFraction", "0.9", "(0, 0.64]"]),
    ("lambda_p nan", BP, None, "drifts { pressure lambdaP; lambdaP nan; }\n", [BP, "drifts.lambdaP", "nan"]),
    ("lambda_p -5", BP, None, "drifts { pressure lambdaP; lambdaP -5; }\n", [BP, "drifts.lambdaP", "-5", "allowed range [-1.5"]),
    ("unknown lambdaUU", BP, None, "drifts { lambdaUU 1; }\n", [BP, "drifts.lambdaUU", "unknown entry", "lambdaU"]),
    ("tanPhi -1", BP, None, "solid { tanPhi -1; }\n", [BP, "solid.tanPhi", "-1", "[0, 5]"]),
    ("mixtureModel bulky", CFD, r"^mixtureModel bulk;", "mixtureModel bulky;",
     [CFD, "mixtureModel", "bulky", "cfdDem, bulk"]),
]
for what, rel, pattern, repl, fragments in BULK_CASES:
    path = os.path.join(bulk, rel)
    original = open(path).read() if os.path.exists(path) else None
    if pattern:
        edit(bulk, rel, pattern, repl)
    else:
        write(path, repl)
    refused(bulk, ["1"], fragments + ["nothing was run"], f"bulk model, {what}", absent=["demDict"])
    if original is None:
        os.remove(path)
    else:
        write(path, original)
# Drift fields of 329 cells: the mesh of cellSize 0.06 in the 2 x 0.6 m channel has 33 x 10 x 1.
field = ("FoamFile { version 2.0; format ascii; class volScalarField; object %s; }\n"
         "dimensions [0 0 0 0 0 0 0];\ninternalField nonuniform List<scalar> 329 (" + " 1" * 329 + " );\n"
         "boundaryField { \".*\" { type zeroGradient; } frontAndBack { type empty; } }\n")
for name in ("lambdaU", "lambdaW", "lambdaP"):
    write(os.path.join(bulk, "constant", name), field % name)
write(os.path.join(bulk, BP), "drifts { pressure lambdaP; fields on; }\n")
refused(bulk, ["1"], ["constant/lambdaU", "329 cells", "330 = 33 x 10 x 1", "allowed: 330 values",
                      "nothing was run"], "bulk model, drift fields of 329 cells for 330", absent=["demDict"])

# 2. SETTLED_DIR: settle W+P-quick once, then offer that sample to cases it does not fit.
sample = copy("W+P-quick", "sample")
r = subprocess.run([os.path.join(build_bin, "mixflowDem"), "-case", sample, "-settleOnly"],
                   capture_output=True, text=True, timeout=180)
check(r.returncode == 0, f"W+P-quick settles a sample to offer (exit {r.returncode})")
sample_dem = os.path.join(sample, "dem")
denser = copy("W+P-quick", "denser")
edit(denser, SP, r"density +2500;", "density 2600;")
outputs(denser)
refused(denser, ["1", sample_dem],
        [os.path.join(sample_dem, "settled.state"), "settled/fingerprint",
         "constant/sceneProperties entry 'particles.density': 2600 in this case, 2500 in the sample",
         "nothing was run or removed"], "SETTLED_DIR settled with another density")
no_restart = os.path.join(work, "no-restart")
shutil.copytree(sample_dem, no_restart)
os.remove(os.path.join(no_restart, "settled.restart"))
plain = copy("W+P-quick", "plain")
outputs(plain)
refused(plain, ["1", no_restart], [os.path.join(no_restart, "settled.restart"), "cannot open file",
                                   "no settled sample to reuse", "nothing was run or removed"],
        "SETTLED_DIR without settled.restart")

# 3. A copy outside the checkout, without MIXFLOW_ROOT.
away = inputcase.copy_inputs(root, "P-quick", os.path.join(work, "elsewhere", "deep", "P"))
edit(away, SP, r"diameter +0\.024;", "diameter -0.024;")
refused(away, ["1"], ["particles.diameter", "-0.024", "(0, inf)", "nothing was run"],
        "a copied case without MIXFLOW_ROOT, programs on PATH", mixflow_root=False)
refused(away, ["1"], ["cannot find mixflow's scripts/RunFunctions", "set MIXFLOW_ROOT",
                      "MIXFLOW_ROOT=/path/to/mixflow ./Allrun", "nothing was run"],
        "a copied case without MIXFLOW_ROOT or programs on PATH", mixflow_root=False, programs=False)

# 4. Warnings once, notes with the case's reason; <case>.foam. blockMesh stops each run after
# mixflowPrepare (and its log) ran.
no_mesh = standin("blockMesh", "echo 'blockMesh: stopped here' >&2\nexit 1\n")
shipped = copy("W+P-quick", "shipped")
rc, msg = allrun(shipped, ["1", sample_dem], path_first=[no_mesh])
notes = [ln for ln in msg.splitlines() if "note: " in ln and "cellSize" in ln]
check("warning" not in msg.lower() and len(notes) == 1 and "coarseCellsReason" in notes[0]
      and "the quick case keeps 5 cells" in notes[0],
      f"shipped W+P-quick: no warning, one note with the reason ({len(notes)} notes)")
check(os.path.isfile(os.path.join(shipped, "shipped.foam")), "the Allrun made shipped/shipped.foam")
bare = copy("W+P-quick", "bare")
edit(bare, CFD, r"^coarseCellsReason .*\n", "")
rc, msg = allrun(bare, ["1", sample_dem], path_first=[no_mesh])
warned = [ln for ln in msg.splitlines() if "warning" in ln and "cellSize" in ln]
check(len(warned) == 1 and "2.5 particle diameters" in warned[0],
      f"without the reason the cells' warning is given once ({len(warned)} times)")
liquid = copy("W", "W")
rc, msg = allrun(liquid, ["1"], path_first=[no_mesh])
check(os.path.isfile(os.path.join(liquid, "W.foam")), "a liquid case's Allrun makes W.foam")

# 5. Disk space.
low_df = standin("df", "echo 'Filesystem 1024-blocks Used Available Capacity Mounted on'\n"
                       "echo 'fake 100000 94880 5120 95% /'\n")
space = copy("W", "space")
outputs(space)
refused(space, ["1"], ["no space left on device", space, "5 MB free", "MIXFLOW_MIN_FREE_MB",
                       "nothing was run or removed"], "5 MB free", path_first=[low_df])


def full_disk_case(case):
    """After the run on a filled disk: the message, no half-written time directory."""
    rc, msg = allrun(case, ["1"], MIXFLOW_MIN_FREE_MB="1")
    check(rc != 0 and "no space left on device" in msg and case in msg
          and "resumeLiquidCase 1" in msg, f"a disk filled during the run: exit {rc}, "
          f"{[ln for ln in msg.splitlines() if 'space' in ln][:1]}")
    half = []
    for d in os.listdir(case):
        if re.fullmatch(r"[0-9.eE+-]+", d) and d != "0":
            for dp, _, files in os.walk(os.path.join(case, d)):
                for f in files:
                    data = open(os.path.join(dp, f), "rb").read()
                    if not data or not re.search(rb"// \*+ //\s*$", data[-200:]):
                        half.append(os.path.join(dp, f))
    check(not half, f"no half-written time directory is left ({half[:3]})")
    log = open(os.path.join(case, "log.mixflowFoam")).read()
    stop = [ln for ln in log.splitlines() if "stopped before writing" in ln]
    check(stop and case in stop[0] and "no space left on device" in stop[0]
          and "error in IOstream" not in log,
          f"the solver stops before the write that does not fit, naming the case ({stop[:1]})")
    return msg


mnt = os.path.join(work, "tmpfs")
os.makedirs(mnt)
mounted = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=4m", "tmpfs", mnt],
                         capture_output=True, text=True).returncode == 0
if mounted:
    try:
        # W in 2-D at 0.1 m cells, a write every 0.01 s: fills 4 MB after about 0.3 s of flow.
        full = inputcase.copy_inputs(root, "W", os.path.join(mnt, "W"))
        edit(full, CFD, r"^dimensions .*$", "dimensions 2;")
        edit(full, CFD, r"^cellSize .*$", "cellSize 0.1;")
        edit(full, "system/controlDict", r"^writeInterval .*$", "writeInterval 0.01;")
        msg = full_disk_case(full)
        print("     " + "\n     ".join(ln for ln in msg.splitlines() if ln.startswith("Allrun:")))
    finally:
        subprocess.run(["umount", mnt])
else:
    print("the real full disk is replaced by a stand-in solver: cannot mount a tmpfs here")
    full = copy("W", "full")
    solver = standin("mixflowFoam", "mkdir -p 0.1 0.2\n"
                     "printf 'x\\n\\n// ***** //\\n' > 0.1/U\nprintf 'FoamFile' > 0.2/U\n"
                     "echo 'error in IOstream: No space left on device' >&2\nexit 1\n",
                     blockMesh="exit 0\n", postProcess="exit 0\n")
    rc, msg = allrun(full, ["1"], path_first=[solver])
    check("no space left on device" in msg and not os.path.exists(os.path.join(full, "0.2"))
          and os.path.exists(os.path.join(full, "0.1")), "stand-in full disk: 0.2 removed, 0.1 kept")

# 6. Drift fields at the admissible bound through decomposePar on 2 ranks.
drift = copy("P-bulk", "drift")
alpha_s = 0.6056
lo = (0.01 - alpha_s) / (1 - alpha_s)  # the bound of prepare/BulkModel.cpp, as a double
check(repr(lo) == "-1.5101419878296147" and float("%.10g" % lo) < lo,
      f"the bound at alpha_s {alpha_s} is {lo!r}; written with 10 digits it falls below")
edit(drift, "system/controlDict", r"^endTime .*$", "endTime 0.002;")
edit(drift, "system/controlDict", r"^writeInterval .*$", "writeInterval 0.001;")
cells = 200 * 60  # the 4 x 1.2 m channel at 0.02 m, 2-D
# Every other cell at the bound (the clipped ones), the rest at -1.
for name, pair in (("lambdaU", (lo, -1.0)), ("lambdaW", (1.0, 0.5)), ("lambdaP", (1.0, 0.5))):
    write(os.path.join(drift, "constant", name),
          "FoamFile { version 2.0; format ascii; class volScalarField; object %s; }\n"
          "dimensions [0 0 0 0 0 0 0];\ninternalField nonuniform List<scalar> %d\n(\n%s)\n;\n"
          "boundaryField { \".*\" { type zeroGradient; } frontAndBack { type empty; } }\n"
          % (name, cells, "".join("%.17g\n" % pair[i % 2] for i in range(cells))))
with open(os.path.join(drift, BP), "a") as f:
    f.write("drifts { pressure lambdaP; fields on; }\n")
mpi = "--oversubscribe" + (" --allow-run-as-root" if os.geteuid() == 0 else "")
r = subprocess.run(["bash", "-c", '. "$1/scripts/RunFunctions" && foamEnv && '
                    'runApplication mixflowPrepare -case . -np 2 && runApplication blockMesh -case . && '
                    'decompose 2 && runOnRanks 2 mixflowBulkFoam', "sh", root],
                   cwd=drift, env=env(MIXFLOW_MPI_ARGS=""), capture_output=True, text=True, timeout=240)
values = []
for rank in (0, 1):
    text = open(os.path.join(drift, f"processor{rank}", "constant", "lambdaU")).read()
    body = text[text.index("(", text.index("internalField")) + 1:text.index(")", text.index("internalField"))]
    values += [float(v) for v in body.split()]
check(len(values) == cells and min(values) >= lo and values.count(lo) == cells // 2,
      f"the ranks' lambdaU keep the bound: {len(values)} cells, smallest {min(values)!r} >= {lo!r}")
check(r.returncode == 0 and "outside the allowed range" not in r.stdout + r.stderr,
      f"mixflowBulkFoam accepts the fields on 2 ranks (exit {r.returncode}): "
      f"{inputcase.last_line(r.stdout + r.stderr)[:200]}")

print("PASS" if inputcase.failures == 0 else f"FAIL ({inputcase.failures} failed)")
sys.exit(1 if inputcase.failures else 0)
