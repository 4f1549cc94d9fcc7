#!/usr/bin/env python3
"""A liquid run killed after a field write continues from it (resumeLiquidCase) as if it had not
stopped, and the failed run says how.

usage: test_liquid_resume.py ROOT BINDIR WORKDIR [RANKS]

The scene is the outflow check of run_liquid_cases.py: a 0.1 x 0.1 m water column in an open
0.3 x 0.15 m channel, 2-D, 5 mm cells, writes every 0.1 s. Run A goes to 0.4 s uninterrupted
(through a liquid case's Allrun, cases/W/Allrun). Run B is started for 1 s and its mixflowFoam is killed
(SIGKILL, a crash) once its first field write is complete; B also gets a half-written later time
directory and a row after the write in each series. Then B's endTime is set to 0.4 s and
`resumeLiquidCase RANKS` continues it. Checks:
  1. the failed run prints the resume command (resumeLiquidCase RANKS) and the write it resumes;
  2. the resume removes the half-written directory and the rows after the write, and finishes;
  3. postProcessing/liquid/timeSeries.csv has the uninterrupted run's times (1e-9 s), strictly
     increasing, and profiles.csv its write times;
  4. at 0.4 s B agrees with A: front within 1e-12 m, outlet volume and kinetic energy within
     1e-12 relative, round-off only. The restart is exact: fields written with every digit
     (writePrecision 17), the flux phi kept as written, the exact time of uniform/time; any lost
     state would grow on the breaking free surface (a restart from fields at 10 digits, its phi
     projected again, at the directory name's rounded time: outlet volume and kinetic energy
     9e-8 and 9e-7 off). Measured: equal, serial and on 2 ranks.
  5. resuming a case without a complete write is refused;
  6. run A's screen shows mixflowFoam's progress line (simulated time, wall, estimate to finish).
"""
import os
import re
import shutil
import signal
import subprocess
import sys
import time

sys.dont_write_bytecode = True  # keep the source tree free of __pycache__
from mixflow import foamcase as fc  # noqa: E402
from mixflow import outputs  # noqa: E402

root, bindir, work = (os.path.abspath(a) for a in sys.argv[1:4])
ranks = int(sys.argv[4]) if len(sys.argv) > 4 else 1
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
env = dict(os.environ, PATH=bindir + os.pathsep + os.environ.get("PATH", ""), MIXFLOW_ROOT=root,
           WM_PROJECT_DIR=os.environ.get("WM_PROJECT_DIR", "/usr/share/openfoam"))
failures = []
SCENE = """content liquid;
sample { length 0.1; height 0.1; width 0.1; }
channel { length 0.3; height 0.15; sideWalls walls; }
liquid { rheology Newtonian; density 1000; viscosity 0.001; }
"""
HDR = "FoamFile { version 2.0; format ascii; class dictionary; object %s; }\n"


def check(cond, what):
    failures.extend([] if cond else [what])
    print(("ok   " if cond else "FAIL ") + what, flush=True)


def make(name, end):
    d = os.path.join(work, name)
    for sub in ("constant", "system"):
        os.makedirs(os.path.join(d, sub))
    files = {"constant/sceneProperties": SCENE, "system/cfdDict": "dimensions 2;\ncellSize 0.005;\n",
             "system/controlDict": f"endTime {end};\nwriteInterval 0.1;\n"}
    for rel, text in files.items():
        with open(os.path.join(d, rel), "w") as f:
            f.write(HDR % os.path.basename(rel) + text)
    shutil.copy(os.path.join(root, "cases", "W", "Allrun"), d)
    return d


def shell(fn, d):
    """FN: ALLRUN, the case's ./Allrun RANKS; or (FILE, FUNCTION), FUNCTION RANKS of scripts/FILE."""
    cmd = (["bash", os.path.join(d, "Allrun"), str(ranks)] if fn == ALLRUN else
           ["bash", "-c", f'. "{root}/scripts/{fn[0]}" && {fn[1]} {ranks}'])
    return subprocess.Popen(cmd, cwd=d,
                            env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)


def run(fn, d):
    p = shell(fn, d)
    out = p.communicate()[0]
    return p.returncode, out


def series(d, name):
    return outputs.read_series(os.path.join(d, outputs.POST, "liquid", name))


def first_write_done(d):
    base = os.path.join(d, "processor0" if ranks > 1 else "")
    for n in os.listdir(base) if os.path.isdir(base) else []:
        if re.fullmatch(r"[0-9.eE+-]+", n) and float(n) > 0 and os.path.isfile(
                os.path.join(base, n, "uniform", "functionObjects", "functionObjectProperties")):
            return n
    return None


def kill_solver(case):
    """SIGKILL the mixflowFoam processes working in CASE (the ranks under mpirun too)."""
    killed = 0
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            comm = open(f"/proc/{pid}/comm").read().strip()
            cwd = os.readlink(f"/proc/{pid}/cwd")
        except OSError:
            continue
        if comm == "mixflowFoam" and os.path.realpath(cwd) == os.path.realpath(case):
            os.kill(int(pid), signal.SIGKILL)
            killed += 1
    return killed


ALLRUN = "Allrun"
a, b = make("a", 0.4), make("b", 1.0)
rc, out = run(ALLRUN, a)
if rc != 0:
    sys.exit("run A failed:\n" + out[-3000:])
check(re.search(r"^\[liquid a\] t = 0\.4000 s of 0\.4000 s \(100\.0 %\), wall \d\d:\d\d:\d\d, "
                r"to finish", out, re.M) is not None,
      "the run shows mixflowFoam's progress line (simulated time, wall, estimate to finish)")

proc = shell(ALLRUN, b)
deadline = time.time() + 300
while first_write_done(b) is None and proc.poll() is None and time.time() < deadline:
    time.sleep(0.02)
killed = kill_solver(b)
out = proc.communicate()[0]
check(killed >= 1 and proc.returncode != 0, f"run B killed after its first write ({killed} "
      f"mixflowFoam process(es), exit {proc.returncode})")
hint = re.search(r"to continue from the last write \(t = (\S+) s\).*resumeLiquidCase (\d+)",
                 out)
check(hint is not None and int(hint.group(2)) == ranks,
      "the failed run prints the resume command: " + (hint.group(0) if hint else out[-1500:]))
t_w = float(hint.group(1)) if hint else 0.1
later = os.path.join(b, "processor0" if ranks > 1 else "", "0.9")
os.makedirs(later)
open(os.path.join(later, "U"), "w").write("half written")
# The steps after the write that a later crash leaves (the kill, seconds after, may leave none).
for name in ("timeSeries.csv", "profiles.csv"):
    with open(os.path.join(b, "postProcessing", "liquid", name), "a") as f:
        f.write(f"{t_w + 0.05},999\n")

fc.set_entry(os.path.join(b, "system", "controlDict"), "endTime", 0.4)
rc, out = run(("ResumeFunctions", "resumeLiquidCase"), b)
check(rc == 0 and "resume: done" in out and f"resume: from t = {hint.group(1) if hint else ''} s"
      in out, f"resumeLiquidCase finishes from the announced write (exit {rc})")
if rc != 0:
    print(out[-3000:])
check(not os.path.exists(later), "the half-written later directory is removed")

sa, sb = series(a, "timeSeries.csv"), series(b, "timeSeries.csv")
ta, tb = [r["time_s"] for r in sa], [r["time_s"] for r in sb]
check(len(ta) == len(tb) and all(abs(x - y) < 1e-9 for x, y in zip(ta, tb))
      and all(x < y for x, y in zip(tb, tb[1:])),
      f"timeSeries.csv: the uninterrupted run's {len(ta)} times, increasing (resumed: {len(tb)})")
pa, pb = ({r["time_s"] for r in series(d, "profiles.csv")} for d in (a, b))
check(sorted(pa) == sorted(pb), f"profiles.csv: the same write times {sorted(pa)}")
ea, eb = sa[-1], sb[-1]
d_front = abs(ea["front_bed_m"] - eb["front_bed_m"])
check(d_front <= 1e-12, f"front at {ea['time_s']:g} s: |d| = {d_front:.2e} m <= 1e-12")
for k in ("volume_outlet_m3", "kinetic_energy_J"):
    if k not in ea:
        check(False, f"{k} in timeSeries.csv")
        continue
    rel = abs(ea[k] - eb[k]) / max(abs(ea[k]), 1e-300)
    check(rel <= 1e-12, f"{k}: {ea[k]:.17g} against {eb[k]:.17g} (relative {rel:.1e} <= 1e-12)")

c = make("c", 0.4)
rc, out = run(("ResumeFunctions", "resumeLiquidCase"), c)
check(rc != 0 and "no complete field write" in out, f"a case without a field write is not resumed "
      f"(exit {rc})")

print("all checks passed" if not failures else f"{len(failures)} check(s) failed")
sys.exit(1 if failures else 0)
