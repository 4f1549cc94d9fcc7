#!/usr/bin/env python3
"""An interrupted settle continues from its checkpoint (demDict settle.checkpointInterval,
dem/SettleCheckpoint.h) and gives the sample an uninterrupted settle gives.

usage: test_settle_checkpoint.py ROOT BINDIR WORKDIR

The small column of tests/collapse/column with checkpoints every 0.1 s of settling (it settles in
about 0.7 s):
  1. A settles uninterrupted (`mixflowDem -settleOnly`): no checkpoint is left once settled;
  2. B is killed (SIGKILL) after its checkpoint at 0.3 s, then run again: it says it continues
     from the checkpoint, and its settled sample (settled.state, settled.restart) is A's byte for
     byte (one rank: LIGGGHTS restarts reproduce the trajectory exactly);
  3. a checkpoint of other settling inputs (settle.friction changed) is reported and not used;
  4. a dry case's Allrun (cases/P/Allrun) keeps a checkpoint when it moves the previous outputs
     aside, continues the settle from it and finishes the collapse;
  5. the same for a stiffened settle (settle.stiffenFrom 1e-2 on tests/dem/stiffen_column, 241
     grains at 70/700 GPa): killed after its soft checkpoint at 0.3 s and run again, it gives the
     uninterrupted sample byte for byte;
  6. the same for the packing control (settle.packingControl friction, first friction 0.7):
     killed in its second settle, it continues there with the first settle's result (the
     checkpoint's `trials`) and gives the uninterrupted sample byte for byte.
Parts 1-5 settle once (packingControl off).
"""
import filecmp
import os
import re
import shutil
import signal
import subprocess
import sys
import time

root, bindir, work = (os.path.abspath(a) for a in sys.argv[1:4])
exe = os.path.join(bindir, "mixflowDem")
env = dict(os.environ, PATH=bindir + os.pathsep + os.environ.get("PATH", ""), MIXFLOW_ROOT=root)
failures = []


def check(ok, what):
    failures.extend([] if ok else [what])
    print(("ok   " if ok else "FAIL ") + what, flush=True)


def make(name, friction=None, source=("tests", "collapse", "column"), extra="", control="off"):
    d = os.path.join(work, name)
    shutil.rmtree(d, ignore_errors=True)
    shutil.copytree(os.path.join(root, *source), d)
    p = os.path.join(d, "system", "demDict")
    extra += f" friction {friction};" if friction is not None else ""
    extra += f" packingControl {control};"
    text = re.sub(r"settle\s*\{[^}]*\}", "settle { maxTime 2; checkpointInterval 0.1;" + extra + " }",
                  open(p).read())
    open(p, "w").write(text)
    return d


def settle(d):
    r = subprocess.run([exe, "-case", d, "-settleOnly"], capture_output=True, text=True, env=env)
    if r.returncode != 0:
        sys.exit(f"mixflowDem -settleOnly failed on {d}:\n{r.stdout[-2000:]}{r.stderr[-2000:]}")
    return r.stdout


def checkpoint_time(d):
    p = os.path.join(d, "dem", "settle.checkpoint.state")
    if not os.path.isfile(p):
        return None
    m = re.search(r"^time\s+([^;]+);", open(p).read(), re.M)
    return float(m.group(1)) if m else None


def finished_trials(d):
    """Settles of the packing control the checkpoint lists as finished."""
    p = os.path.join(d, "dem", "settle.checkpoint.state")
    m = re.search(r"^trials\s+\(([^)]*)\)", open(p).read(), re.M) if os.path.isfile(p) else None
    return len(m.group(1).split()) // 2 if m else 0


def kill_after_checkpoint(d, t_min, trials=0):
    """Starts the settle and kills it once its checkpoint is at t >= t_min (in the settle after
    `trials` finished ones of the packing control)."""
    p = subprocess.Popen([exe, "-case", d, "-settleOnly"], stdout=subprocess.DEVNULL,
                         stderr=subprocess.DEVNULL, env=env)
    deadline = time.time() + 600
    while time.time() < deadline and p.poll() is None:
        t = checkpoint_time(d)
        if t is not None and t >= t_min and finished_trials(d) >= trials:
            p.send_signal(signal.SIGKILL)
            p.wait()
            return t
        time.sleep(0.05)
    p.kill()
    sys.exit(f"{d}: no checkpoint at t >= {t_min} s before the settle ended")


os.makedirs(work, exist_ok=True)
a = make("a")
settle(a)
check(not any(n.startswith("settle.checkpoint") for n in os.listdir(os.path.join(a, "dem"))),
      "a settled sample leaves no checkpoint")

b = make("b")
t = kill_after_checkpoint(b, 0.3)
check(not os.path.exists(os.path.join(b, "dem", "settled.state")), f"B killed at its "
      f"checkpoint t = {t:.4f} s, before it settled")
out = settle(b)
check("settling continues from its checkpoint" in out, "B's second run continues from the checkpoint")
for f in ("settled.state", "settled.restart"):
    check(filecmp.cmp(os.path.join(a, "dem", f), os.path.join(b, "dem", f), shallow=False),
          f"B's dem/{f} is A's byte for byte")

c = make("c", friction=0.2)
os.makedirs(os.path.join(c, "dem"), exist_ok=True)
t = kill_after_checkpoint(make("b2"), 0.2)  # a checkpoint of the inputs with friction 0.1
for n in os.listdir(os.path.join(work, "b2", "dem")):
    if n.startswith("settle.checkpoint"):
        shutil.copy(os.path.join(work, "b2", "dem", n), os.path.join(c, "dem", n))
out = settle(c)
check("a checkpoint of other settling inputs" in out and "settling continues" not in out,
      "a checkpoint of other settling inputs is reported and not used")

d = os.path.join(work, "d")
shutil.rmtree(d, ignore_errors=True)
shutil.copytree(os.path.join(work, "b2"), d)  # the killed B2: its checkpoint in dem/
shutil.copy(os.path.join(root, "cases", "P", "Allrun"), d)
r = subprocess.run(["bash", os.path.join(d, "Allrun"), "1"], cwd=d, capture_output=True, text=True,
                   env=env)
log = open(os.path.join(d, "log.mixflowDem")).read() if os.path.isfile(
    os.path.join(d, "log.mixflowDem")) else ""
check(r.returncode == 0 and "settling continues from its checkpoint" in log and
      os.path.isfile(os.path.join(d, "postProcessing", "dem", "summary.json")),
      f"the dry Allrun keeps the checkpoint, continues the settle and finishes (exit {r.returncode})")
if r.returncode != 0:
    print(r.stdout[-2000:], r.stderr[-2000:])

# 5. A stiffened settle (settle.stiffenFrom, as the paper tier) checkpoints its soft phase: killed
#    there and run again, it continues and stiffens to A's sample byte for byte.
sa = make("stiffened_a", 0.1, ("tests", "dem", "stiffen_column"), " stiffenFrom 1e-2;")
settle(sa)
sb = make("stiffened_b", 0.1, ("tests", "dem", "stiffen_column"), " stiffenFrom 1e-2;")
kill_after_checkpoint(sb, 0.3)
out = settle(sb)
check("settling continues from its checkpoint" in out and "stiffened to E = 7e+10 Pa" in out,
      "a stiffened settle continues from its soft checkpoint and stiffens")
for f in ("settled.state", "settled.restart", "settled.inputs"):
    check(filecmp.cmp(os.path.join(sa, "dem", f), os.path.join(sb, "dem", f), shallow=False),
          f"the continued stiffened settle's dem/{f} is the uninterrupted one's byte for byte")

# 6. The packing control (settle.packingControl friction) checkpoints its search: killed in its
#    second settle and run again, it goes on with the first settle's result and ends with A's
#    sample byte for byte. From friction 0.7 the column needs more than one settle.
pa = make("control_a", 0.7, control="friction")
out_a = settle(pa)
n_a = int(re.search(r"settles (\d+);", open(os.path.join(pa, "dem", "settled.state")).read()).group(1))
check(n_a >= 2, f"the controlled settle from friction 0.7 takes {n_a} settles (at least 2)")
pb = make("control_b", 0.7, control="friction")
kill_after_checkpoint(pb, 0.2, trials=1)
out = settle(pb)
check("settling continues from its checkpoint" in out and "settle 1 at" not in out,
      "the controlled settle continues in its second settle, without settling the first again")
for f in ("settled.state", "settled.restart", "settled.inputs"):
    check(filecmp.cmp(os.path.join(pa, "dem", f), os.path.join(pb, "dem", f), shallow=False),
          f"the continued controlled settle's dem/{f} is the uninterrupted one's byte for byte")

print("all checks passed" if not failures else f"{len(failures)} check(s) failed")
sys.exit(1 if failures else 0)
