#!/usr/bin/env python3
"""The generated tables of docs/parameters.md equal what the declarations print
(`mixflowSchema -check`). A stale table and a missing block are refused (exit 1), and the refusal
names the command that regenerates the tables, so that the check cannot pass by accident.

usage: test_doc_tables.py MIXFLOWSCHEMA DOC WORKDIR"""
import os
import subprocess
import sys

exe, doc, work = sys.argv[1], sys.argv[2], sys.argv[3]
os.makedirs(work, exist_ok=True)
text = open(doc).read()


def check(path):
    res = subprocess.run([exe, "-check", path], capture_output=True, text=True)
    return res.returncode, res.stdout + res.stderr


failures = 0
rc, msg = check(doc)
print(msg.strip())
if rc != 0:
    failures += 1
    print(f"FAIL {doc}: generated tables are stale (exit {rc})")

# Stale: one cell of a generated row changed; missing: a block's markers removed.
edits = {
    "stale table": text.replace("| `particles.diameter` | 0.024 |", "| `particles.diameter` | 0.025 |", 1),
    "missing block": text.replace("<!-- BEGIN generated: mixflowProperties -->", "", 1),
}
for name, new in edits.items():
    assert new != text, f"{name}: the edit did not apply"
    path = os.path.join(work, name.replace(" ", "_") + ".md")
    open(path, "w").write(new)
    rc, msg = check(path)
    expected = "-update" if name == "stale table" else "mixflowProperties"
    ok = rc == 1 and expected in msg
    print(f"{'ok  ' if ok else 'FAIL'} {name}: exit {rc}; {msg.strip()}")
    failures += not ok
print(f"{3 - failures} passed, {failures} failed")
sys.exit(1 if failures else 0)
