#!/usr/bin/env python3
"""mixflowExtract on a full disk: a failed HDF5 write or flush
stops it with exit status 1 and a message naming the file and the system's reason, the previous file
intact and no temporary file left; before the fix it then segfaulted in HDF5's exit handler (exit
139) after a failed flush.

Two ways to fill the disk:
  - always: a file size limit (RLIMIT_FSIZE, with SIGXFSZ ignored, so writes past it fail with EFBIG
    like on a full disk), set for the extractor's process only;
  - when the test may mount (root): a real tmpfs of about 1.5 times the output file, holding the
    previous file, unmounted at the end (skipped, and said so, when mounting is not allowed).
Also: an XDMF that cannot be written after the HDF5 file was updated exits 1 saying so, and a re-run
rewrites it.

usage: test_extract_full_disk.py MIXFLOWEXTRACT WORKDIR"""
import hashlib
import os
import resource
import shutil
import signal
import subprocess
import sys
import tempfile

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
from mixflow import synthcase as sc  # noqa: E402

exe, work = sys.argv[1], sys.argv[2]
os.makedirs(work, exist_ok=True)
failures = []
check = sc.checker(failures)


def run(case, *extra, fsize=None):
    def limit():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (fsize, fsize))
    r = subprocess.run([exe, "-case", case, *extra], capture_output=True, text=True,
                       preexec_fn=limit if fsize else None)
    return r.returncode, r.stdout + r.stderr


def digest(path):
    return hashlib.sha256(open(path, "rb").read()).hexdigest()


times = [round(0.01 * k, 10) for k in range(10)]
case = os.path.join(work, "case")
sc.drift_case(case, times, times)
rc, out = run(case)
h5 = os.path.join(case, "postProcessing/mixture/mixture.h5")
size = os.path.getsize(h5)
good = digest(h5)
check(rc == 0, f"reference extraction ({size} bytes)")


def failed_cleanly(rc, out, base, old_digest, reason, what):
    last = [ln for ln in out.splitlines() if "stopped" in ln]
    print("     " + (last[0] if last else out.strip()[-300:]))
    check(rc == 1, f"{what}: exit status 1 (got {rc})")
    check(reason in out and base + ".h5" in out, f"{what}: message names the file and '{reason}'")
    check(digest(base + ".h5") == old_digest and not os.path.exists(base + ".h5.tmp"),
          f"{what}: previous file intact, no temporary file")


# 1. File size limit: a new file (-overwrite, the flush fails) and an update (the copy fails).
base = os.path.splitext(h5)[0]
rc, out = run(case, "-overwrite", fsize=size // 2)
failed_cleanly(rc, out, base, good, "File too large", "size limit, -overwrite")
rc, out = run(case, fsize=size // 2)
failed_cleanly(rc, out, base, good, "File too large", "size limit, update")
rc, out = run(case, "-overwrite", fsize=4096)
failed_cleanly(rc, out, base, good, "File too large", "size limit 4 KiB, -overwrite")

# 2. A real full tmpfs, when mounting is allowed.
mnt = tempfile.mkdtemp(prefix="mx_full_disk_", dir=work)
mounted = False
try:
    kib = (size * 3 // 2) // 4096 * 4
    r = subprocess.run(["mount", "-t", "tmpfs", "-o", f"size={kib}k", "tmpfs", mnt], capture_output=True, text=True)
    mounted = r.returncode == 0
    if not mounted:
        print(f"skip the tmpfs part: cannot mount ({(r.stderr or r.stdout).strip()})")
    else:
        fbase = os.path.join(mnt, "mixture")
        shutil.copy(h5, fbase + ".h5")
        free = shutil.disk_usage(mnt).free
        print(f"tmpfs of {kib} KiB holding the {size}-byte file, {free} bytes free")
        rc, out = run(case, "-overwrite", "-output", fbase)
        failed_cleanly(rc, out, fbase, good, "No space left on device", "full tmpfs, -overwrite")
        rc, out = run(case, "-output", fbase)
        failed_cleanly(rc, out, fbase, good, "No space left on device", "full tmpfs, update")
finally:
    if mounted:
        subprocess.run(["umount", mnt], check=False)
    os.rmdir(mnt)

# 3. The XDMF cannot be written after the HDF5 file was updated: exit 1 saying so; a re-run fixes it.
xbase = os.path.join(work, "xdmf_blocked")
for ext in (".h5", ".xdmf", "_regions.csv"):
    if os.path.exists(xbase + ext):
        os.remove(xbase + ext)
os.makedirs(xbase + ".xdmf.tmp", exist_ok=True)  # the temporary XDMF cannot be opened
rc, out = run(case, "-output", xbase)
print("     " + " | ".join(ln for ln in out.splitlines() if "stopped" in ln or "holds" in ln))
check(rc == 1 and "xdmf_blocked.xdmf.tmp: write failed" in out and "holds the 2 new windows" in out
      and "run mixflowExtract again" in out and os.path.exists(xbase + ".h5") and not os.path.exists(xbase + ".xdmf"),
      "XDMF not writable: exit 1, says the HDF5 file holds the new windows and how to rewrite the XDMF")
os.rmdir(xbase + ".xdmf.tmp")
rc, out = run(case, "-output", xbase)
check(rc == 0 and "0 new windows, 2 already in the file" in out and os.path.exists(xbase + ".xdmf")
      and os.path.exists(xbase + "_regions.csv"), "re-run: XDMF and CSV rewritten")

print(f"{len(failures)} failure(s)")
sys.exit(1 if failures else 0)
