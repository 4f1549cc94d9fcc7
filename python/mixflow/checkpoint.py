"""A stopped mixture run's checkpoint: what `mixflow suite` needs to resume it (resumeMixtureCase,
docs/suite.md), small enough to commit (a few MB), so that a run longer than a session goes on
in the next session on any machine (results/li_zhao_2018/make.sh).

A checkpoint keeps, from the last field write T named by dem/coupled.resume.state:
- the case's dictionaries and mesh (system/, constant/, processor*/constant/), its Allrun, and
  the field write T itself (also in processor*/ for a parallel run);
- the particles' restart of that write (checked against the state's cksum) and the state, with
  the settled sample's state files (not its restart: the run does not settle again);
- the output series up to T: the DEM's whole, the liquid series and the exchange log thinned as a
  record thins them (record.py: the first row of each step, the row at T kept), so that the
  record of the finished run is the record of the uninterrupted run;
- the surface grains of the particle snapshots at paper.PROFILE_TIMES up to T (record.py).
The run's outputs after T are dropped: the resumed run writes them again.
"""

import glob
import os
import shutil
import subprocess

from . import outputs
from .paper import PROFILE_TIMES
from .record import STEP_S, file_sizes, record_snapshots, thinned

STATE = os.path.join("dem", "coupled.resume.state")
SETTLED_FILES = ("settled.state", "settled.inputs", "settled.entries")
CHECKPOINT = "checkpoint.json"
# The series the resume cuts (scripts/ResumeFunctions, resumeMixtureCase): True at the state's
# time, False at the DEM's last sampled row; the others are kept whole. The exchange log's stage
# timings are thinned with the log.
STAGE_TIMES = os.path.join("postProcessing", "coupling", "stageTimes.csv")
CUT = {outputs.LIQUID_SERIES: True, outputs.LIQUID_PROFILES: True, outputs.EXCHANGE: True,
       STAGE_TIMES: True, outputs.DEM_SERIES: False, outputs.RANK_LOAD: False}
THINNED = dict(STEP_S, **{STAGE_TIMES: STEP_S[outputs.EXCHANGE]})


def read_state(case):
    """dem/coupled.resume.state's entries as strings (quotes and comments dropped)."""
    entries = {}
    with open(os.path.join(case, STATE)) as f:
        for line in f:
            line = line.split("//", 1)[0].strip()
            if line.endswith(";") and " " in line:
                key, value = line[:-1].split(None, 1)
                entries[key] = value.strip().strip('"')
    return entries


def cksum(path):
    """POSIX cksum of PATH: (crc, bytes) as the state records them."""
    out = subprocess.run(["cksum", path], capture_output=True, text=True, check=True).stdout
    crc, size = out.split()[:2]
    return crc, size


def cut_lines(path, t):
    """PATH's lines with the rows after time T left out (headers and comments kept), as the
    resume's _cutRows cuts them."""
    keep, eps = [], 1e-9 * t + 1e-12
    with open(path) as f:
        for line in f:
            first = line.split(",", 1)[0]
            try:
                if float(first) > t + eps:
                    continue
            except ValueError:
                pass
            keep.append(line)
    return keep


def checkpoint_scene(case, out):
    """CASE's checkpoint into OUT (replaced if it exists). CASE must be a stopped mixture run
    with an intact field write; returns {relative path: bytes} of the files written."""
    if os.path.isfile(os.path.join(case, outputs.DONE)):
        raise ValueError(f"{case}: a finished run (it has {outputs.DONE}): record it (mixflow "
                         "scene-record), a checkpoint is for a stopped one")
    if not os.path.isfile(os.path.join(case, STATE)):
        raise ValueError(f"{case}: no {STATE}: the run stopped before its first field write, "
                         "so it restarts from its start and has nothing to keep")
    state = read_state(case)
    restart, name = state["restartFile"], state["timeName"]
    t = float(state["time"])
    if "restartCrc" in state and cksum(os.path.join(case, restart)) != (state["restartCrc"],
                                                                        state["restartBytes"]):
        raise ValueError(f"{case}: {restart} does not match {STATE}'s cksum: the run is still "
                         "writing it, or it is damaged; stop the run and checkpoint again")
    if os.path.isdir(out):
        shutil.rmtree(out)
    os.makedirs(out)
    for entry in sorted(os.listdir(case)):
        if os.path.isfile(os.path.join(case, entry)) and not entry.startswith("log."):
            shutil.copy2(os.path.join(case, entry), out)
    for base in [case] + sorted(glob.glob(os.path.join(case, "processor[0-9]*"))):
        rel = os.path.relpath(base, case)
        for d in ("system", "constant", name):
            src = os.path.join(case, rel, d)
            if os.path.isdir(src):
                shutil.copytree(src, os.path.join(out, rel, d))
    os.makedirs(os.path.join(out, "dem"))
    for f in (STATE, restart) + tuple(os.path.join("dem", s) for s in SETTLED_FILES):
        if os.path.isfile(os.path.join(case, f)):
            shutil.copy2(os.path.join(case, f), os.path.join(out, f))
    # The DEM's series up to its last sampled row (lastSampleStep x the DEM step).
    step, sampled = float(state.get("step", 0)), float(state.get("lastSampleStep", 0))
    t_dem = t * sampled / step if step > 0 else t
    for src in sorted(glob.glob(os.path.join(case, "postProcessing", "*", "*.csv"))):
        rel = os.path.relpath(src, case)
        if rel not in CUT:
            with open(src) as f:
                lines = f.readlines()
        else:
            lines = cut_lines(src, t if CUT[rel] else t_dem)
        if rel in THINNED:
            lines = thinned(lines, THINNED[rel])
        os.makedirs(os.path.dirname(os.path.join(out, rel)), exist_ok=True)
        with open(os.path.join(out, rel), "w") as f:
            f.writelines(lines)
    reached = [s for s in PROFILE_TIMES if s <= t]
    if reached:
        record_snapshots(case, out, reached)
    outputs.write_json(os.path.join(out, CHECKPOINT), {
        "source": os.path.abspath(case), "time_s": t, "time_name": name,
        "thinned_step_s": THINNED})
    return file_sizes(out)


def restore(checkpoint, run_dir):
    """CHECKPOINT copied to RUN_DIR, where `mixflow suite` resumes it; RUN_DIR must not exist."""
    if os.path.exists(run_dir):
        raise ValueError(f"{run_dir} exists: a checkpoint is restored only where there is no run")
    if not os.path.isfile(os.path.join(checkpoint, CHECKPOINT)):
        raise ValueError(f"{checkpoint}: not a checkpoint (no {CHECKPOINT})")
    shutil.copytree(checkpoint, run_dir)
