"""Helpers of the input tests (test_allrun_checks.py, test_case_check.py): copies of the committed
cases' inputs, one-entry edits, file trees to compare before and after, and the ok/FAIL lines."""
import os
import re
import shutil

failures = 0


def check(ok, what):
    """Prints an ok/FAIL line for WHAT; counts the failures (inputcase.failures)."""
    global failures
    print(f"{'ok  ' if ok else 'FAIL'} {what}", flush=True)
    if not ok:
        failures += 1
    return ok


def tree(case):
    """{relative path: bytes} of every file (and symlink target) below CASE."""
    out = {}
    for d, _dirs, files in os.walk(case):
        for f in files:
            p = os.path.join(d, f)
            with open(p, "rb") as fh:
                out[os.path.relpath(p, case)] = fh.read()
    return out


def copy_inputs(root, name, case):
    """cases/NAME of the checkout ROOT into CASE (made afresh): Allrun and the files of constant/
    and system/, no outputs (a run in cases/ may have left some)."""
    src = os.path.join(root, "cases", name)
    shutil.rmtree(case, ignore_errors=True)
    os.makedirs(case)
    shutil.copy2(os.path.join(src, "Allrun"), case)
    for sub in ("constant", "system"):
        os.makedirs(os.path.join(case, sub))
        for f in os.listdir(os.path.join(src, sub)):
            if os.path.isfile(os.path.join(src, sub, f)):
                shutil.copy2(os.path.join(src, sub, f), os.path.join(case, sub, f))
    return case


def edit(case, rel, pattern, repl):
    """Replaces the first match of PATTERN (multi-line) in CASE/REL; returns the original text."""
    p = os.path.join(case, rel)
    text = open(p).read()
    new = re.sub(pattern, repl, text, count=1, flags=re.M)
    assert new != text, f"{rel}: the edit {pattern!r} did not apply"
    open(p, "w").write(new)
    return text


def last_line(msg):
    lines = msg.strip().splitlines()
    return lines[-1] if lines else "no message"
