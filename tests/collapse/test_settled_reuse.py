#!/usr/bin/env python3
"""A settled mixture sample is reused only where settling again would make the same sample.

usage: test_settled_reuse.py MIXFLOWDEM MIXFLOWPREPARE CASE WORKDIR

CASE is a mixture case (cases/W+P-quick, 813 grains). Checks, each exact:
  1. mixflowDem -settleOnly records its inputs (dem/settled.inputs) and their FNV-1a 64 hash as
     settled.state's fingerprint (recomputed here from the file);
  2. a copy whose liquid and coupling differ (viscosity, exchangeEvery) reuses it: exit 0, the
     restart file byte for byte, the same fingerprint, reusedFrom naming the source; mixflowPrepare
     accepts it;
  3. a copy with another DEM stiffness is refused (exit 2), naming the source's settled.state, the
     entry settled/fingerprint and the first differing input line (the Young's modulus);
  4. editing the DEM stiffness after the reuse makes mixflowPrepare refuse the sample (exit 2);
  5. a sample without a fingerprint (settled before they were recorded) is refused (exit 2);
  6. settling on 2 ranks gives the same fingerprint (the rank count is not an input).
"""
import os
import re
import shutil
import subprocess
import sys

sys.dont_write_bytecode = True
from mixflow import outputs  # noqa: E402

dem, prepare, case, work = sys.argv[1:5]
work = os.path.abspath(work)
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
failures = []


def check(cond, what):
    failures.extend([] if cond else [what])
    print(("ok   " if cond else "FAIL ") + what, flush=True)


def copy(name, edits=()):
    """CASE's inputs into WORK/name, with (file, regex, replacement) edits."""
    d = os.path.join(work, name)
    outputs.copy_inputs(case, d)
    for rel, pattern, repl in edits:
        path = os.path.join(d, rel)
        text, n = re.subn(pattern, repl, open(path).read(), count=1, flags=re.M)
        assert n == 1, (rel, pattern)
        open(path, "w").write(text)
    return d


def run(cmd):
    env = dict(os.environ, WM_PROJECT_DIR=os.environ.get("WM_PROJECT_DIR", "/usr/share/openfoam"))
    r = subprocess.run(cmd, capture_output=True, text=True, env=env)
    return r.returncode, r.stdout + r.stderr


def fingerprint(state):
    m = re.search(r'fingerprint\s+"([0-9a-f]{16})"', open(state).read())
    return m.group(1) if m else None


def fnv1a64(data):
    h = 14695981039346656037
    for b in data:
        h = ((h ^ b) * 1099511628211) % 2**64
    return "%016x" % h


stiffer = ("system/demDict", r"^(youngModulusFactor\s+)[^;]+;", r"\g<1>2e-3;")

# 1. Settle once, serially.
a = copy("a")
rc, out = run([dem, "-case", a, "-settleOnly"])
check(rc == 0, f"settling the sample (exit {rc})")
if rc != 0:
    sys.exit(out[-2000:])
fa = fingerprint(os.path.join(a, "dem", "settled.state"))
inputs = open(os.path.join(a, "dem", "settled.inputs"), "rb").read()
check(fa is not None and fa == fnv1a64(inputs),
      f"settled.state's fingerprint {fa} is the FNV-1a 64 hash of dem/settled.inputs")
check(b"youngsModulus" in inputs and b"dem/initial.data: 813 particles" in inputs,
      "the inputs hold the fill and the contact law")

# 2. Another liquid and exchange interval, same grains: reused.
b = copy("b", [("constant/sceneProperties", r"^(\s*viscosity\s+)0\.001;", r"\g<1>0.01;"),
               ("constant/couplingProperties", r"^(exchangeEvery\s+)\d+;", r"\g<1>10;")])
rc, out = run([dem, "-case", b, "-settleOnly", "-reuse", os.path.join(a, "dem")])
check(rc == 0 and "settled sample reused" in out, f"another liquid and interval reuse it (exit {rc})")
same = open(os.path.join(a, "dem", "settled.restart"), "rb").read() == \
    open(os.path.join(b, "dem", "settled.restart"), "rb").read()
state_b = os.path.join(b, "dem", "settled.state")
check(same and fingerprint(state_b) == fa, "the restart file byte for byte, the same fingerprint")
check(f'reusedFrom "{os.path.join(a, "dem")}"' in open(state_b).read(), "reusedFrom names the source")
rc, out = run([prepare, "-case", b])
check(rc == 0, f"mixflowPrepare accepts the reused sample (exit {rc})")

# 3. Another stiffness: refused, with the reason.
c = copy("c", [stiffer])
rc, out = run([dem, "-case", c, "-settleOnly", "-reuse", os.path.join(a, "dem")])
check(rc == 2 and os.path.join(a, "dem", "settled.state") in out and "settled/fingerprint" in out
      and "youngsModulus" in out, f"another stiffness is refused, naming file, entry, line (exit {rc})")
check(not os.path.exists(os.path.join(c, "dem", "settled.state")), "nothing is copied then")

# 4. DEM edited after the reuse: mixflowPrepare refuses the sample.
text = open(os.path.join(b, "system", "demDict")).read()
open(os.path.join(b, "system", "demDict"), "w").write(
    re.sub(r"^(youngModulusFactor\s+)[^;]+;", r"\g<1>2e-3;", text, count=1, flags=re.M))
rc, out = run([prepare, "-case", b])
check(rc == 2 and "settled/fingerprint" in out and "youngsModulus" in out,
      f"mixflowPrepare refuses a sample settled with other DEM inputs (exit {rc})")

# 5. No fingerprint: refused.
old = os.path.join(work, "old")
os.makedirs(old)
shutil.copy(os.path.join(a, "dem", "settled.restart"), old)
with open(os.path.join(old, "settled.state"), "w") as f:
    f.write(re.sub(r"\s*fingerprint[^;]*;", "", open(os.path.join(a, "dem", "settled.state")).read()))
rc, out = run([dem, "-case", copy("d"), "-settleOnly", "-reuse", old])
check(rc == 2 and "settled/fingerprint' is missing" in out, f"a sample without fingerprint is refused (exit {rc})")

# 6. Two ranks settle to the same fingerprint.
e = copy("e")
mpi = ["mpirun", "--oversubscribe", "-np", "2"] + (["--allow-run-as-root"] if os.geteuid() == 0 else [])
rc, out = run(mpi + [dem, "-case", e, "-settleOnly", "-parallel"])
check(rc == 0 and fingerprint(os.path.join(e, "dem", "settled.state")) == fa,
      f"2 ranks: the same fingerprint (exit {rc})")

print("all checks passed" if not failures else f"{len(failures)} check(s) failed")
sys.exit(1 if failures else 0)
