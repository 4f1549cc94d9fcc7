#!/usr/bin/env python3
"""A coupled mixture run killed with SIGKILL after a field write and resumed (resumeMixtureCase,
mixflowCoupled -resume) is the uninterrupted run.

usage: test_coupled_resume.py ROOT BINDIR WORKDIR [RANKS]

The scene is the quick HB&P (cases/W+P-quick with case HB+P's liquid). Run A goes to 0.15 s; run B
(endTime 0.15 s, A's settled sample) is killed with SIGKILL (every process of its session: Allrun, the solver,
mpirun and its ranks) as soon as dem/coupled.resume.state records its first field write, at
0.05 s; what a kill during a later write leaves is added (a half-written later time directory, a
row after the write in each time series); then it is resumed. Checks:
  1. the resume removes the later time directory and the later rows, and finishes;
  2. liquid, granular and exchange series: the same times as A (1e-8 s), strictly increasing, no
     duplicate; the same field writes as A, the end time's included (cfd/vofSolver/RunTime.H);
  3. the resume restores the whole state: the first 10 exchanges after the resumed write equal
     A's within 1e-12 relative in every column of postProcessing/coupling/exchange.csv but the
     wall time (`seconds`). A round-off change is the only admissible difference, and it is
     already at that level: A with the liquid's density x (1 + 1e-12) from t = 0 differs from A
     by 1e-12 to 4e-12 in the forces of its first exchanges and by 1e-7 to 1e-5 at 0.05-0.06 s,
     and its actionReaction column, a cancellation residue of 1e-16, differs by 0.4 from the
     first exchange on: every column within 1e-12 means the same state, bit for bit. A state lost
     at the resume shows at once (without the old-time flux kept from the start, 0.90 relative in
     the drag's x total at the second exchange). Measured serially and on 2 ranks: equal bit for
     bit;
     Serially also with the held drag (dragIntegration held, runs to 0.065 s) on the plain
     void-fraction split (dividedCoeffs smoothing 0): measured equal. With the case's face
     smoothing the held drag's resumed run parts from A at round-off (1e-16 in the mean
     position) from the third exchange after the resume, which this check catches: not yet
     explained, and the mixture cases use the implicit drag, which resumes bit for bit;
     Serially also with a lifted gate (10 m/s, to 0.065 s, the grains' plate parked by the
     kill): the plates placed again at h(t), within round-off (1e-10 but the residues; below);
  4. at 0.15 s the granular and liquid fronts and the grains' kinetic energy are A's within the
     largest difference a round-off change (liquid density x (1 + 1e-12)) makes over the HB&P
     run (results/reproducibility/summary.json, HB+P "perturbed": 0.083 m, 0.011 m, 0.035 J):
     beyond the first exchanges only chaos may part the runs. Measured: equal;
  5. resuming a case that wrote no field is refused, naming dem/coupled.resume.state; resuming on
     another rank count is refused before anything is removed; the state records its restart's
     cksum and size, and a truncated restart is refused naming the previous resume point.
  6. a checkpoint of the stopped run (mixflow scene-checkpoint, mixflow.checkpoint), restored
     into another directory, resumes there as the run itself does: its first 10 exchanges after
     the write equal A's within 1e-12 relative.
"""
import csv
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import time

sys.dont_write_bytecode = True
from mixflow import foamdict  # noqa: E402
from mixflow import outputs  # noqa: E402
from mixflow.commands.reproducibility import QUANTITIES  # noqa: E402

root, bindir, work = (os.path.abspath(a) for a in sys.argv[1:4])
ranks = sys.argv[4] if len(sys.argv) > 4 else "1"  # every run and the resume on RANKS ranks
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
env = dict(os.environ, PATH=bindir + os.pathsep + os.environ.get("PATH", ""), MIXFLOW_ROOT=root,
           WM_PROJECT_DIR=os.environ.get("WM_PROJECT_DIR", "/usr/share/openfoam"))
failures = []


def check(cond, what):
    failures.extend([] if cond else [what])
    print(("ok   " if cond else "FAIL ") + what, flush=True)


def make(name, end):
    d = os.path.join(work, name)
    # Inputs only: scripts/run.sh runs this case in place, leaving its outputs (and resume state).
    outputs.copy_inputs(os.path.join(root, "cases", "W+P-quick"), d)
    sp = os.path.join(d, "constant", "sceneProperties")
    text, hb = open(sp).read(), open(os.path.join(root, "cases", "HB+P", "constant",
                                                   "sceneProperties")).read()
    text = text[:text.index("liquid   //")] + hb[hb.index("liquid   //"):]
    open(sp, "w").write(text)
    set_end(d, end)
    return d


def set_end(d, end):
    path = os.path.join(d, "system", "controlDict")
    text = re.sub(r"^endTime\s+[^;]+;", f"endTime {end};", open(path).read(), flags=re.M)
    open(path, "w").write(text)


def run(cmd, cwd):
    r = subprocess.run(cmd, cwd=cwd, env=env, capture_output=True, text=True)
    return r.returncode, r.stdout + r.stderr


def resume(d):
    return run(["bash", "-c", f'. "{root}/scripts/ResumeFunctions" && resumeMixtureCase {ranks}'], d)


def series(d, rel):
    with open(os.path.join(d, rel)) as f:
        rows = list(csv.DictReader(ln for ln in f if not ln.startswith("#")))
    return rows


def col(rows, name):
    return [float(r[name]) for r in rows]


def state_time(d):
    """The time of the last field write dem/coupled.resume.state records (None: no write yet)."""
    try:
        m = re.search(r"^time\s+([^;]+);", open(os.path.join(d, "dem", "coupled.resume.state")).read(),
                      re.M)
        return float(m.group(1)) if m else None
    except OSError:
        return None


def kill_session(sid):
    """SIGKILL to every process of session SID at once. Open MPI gives each rank a process group
    of its own, so killing Allrun's group leaves the ranks running until they notice mpirun is
    gone (long enough to write another time); a machine that dies takes them all."""
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            with open(f"/proc/{pid}/stat") as f:
                fields = f.read().rsplit(")", 1)[1].split()
            if int(fields[3]) == sid:  # stat fields after the name: state ppid pgrp session
                os.kill(int(pid), signal.SIGKILL)
        except (OSError, ValueError, IndexError):
            pass


def run_killed(d, settled, after):
    """Allrun in its own session, killed with SIGKILL (every process of the session: Allrun,
    mpirun, the ranks) once its state records a field write at `after` s or later. Returns the
    exit status and the log."""
    log = open(os.path.join(d, "log.Allrun"), "w")
    p = subprocess.Popen(["./Allrun", ranks, settled], cwd=d, env=env, stdout=log,
                         stderr=subprocess.STDOUT, start_new_session=True)
    while p.poll() is None:
        t = state_time(d)
        if t is not None and t >= after - 1e-3:
            kill_session(p.pid)
            break
        time.sleep(0.02)
    rc = p.wait()
    log.close()
    return rc, open(os.path.join(d, "log.Allrun")).read()


def alive_in(d):
    """Processes still running in case directory d (the killed run's)."""
    pids = []
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            if os.path.realpath(f"/proc/{pid}/cwd").startswith(os.path.realpath(d) + os.sep):
                pids.append(int(pid))
        except OSError:
            pass
    return pids


a, b = make("a", 0.15), make("b", 0.15)
rc, out = run(["./Allrun", ranks], a)
if rc != 0:
    sys.exit("run A failed:\n" + out[-3000:])
rc, out = run_killed(b, os.path.join(a, "dem"), 0.05)
time.sleep(1)
check(rc == -signal.SIGKILL and not alive_in(b),
      f"run B killed with SIGKILL after its first field write (exit {rc}; left running: "
      f"{alive_in(b)})")
t_w = state_time(b)
check(t_w is not None and abs(t_w - 0.05) < 1e-3,
      f"B's resume state is its first field write ({t_w} s)")
if t_w is None:
    sys.exit("run B wrote no resume state:\n" + out[-3000:])
# A resume point is a complete write: the function objects' state (the liquid series' volumes)
# is in it when the state names it, or the resumed liquid series would start again.
name = re.search(r'^timeName\s+"?([^";]+)"?;',
                 open(os.path.join(b, "dem", "coupled.resume.state")).read(), re.M).group(1)
props = os.path.join(b, "" if ranks == "1" else "processor0", name, "uniform", "functionObjects",
                     "functionObjectProperties")
check(os.path.exists(props) and "initialVolume" in open(props).read(),
      f"the resume point {name} holds the liquid series' state ({os.path.relpath(props, b)})")

# What a kill during a later write leaves (a decomposed run writes into processor*/).
later = os.path.join(b, "0.0700000" if ranks == "1" else "processor0/0.0700000")
os.makedirs(later, exist_ok=True)
open(os.path.join(later, "U"), "w").write("half written")
for rel in ("postProcessing/liquid/timeSeries.csv", "postProcessing/dem/timeSeries.csv",
            "postProcessing/coupling/exchange.csv"):
    with open(os.path.join(b, rel), "a") as f:
        f.write("0.0600000,999\n")
# Another rank count is refused before anything is removed (the later directory stays).
other = "2" if ranks == "1" else "1"
rc, out = run(["bash", "-c", f'. "{root}/scripts/ResumeFunctions" && resumeMixtureCase {other}'], b)
check(rc == 2 and f"written on {ranks} rank(s), not {other}" in out and os.path.exists(later),
      f"a resume on {other} rank(s) of a run written on {ranks} is refused, nothing changed "
      f"(exit {rc})")
# 6. The same run through a checkpoint (mixflow scene-checkpoint: the write, the restart and the
# outputs so far, thinned) restored into another directory, where the resume goes on from it.
ckpt = os.path.join(work, "checkpoints")
rc_c, out_c = run([sys.executable, "-m", "mixflow", "scene-checkpoint", b, "--out", ckpt], work)
rc_r, out_r = run([sys.executable, "-m", "mixflow", "scene-checkpoint", "--restore",
                   os.path.join(ckpt, "b"), "--work", os.path.join(work, "restored")], work)
c = os.path.join(work, "restored", "b")
rc_cr, out_cr = resume(c) if rc_c == rc_r == 0 else (1, out_c + out_r)
check(rc_cr == 0 and "resume: done" in out_cr, f"a checkpoint of B, restored, resumes and finishes "
      f"(exits {rc_c}, {rc_r}, {rc_cr})")
rc, out = resume(b)
check(rc == 0 and "resume: done" in out, f"resumeMixtureCase finishes (exit {rc})")
check("resumed with the drag state of the particles' restart" in
      open(os.path.join(b, "log.mixflowCoupled")).read(),
      "the resumed run kept the drag state of the particles' restart")
if rc != 0:
    print(out[-3000:])
check(not os.path.exists(later), "the later time directory is removed")

for rel in ("postProcessing/liquid/timeSeries.csv", "postProcessing/coupling/exchange.csv"):
    ta, tb = col(series(a, rel), "time_s" if "liquid" in rel else "time"), \
        col(series(b, rel), "time_s" if "liquid" in rel else "time")
    same = len(ta) == len(tb) and all(abs(x - y) < 1e-8 for x, y in zip(ta, tb))
    check(same and all(x < y for x, y in zip(tb, tb[1:])),
          f"{rel}: the uninterrupted run's {len(ta)} times, increasing (resumed: {len(tb)})")
ga, gb = series(a, "postProcessing/dem/timeSeries.csv"), series(b, "postProcessing/dem/timeSeries.csv")
ta, tb = col(ga, "time_s"), col(gb, "time_s")
check(len(ta) == len(tb) and all(abs(x - y) < 1e-8 for x, y in zip(ta, tb))
      and all(x < y for x, y in zip(tb, tb[1:])),
      f"granular series: the uninterrupted run's {len(ta)} times, increasing (resumed: {len(tb)})")



def field_writes(d):
    """The time directories of a run (processor0's on several ranks), as times."""
    base = d if ranks == "1" else os.path.join(d, "processor0")
    return sorted(float(n) for n in os.listdir(base) if re.fullmatch(r"[0-9.eE+-]+", n))


wa, wb = field_writes(a), field_writes(b)
check(len(wa) == len(wb) and all(abs(x - y) < 1e-8 for x, y in zip(wa, wb)),
      f"field writes: the uninterrupted run's {wa} (resumed: {wb}), the end time's included")

def first_exchanges(a, b, t_w, n=10, ignore=()):
    """The largest relative difference between B's first n exchanges after t_w and A's at the
    same times, over every column of exchange.csv but the wall time and IGNORE, and where it is."""
    ea, eb = series(a, "postProcessing/coupling/exchange.csv"), \
        series(b, "postProcessing/coupling/exchange.csv")
    resumed = [r for r in eb if float(r["time"]) > t_w + 1e-9][:n]
    worst, where = (0.0, "none") if len(resumed) == n else (float("inf"), f"{len(resumed)} rows")
    for r in resumed:
        ra = next((x for x in ea if abs(float(x["time"]) - float(r["time"])) < 1e-9), None)
        if ra is None:
            return float("inf"), f"no row of A at t = {r['time']}"
        for k in r:
            if k == "seconds" or k in ignore:
                continue
            x, y = float(ra[k]), float(r[k])
            rel = abs(x - y) / max(abs(x), abs(y)) if x != y else 0.0
            if rel > worst:
                worst, where = rel, f"{k} at t = {r['time']} ({ra[k]} against {r[k]})"
    return worst, where


# 3. The first 10 exchanges after the write, column by column (`seconds` is wall time).
worst, where = first_exchanges(a, b, t_w)
check(worst <= 1e-12, f"the first 10 exchanges after the resume equal A's in every column: "
      f"largest relative difference {worst:.3e} <= 1e-12 ({where})")

if rc_cr == 0:
    worst, where = first_exchanges(a, c, t_w)
    check(worst <= 1e-12, f"checkpoint: the first 10 exchanges after its write equal A's in every "
          f"column: largest relative difference {worst:.3e} <= 1e-12 ({where})")

# 4. The end state within the spread a round-off change makes (results/reproducibility).
spread = json.load(open(os.path.join(root, "results", "reproducibility", "summary.json")))
spread = spread["scenes"]["HB+P"]["perturbed"]
ends = {"dem": (ga[-1], gb[-1]), "liquid": (series(a, "postProcessing/liquid/timeSeries.csv")[-1],
                                            series(b, "postProcessing/liquid/timeSeries.csv")[-1])}
for name, (kind, column) in QUANTITIES.items():
    ra, rb = ends[kind]
    diff, bound = abs(float(ra[column]) - float(rb[column])), spread[name]["max_abs"]
    check(diff <= bound, f"{name} at the end: |A - B| = {diff:.3e} <= {bound:.3e} (the round-off "
          "spread of results/reproducibility)")

# 3b. The same with the held drag (serially: its forces are the restart's mixflowHeldForce).
if ranks == "1":
    ah, bh = make("a_held", 0.065), make("b_held", 0.065)
    for d in (ah, bh):
        foamdict.edit_file(os.path.join(d, "constant", "couplingProperties"),
                           {"dragIntegration": "held", "dividedCoeffs": {"smoothing": "0"}})
    rc, out = run(["./Allrun", ranks, os.path.join(a, "dem")], ah)
    rc_b, _ = run_killed(bh, os.path.join(a, "dem"), 0.05)
    t_h = state_time(bh)
    rc_r, _ = resume(bh) if rc == 0 and t_h is not None else (1, "")
    worst, where = first_exchanges(ah, bh, t_h or 0.0) if rc_r == 0 else (float("inf"), "")
    check(rc_b == -signal.SIGKILL and rc_r == 0 and worst <= 1e-12,
          f"held drag, killed at {t_h} s and resumed (exits {rc}, {rc_b}, {rc_r}): the first 10 "
          f"exchanges equal A's, largest relative difference {worst:.3e} <= 1e-12 ({where})")

# 3c. With a lifted gate (sceneProperties gate, 10 m/s: the grains' plate parked above the 0.3 m
# column from 0.035 s on): the DEM script places the plate at h(t) of the restart's step, the
# liquid's fvOption at the resumed time. The uninterrupted run's plate got there by adding one
# step's lift at a time and parked up to a step's lift higher, so the two differ at round-off
# (mesh binning, summation order): every column within 1e-10 but the cancellation residues
# (actionReaction, volumeError, outsideVolume), which round-off alone moves by O(1), as above.
# (A resume while grains touch the moving plate parts at once: LIGGGHTS' force set-up sees the
# new mesh at rest, fix move/mesh giving it its velocity only at the first step; dem/README.md.)
if ranks == "1":
    ag, bg = make("a_gate", 0.065), make("b_gate", 0.065)
    for d in (ag, bg):
        with open(os.path.join(d, "constant", "sceneProperties"), "a") as f:
            f.write("gate { removal lifted; speed 10; }\n")
    rc, out = run(["./Allrun", ranks, os.path.join(a, "dem")], ag)
    rc_b, _ = run_killed(bg, os.path.join(a, "dem"), 0.05)
    t_g = state_time(bg)
    rc_r, _ = resume(bg) if rc == 0 and t_g is not None else (1, "")
    residues = ("actionReaction", "volumeError", "outsideVolume")
    worst, where = (first_exchanges(ag, bg, t_g or 0.0, ignore=residues) if rc_r == 0
                    else (float("inf"), ""))
    check(rc_b == -signal.SIGKILL and rc_r == 0 and worst <= 1e-10,
          f"lifted gate, killed at {t_g} s and resumed (exits {rc}, {rc_b}, {rc_r}): the first 10 "
          f"exchanges within round-off of A's, largest relative difference {worst:.3e} <= 1e-10 "
          f"but the residues ({where})")

# The restart as recorded: `cksum` prints the state's restartCrc and restartBytes.
st = open(os.path.join(a, "dem", "coupled.resume.state")).read()
restart = re.search(r'^restartFile\s+"([^"]+)"', st, re.M).group(1)
crc, nbytes = (re.search(rf"^{k}\s+(\d+);", st, re.M).group(1) for k in ("restartCrc", "restartBytes"))
got = subprocess.run(["cksum"], stdin=open(os.path.join(a, restart), "rb"), capture_output=True,
                     text=True).stdout.split()
check(got == [crc, nbytes], f"the state records the restart's cksum and size ({crc} {nbytes}; "
      f"cksum prints {' '.join(got)})")
# A damaged (truncated) restart is refused before anything is removed, naming the previous state.
damaged = os.path.join(work, "a_damaged")
shutil.copytree(a, damaged, symlinks=True)
with open(os.path.join(damaged, restart), "r+b") as f:
    f.truncate(int(nbytes) // 2)
n_before = len(os.listdir(damaged))
rc, out = resume(damaged)
check(rc == 2 and "is damaged" in out and "coupled.resume.state.previous" in out
      and len(os.listdir(damaged)) == n_before,
      f"a truncated restart is refused, the previous resume point named, nothing removed (exit {rc})")

c = make("c", 0.05)
rc, out = resume(c)
check(rc != 0 and "dem/coupled.resume.state: cannot open file" in out,
      f"a case without a field write is not resumed (exit {rc})")

print("all checks passed" if not failures else f"{len(failures)} check(s) failed")
sys.exit(1 if failures else 0)
