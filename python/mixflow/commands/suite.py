"""Runs the scenes of Li & Zhao (2018) Table 1 at a fidelity tier (docs/suite.md).

usage: suite.py --tier quick|reference|paper|FILE [--np N] [--scenes P,W,HB+P,...] [--work DIR]
                [--cost-only] [--force] [--dry-run] [--progress-every S] [--set FILE.ENTRY=VALUE ...]

For each scene: cases/<scene> is copied to WORK/<scene> (once), the tier's overrides
(cases/tiers/<tier>) are set in the copy's files and recorded in WORK/<scene>/system/tier, then
`./Allrun N` runs it (PATH gets the build's bin/: $MIXFLOW_BUILD or build/). A finished scene gets
WORK/<scene>/.done and is skipped next time, unless a later `--set controlDict.endTime` takes it on
to that time; an interrupted dry scene continues with
`mixflowDem -resume`, an interrupted liquid one from its latest complete field write
(resumeLiquidCase), an interrupted mixture one from its last field write (resumeMixtureCase), or,
stopped before one, again from its start with its own settled sample. Progress lines: scene i/n,
simulated time, wall time, estimated time to finish.

--cost-only (the default of tier paper on a machine with fewer than 16 cores, unless --force)
runs one scene per content (dry, liquid, mixture) for a short window, measures core-seconds per
simulated second and writes WORK/cost.json with the extrapolated core-hours of every scene.
"""

import argparse
import copy
import json
import math
import os
import re
import shutil
import subprocess
import sys
import time

from mixflow import ROOT, outputs, schema
from mixflow.foamcase import run_env
from mixflow.foamdict import (DictError, add_missing_blocks, edit_dict, edit_file, format_dict,  # noqa: F401
                              leaves, list_value, parse_dict, read_dict, unquote)
from mixflow.paper import TABLE1

CASES = os.path.join(ROOT, "cases")
TIERS = os.path.join(CASES, "tiers")

# Files a tier may name (top-level blocks of a tier file) and where they are in a case.
FILES = {"demDict": "system/demDict", "cfdDict": "system/cfdDict",
         "controlDict": "system/controlDict", "sceneProperties": "constant/sceneProperties",
         "couplingProperties": "constant/couplingProperties",
         "bulkProperties": "constant/bulkProperties",
         "mixflowProperties": "constant/mixflowProperties"}
# Mixture files whose every entry has a default (absent: the defaults): --set creates them.
CREATED_BY_SET = {"bulkProperties", "mixflowProperties"}
CONTENTS = ("particles", "liquid", "mixture")
TIER_KEYS = ({"FoamFile", "description", "contentSpecific", "settledSamples", "scenes"} | set(FILES)
             | set(CONTENTS))
# Time series whose last row is the simulated time reached, by content (first found counts).
SERIES = {"particles": [outputs.DEM_SERIES], "liquid": [outputs.LIQUID_SERIES],
          "mixture": [outputs.DEM_SERIES, outputs.LIQUID_SERIES]}
REPRESENTATIVE = {"particles": "P", "liquid": "W", "mixture": "W+P"}
SETTLE_ESTIMATE_S = 1.1  # settling of a Table 1 column (results/runout_scaling: 1.07 s for P-I-I)


# --------------------------------------------------------------------------------------------
# Tiers

def _merge(a, b):
    out = copy.deepcopy(a)
    for k, v in b.items():
        if isinstance(v, dict) and isinstance(out.get(k), dict):
            out[k] = _merge(out[k], v)
        else:
            out[k] = copy.deepcopy(v)
    return out


def set_item(item):
    """(FILE.entry[.sub], VALUE) of one --set item; DictError unless it is FILE.entry=VALUE with FILE
    a case file."""
    key, sep, value = item.partition("=")
    fkey, *path = key.split(".")
    if not sep or not path or not value.strip():
        raise DictError(f"--set '{item}': expected FILE.entry=VALUE")
    if fkey not in FILES:
        raise DictError(f"--set '{item}': '{fkey}' is not a case file (allowed: {', '.join(FILES)})")
    return key, value.strip()


class Tier:
    """A named set of per-file overrides (cases/tiers/<name>)."""

    def __init__(self, name_or_path):
        named = os.path.join(TIERS, name_or_path)
        path = named if os.sep not in name_or_path and os.path.isfile(named) else name_or_path
        if not os.path.isfile(path):
            known = sorted(os.listdir(TIERS)) if os.path.isdir(TIERS) else []
            raise DictError(f"no tier '{name_or_path}' (known: {', '.join(known)})")
        self.path = os.path.abspath(path)
        self.name = os.path.basename(path)
        d = read_dict(self.path)
        for k, v in d.items():
            if k not in TIER_KEYS:
                raise DictError(f"{self.path}: unknown entry '{k}' (allowed: {', '.join(sorted(TIER_KEYS))})")
            if k in FILES or k in CONTENTS or k == "scenes":
                if not isinstance(v, dict):
                    raise DictError(f"{self.path}: entry '{k}' must be a block")
        for c in CONTENTS:
            for k in d.get(c, {}):
                if k not in FILES:
                    raise DictError(f"{self.path}: entry '{c}.{k}': not a case file "
                                    f"(allowed: {', '.join(FILES)})")
        for s, blk in d.get("scenes", {}).items():
            for k in blk if isinstance(blk, dict) else [None]:
                if k not in FILES:
                    raise DictError(f"{self.path}: entry 'scenes.{s}.{k}': not a case file "
                                    f"(allowed: {', '.join(FILES)})")
        self.description = unquote(d.get("description", ""))
        self.content_specific = set(list_value(d.get("contentSpecific", "()")))
        # Shipped settled samples (ROOT/<dir>/<scene>/dem) a mixture starts from when they fit.
        samples = unquote(d.get("settledSamples", ""))
        self.settled_samples = os.path.join(ROOT, samples) if samples else None
        self.common = {k: v for k, v in d.items() if k in FILES}
        self.by_content = {c: d.get(c, {}) for c in CONTENTS}
        self.scenes = d.get("scenes", {})
        self.sets, self.set_text = {}, ""

    def set_entries(self, items):
        """Command-line overrides FILE.entry[.sub]=VALUE (--set), applied after the tier's own and
        recorded with the run: a variant of a tier (another drag scheme, exchange interval ...)
        is then a rerunnable command rather than a hand-edited copy."""
        for item in items:
            key, value = set_item(item)
            fkey, *path = key.split(".")
            node = self.sets.setdefault(fkey, {})
            for b in path[:-1]:
                node = node.setdefault(b, {})
            node[path[-1]] = value
        self.set_text = " ".join(items)

    def overrides(self, scene, content):
        """{file: nested overrides} for SCENE of CONTENT: common, then content, then scene, then
        the command line's --set."""
        return _merge(_merge(_merge(self.common, self.by_content.get(content, {})),
                             self.scenes.get(scene, {})), self.sets)

    def optional(self, file_key, block_path=()):
        """True if the tier lists FILE (or FILE.block...) as content-specific, unless --set names
        something in it (asked for on the command line: it must apply)."""
        node = self.sets.get(file_key)
        for b in block_path:
            node = node.get(b) if isinstance(node, dict) else None
        if node is not None:
            return False
        names = [file_key] + [".".join((file_key,) + tuple(block_path[:i + 1]))
                              for i in range(len(block_path))]
        return any(n in self.content_specific for n in names)


def scene_content(case_dir):
    path = os.path.join(case_dir, FILES["sceneProperties"])
    content = read_dict(path).get("content")
    if content not in CONTENTS:
        raise DictError(f"{path}: content '{content}' is none of {', '.join(CONTENTS)}")
    return content


def tier_edits(case_dir, tier, scene):
    """What TIER does to the files of CASE_DIR: ({relative path: new text}, records).

    records: [(file key, dotted entry, value, action)]. Nothing is written. Raises DictError
    naming the tier file and entry for an override that cannot be applied."""
    content = scene_content(case_dir)
    texts, records = {}, []
    for fkey, tree in tier.overrides(scene, content).items():
        rel = FILES[fkey]
        path = os.path.join(case_dir, rel)
        if (not os.path.isfile(path) and fkey in CREATED_BY_SET and tier.sets.get(fkey)
                and content == "mixture"):
            text = (f"FoamFile {{ version 2.0; format ascii; class dictionary; object {fkey}; }}\n"
                    "// Created by mixflow suite --set; entries not here take their defaults\n")
        elif not os.path.isfile(path):
            if tier.optional(fkey):
                records += [(fkey, ".".join(p), v, "skipped") for p, v in leaves(tree)]
                continue
            first = ".".join(next(iter(leaves(tree)))[0])
            raise DictError(f"{tier.path}: entry '{fkey}.{first}': scene {scene} ({content}) has no "
                            f"{rel}; list '{fkey}' in contentSpecific if that is expected")
        else:
            with open(path) as f:
                text = f.read()
        # A block named on the command line (--set FILE.block.entry=V) is created if the case
        # lacks it (e.g. DiFeliceDragCoeffs); a tier's own overrides must find theirs.
        if tier.sets.get(fkey):
            text = add_missing_blocks(text, tier.sets[fkey])
        try:
            new, actions = edit_dict(text, tree, note=f"tier {tier.name}",
                                     optional=lambda blk, fk=fkey: tier.optional(fk, blk))
        except DictError as e:
            raise DictError(f"{tier.path}: entry '{fkey}': {e} in {path}") from None
        texts[rel] = new
        records += [(fkey, dotted, v, a) for dotted, v, a in actions]
    return texts, records


def tier_record(tier, scene, content, records):
    """Text of WORK/<scene>/system/tier."""
    trees = {"overrides": {}, "skipped": {}}
    for fkey, dotted, v, action in records:
        node = trees["skipped" if action == "skipped" else "overrides"].setdefault(FILES[fkey], {})
        *blocks, key = dotted.split(".")
        for b in blocks:
            node = node.setdefault(b, {})
        node[key] = v
    return ("FoamFile { version 2.0; format ascii; class dictionary; object tier; }\n"
            "// Written by mixflow suite: the fidelity tier of this run and what it set\n"
            "// (skipped: content-specific overrides naming a file or block this case has not).\n"
            f"tier        {tier.name};\n"
            f"tierFile    \"{tier.path}\";\n"
            f"description \"{tier.description}\";\n"
            + (f"set         \"{tier.set_text}\";\n" if tier.set_text else "")
            + f"scene       {scene};\n"
            f"content     {content};\n"
            + format_dict(trees))


# --------------------------------------------------------------------------------------------
# Run copies, progress, resume

def last_time(path):
    """First field of the last complete data row of a CSV (None if none)."""
    try:
        with open(path, "rb") as f:
            f.seek(0, 2)
            size = f.tell()
            f.seek(max(0, size - 8192))
            tail = f.read().decode(errors="replace")
    except OSError:
        return None
    lines = [ln for ln in tail.split("\n")[:-1] if ln and not ln.startswith("#")]
    for ln in reversed(lines):
        try:
            return float(ln.split(",")[0])
        except ValueError:
            continue
    return None


def sim_time(run_dir, content):
    for rel in SERIES[content]:
        t = last_time(os.path.join(run_dir, rel))
        if t is not None:
            return t
    return None


def end_time(run_dir):
    return float(read_dict(os.path.join(run_dir, FILES["controlDict"]))["endTime"])


def hms(seconds):
    if seconds is None or math.isinf(seconds) or math.isnan(seconds):
        return "--:--:--"
    s = int(round(seconds))
    return f"{s // 3600}:{s % 3600 // 60:02d}:{s % 60:02d}"


def make_copy(scene, run_dir, tier, texts, records, content):
    """cases/<scene> -> RUN_DIR (inputs only), tier set. An Allrun that sources ../../scripts/
    is pointed at this checkout's scripts/ (newer ones use $MIXFLOW_ROOT, which run_env sets)."""
    outputs.copy_inputs(os.path.join(CASES, scene), run_dir)
    allrun = os.path.join(run_dir, "Allrun")
    if os.path.isfile(allrun):
        with open(allrun) as f:
            text = f.read()
        with open(allrun, "w") as f:
            f.write(re.sub(r"(\.\./)+scripts/", os.path.join(ROOT, "scripts") + "/", text))
    for rel, text in texts.items():
        with open(os.path.join(run_dir, rel), "w") as f:
            f.write(text)
    with open(os.path.join(run_dir, "system", "tier"), "w") as f:
        f.write(tier_record(tier, scene, content, records))


def copy_at_tier(scene, tier, run_dir):
    """cases/<scene> set to TIER in RUN_DIR (replaced), as a fresh run of the suite sets it."""
    src = os.path.join(CASES, scene)
    texts, records = tier_edits(src, tier, scene)
    shutil.rmtree(run_dir, ignore_errors=True)
    make_copy(scene, run_dir, tier, texts, records, scene_content(src))


def liquid_restart_time(run_dir, ranks):
    """Latest complete field write of an interrupted liquid run, else None: the one
    resumeLiquidCase continues from (asked of the same shell function, latestLiquidWrite)."""
    if not os.path.isfile(os.path.join(run_dir, "log.mixflowFoam")):
        return None
    out = subprocess.run(["bash", "-c", '. "$1" && latestLiquidWrite "$2"', "RunFunctions",
                          os.path.join(ROOT, "scripts", "RunFunctions"), str(ranks)],
                         cwd=run_dir, capture_output=True, text=True).stdout.strip()
    return out or None


def has_fingerprint(state_path):
    """True if a settled.state records its settling inputs' fingerprint (mixflowDem -reuse)."""
    try:
        with open(state_path) as f:
            return re.search(r"\bfingerprint\s+\"[0-9a-f]+\"", f.read()) is not None
    except OSError:
        return False


def plan_settled(p, settled_from, shipped=None):
    """Mixture scenes: the settled sample Allrun reuses (its SETTLED_DIR), if any: the one of
    --settled-from, else, rerunning a copy that failed after settling, its own, else for a fresh
    copy the tier's shipped sample SHIPPED/<scene>/dem if there is one (p["shipped"]: used once
    the copy shows that it fits, shipped_sample_fits)."""
    if p.get("content") != "mixture" or p["status"] not in ("fresh", "restart"):
        return
    if shipped and not settled_from and p["status"] == "fresh":
        d = os.path.join(shipped, p["scene"], "dem")
        if os.path.isfile(os.path.join(d, "settled.state")):
            p["shipped"] = d
            p["command"] += f" {d} (the tier's shipped sample, if the copy's settling inputs fit it)"
        return
    if settled_from:
        d = os.path.join(settled_from, p["scene"], "dem")
        if not os.path.isfile(os.path.join(d, "settled.state")):
            p["status"], p["error"] = "error", (f"--settled-from: {d}/settled.state: cannot open "
                                                "file: no settled sample of this scene there")
            return
        p["settled"] = d
    elif p["status"] == "restart" and has_fingerprint(
            os.path.join(p["run_dir"], "dem", "settled.state")):
        p["settled"] = os.path.join(p["run_dir"], "dem")
    if p.get("settled"):
        p["command"] += f" {p['settled']} (reusing its settled sample)"


def plan_scene(scene, work, tier, ranks, settled_from=None):
    """What run_scene would do: dict with status fresh (copy and run), resume, restart (rerun an
    existing copy from its start), done, missing (no case) or error (with the message). A mixture
    scene reuses a settled sample (plan_settled) when one can be."""
    p = _plan_scene(scene, work, tier, ranks)
    plan_settled(p, settled_from, tier.settled_samples)
    return p


def shipped_sample_fits(run_dir, sample):
    """(fits, mixflowDem's last line): whether the copy RUN_DIR can start from the shipped SAMPLE
    (mixflowDem -check -settleOnly -reuse: the same settling inputs by fingerprint), and what it
    said (the match, or the first entry that differs)."""
    r = subprocess.run(["mixflowDem", "-case", ".", "-check", "-settleOnly", "-reuse", sample],
                       cwd=run_dir, env=run_env(), capture_output=True, text=True)
    lines = (r.stderr or r.stdout).strip().splitlines()
    return r.returncode == 0, (lines[-1] if lines else f"exit status {r.returncode}")


def _split_end(set_text):
    """(the entries the --set items leave other than controlDict.endTime, {key: value} with the
    last of a key winning, so that their order does not matter; endTime's value or None)."""
    entries, end = {}, None
    for item in set_text.split():
        key, value = set_item(item)
        if key == "controlDict.endTime":
            end = value
        else:
            entries[key] = value
    return entries, end


def later_end(run_dir, recorded_set, tier):
    """The later endTime asked of RUN_DIR when the --set values differ from those it was made
    with only in controlDict.endTime (a finished or stopped run then goes on to it); None when
    they are the same, in any order. Another difference, or an earlier endTime, is an error."""
    if recorded_set == tier.set_text:
        return None
    (was, _), (now, end) = _split_end(recorded_set), _split_end(tier.set_text)
    mismatch = DictError(f"{run_dir} was made with --set '{recorded_set}', not '{tier.set_text}': "
                         "choose another --work")
    if was != now or end is None:
        raise mismatch
    try:
        new, current = float(end), end_time(run_dir)
    except (ValueError, KeyError) as e:
        raise DictError(f"--set controlDict.endTime={end}: {e}")
    if new < current:
        raise DictError(f"{run_dir} runs to endTime {current:g} s: --set controlDict.endTime={end} "
                        "would shorten it (a run only goes on to a later time): choose another --work")
    return new if new > current else None


def _plan_scene(scene, work, tier, ranks):
    src = os.path.join(CASES, scene)
    run_dir = os.path.join(work, scene)
    p = {"scene": scene, "case": src, "run_dir": run_dir}
    if not os.path.isdir(src) and not os.path.isdir(run_dir):
        p["status"] = "missing"
        return p
    try:
        if os.path.isdir(run_dir):
            if not os.path.isfile(os.path.join(run_dir, "system", "tier")):
                raise DictError(f"{run_dir} exists but has no system/tier (not made by suite.py, or "
                                "its copy was interrupted): remove it")
            rec = read_dict(os.path.join(run_dir, "system", "tier"))
            if rec.get("tier") != tier.name:
                raise DictError(f"{run_dir} was made with tier '{rec.get('tier')}', not "
                                f"'{tier.name}': choose another --work")
            extend_to = later_end(run_dir, unquote(rec.get("set", "")), tier)
            if extend_to is None and os.path.isfile(os.path.join(run_dir, outputs.DONE)):
                p["status"] = "done"
                return p
            if extend_to is not None:
                p["extend_to"] = extend_to
            p["content"] = rec["content"]
            p["texts"], p["records"] = {}, []
            if p["content"] == "particles" and os.path.isfile(os.path.join(run_dir, "dem", "resume.state")):
                p["status"], p["command"] = "resume", f"mixflowDem -resume ({ranks} ranks)"
            elif p["content"] == "mixture" and os.path.isfile(
                    os.path.join(run_dir, "dem", "coupled.resume.state")):
                p["status"] = "resume"
                p["command"] = f"mixflowCoupled -resume from its last field write ({ranks} ranks)"
            elif p["content"] == "liquid" and (t := liquid_restart_time(run_dir, ranks)):
                p["status"], p["restart_time"] = "resume", t
                p["command"] = f"mixflowFoam from t = {p['restart_time']} s ({ranks} ranks)"
            else:
                p["status"], p["command"] = "restart", f"./Allrun {ranks}"
            if extend_to is not None:
                p["command"] = f"endTime -> {extend_to:g} s, then {p['command']}"
        else:
            p["content"] = scene_content(src)
            p["texts"], p["records"] = tier_edits(src, tier, scene)
            p["status"], p["command"] = "fresh", f"./Allrun {ranks}"
    except (DictError, OSError, KeyError) as e:
        p["status"], p["error"] = "error", str(e)
    return p


def resume_command(content, ranks):
    fn = {"particles": "resumeDemCase", "mixture": "resumeMixtureCase"}.get(content, "resumeLiquidCase")
    return ["bash", "-c", f'. "$1" && {fn} "$2"', "ResumeFunctions",
            os.path.join(ROOT, "scripts", "ResumeFunctions"), str(ranks)]


def execute(p, ranks, label, progress_every, samples=None, poll=1.0):
    """Runs the planned scene; returns (ok, wall seconds). SAMPLES collects (wall, sim time)."""
    run_dir, content = p["run_dir"], p["content"]
    cmd = resume_command(content, ranks) if p["status"] == "resume" else \
        ["./Allrun", str(ranks)] + ([p["settled"]] if p.get("settled") else [])
    t_end = end_time(run_dir)
    log = open(os.path.join(run_dir, "log.suite"), "a")
    log.write(f"\n=== {time.strftime('%Y-%m-%d %H:%M:%S')} {' '.join(cmd)}\n")
    log.flush()
    start = time.time()
    proc = subprocess.Popen(cmd, cwd=run_dir, env=run_env(), stdout=log, stderr=subprocess.STDOUT)
    first = None  # (wall, sim) of the first simulated time seen in this invocation
    last_print = 0.0
    try:
        while True:
            try:
                proc.wait(timeout=poll)
                break
            except subprocess.TimeoutExpired:
                pass
            now = time.time()
            t = sim_time(run_dir, content)
            if t is not None:
                if samples is not None:
                    samples.append((now, t))
                if first is None or t < first[1]:
                    first = (now, t)
            if now - last_print >= progress_every:
                last_print = now
                print(progress_line(label, t, t_end, now - start, first, now), flush=True)
    except KeyboardInterrupt:
        proc.wait()
        log.close()
        raise
    log.close()
    wall = time.time() - start
    t = sim_time(run_dir, content)
    print(progress_line(label, t, t_end, wall, first, time.time(),
                        "finished" if proc.returncode == 0 else f"FAILED (exit {proc.returncode})"),
          flush=True)
    return proc.returncode == 0, wall


def progress_line(label, t, t_end, wall, first, now, state=None):
    if t is None:
        sim = "sim    preparing (settling / meshing)"
        eta = None
    else:
        sim = f"sim {t:7.3f} / {t_end:g} s"
        rate = (t - first[1]) / (now - first[0]) if first and now > first[0] and t > first[1] else 0
        eta = (t_end - t) / rate if rate > 0 else None
    tail = state or f"ETA {hms(eta)}"
    return f"{label:<16} {sim}   wall {hms(wall)}   {tail}"


def tag_summaries(run_dir, tier_name):
    """Adds "tier" to every postProcessing/*/summary.json of RUN_DIR."""
    pp = os.path.join(run_dir, outputs.POST)
    for sub in sorted(os.listdir(pp)) if os.path.isdir(pp) else []:
        path = os.path.join(pp, sub, "summary.json")
        if os.path.isfile(path):
            with open(path) as f:
                s = json.load(f)
            s["tier"] = tier_name
            with open(path, "w") as f:
                json.dump(s, f, indent=2)
                f.write("\n")


def extend_run(run_dir, tier, end):
    """A run copy goes on to a later endTime: its controlDict and its system/tier record (the
    --set values and the controlDict override) take the new one, and .done goes."""
    edit_file(os.path.join(run_dir, FILES["controlDict"]), {"endTime": f"{end:.12g}"}, note="set")
    edit_file(os.path.join(run_dir, "system", "tier"),
              {"set": f'"{tier.set_text}"',
               "overrides": {FILES["controlDict"]: {"endTime": f"{end:.12g}"}}}, create_blocks=True)
    if os.path.exists(os.path.join(run_dir, outputs.DONE)):
        os.remove(os.path.join(run_dir, outputs.DONE))


def run_scene(p, tier, ranks, label, progress_every, samples=None, poll=1.0):
    if p["status"] == "fresh":
        make_copy(p["scene"], p["run_dir"], tier, p["texts"], p["records"], p["content"])
        if p.get("shipped"):
            fits, why = shipped_sample_fits(p["run_dir"], p["shipped"])
            if fits:
                p["settled"] = p["shipped"]
            else:
                print(f"{label}: settling: the shipped sample {p['shipped']} does not fit "
                      f"this copy ({why})", flush=True)
    if p.get("extend_to") is not None:
        extend_run(p["run_dir"], tier, p["extend_to"])
    for name in (".failed",):
        if os.path.exists(os.path.join(p["run_dir"], name)):
            os.remove(os.path.join(p["run_dir"], name))
    ok, wall = execute(p, ranks, label, progress_every, samples, poll)
    run_dir = p["run_dir"]
    info = {"tier": tier.name, "ranks": ranks, "wall_s": round(wall, 1), "mode": p["status"],
            "simulated_s": sim_time(run_dir, p["content"]), "finished": time.strftime("%Y-%m-%d %H:%M:%S")}
    if ok:
        tag_summaries(run_dir, tier.name)
        with open(os.path.join(run_dir, outputs.DONE), "w") as f:
            json.dump(info, f, indent=2)
    else:
        with open(os.path.join(run_dir, ".failed"), "w") as f:
            json.dump(info, f, indent=2)
        print(f"  see {os.path.join(run_dir, 'log.suite')}", file=sys.stderr)
    return ok, wall


# --------------------------------------------------------------------------------------------
# Cost of a tier: measured on one scene per content, extrapolated to every scene

def tier_file_tree(case_dir, texts, fkey):
    """The parsed file FKEY (a key of FILES) of the case in CASE_DIR as the tier leaves it: the
    edited text of TEXTS (tier_edits) if the tier changed it, else the case's own ({} if absent)."""
    rel = FILES[fkey]
    if rel in texts:
        return parse_dict(texts[rel])
    path = os.path.join(case_dir, rel)
    return read_dict(path) if os.path.isfile(path) else {}


def scene_size(case_dir, texts, content):
    """(particles, fluid cells, H) of the case as the tier leaves it."""
    def d(fkey):
        return tier_file_tree(case_dir, texts, fkey)
    sp = d("sceneProperties")
    L, H, W = (float(sp["sample"][k]) for k in ("length", "height", "width"))
    particles = cells = None
    if content in ("particles", "mixture"):
        dp = float(schema.value(sp, FILES["sceneProperties"], "particles.diameter"))
        phi = float(schema.value(sp, FILES["sceneProperties"], "sample.solidFraction"))
        particles = phi * L * H * W / (math.pi / 6 * dp ** 3)
    if content in ("liquid", "mixture"):
        cfd = d("cfdDict")
        dx = float(cfd.get("cellSize", H / 20)) if cfd.get("cellSize", "auto") != "auto" else H / 20
        two_d = int(float(schema.value(cfd, FILES["cfdDict"], "dimensions"))) == 2
        nz = 1 if two_d else max(1, round(W / dx))
        cells = round(float(sp["channel"]["length"]) / dx) * round(float(sp["channel"]["height"]) / dx) * nz
        cells = {"cells": cells, "dx": dx}
    return {"particles": particles, "cells": cells, "H": H}


def cost_scale(size, ref):
    """Cost per simulated second of a scene relative to the measured one of its content.

    Particles: proportional to the number of grains (same DEM step). Fluid: cells x steps per
    second, the Courant-limited step ~ dx / sqrt(g H)."""
    if size["particles"] is not None:
        return size["particles"] / ref["particles"]
    c, r = size["cells"], ref["cells"]
    return (c["cells"] / c["dx"] * math.sqrt(size["H"])) / (r["cells"] / r["dx"] * math.sqrt(ref["H"]))


def cost_run(args, tier, scenes, work):
    """--cost-only: measure one scene per content for a short window; write WORK/cost.json."""
    # Planned as fresh copies (a directory that never exists): what the tier sets in each case.
    plans = {s: plan_scene(s, os.path.join(work, "cost", "none"), tier, args.np) for s in scenes}
    by_content = {}
    for s in scenes:
        p = plans[s]
        if p["status"] == "error":
            sys.exit(f"suite.py: {p['error']}")
        if p["status"] == "missing":
            print(f"{s}: no case directory {p['case']}: left out of the cost estimate")
            continue
        by_content.setdefault(p["content"], []).append(s)
    measured, failed = {}, []
    for content, members in by_content.items():
        rep = REPRESENTATIVE[content] if REPRESENTATIVE[content] in members else members[0]
        window = args.cost_window or ((0.01 if content != "liquid" else 0.02) if tier.name == "paper" else 0.3)
        run_dir = os.path.join(work, "cost", rep)
        extra = {"controlDict": {"endTime": f"{window:g}", "writeInterval": f"{window:g}"}}
        if content != "liquid":
            # The sample is not left to settle (seconds of settling at the tier's step): the
            # collapse starts from the loose fill. Fewer contacts than in a settled column, so the
            # measured cost is a lower bound (docs/suite.md).
            extra["demDict"] = {"settle": {"maxTime": f"{args.cost_settle:g}", "relaxTime": "0"}}
        print(f"cost: {content} scene {rep}, {window:g} s simulated after "
              f"{'settling capped at %g s' % args.cost_settle if content != 'liquid' else 'meshing'}"
              f", {args.np} rank(s)", flush=True)
        p = dict(plans[rep], run_dir=run_dir, status="fresh")
        texts = dict(p["texts"])
        for fkey, tree in extra.items():
            rel = FILES[fkey]
            base = texts.get(rel) or open(os.path.join(CASES, rep, rel)).read()
            texts[rel], acts = edit_dict(base, tree, note="suite.py --cost-only", create_blocks=True)
            p["records"] = p["records"] + [(fkey, d, v, a) for d, v, a in acts]
        p["texts"] = texts
        if args.dry_run:
            print(f"  would run {rep} in {run_dir}: ./Allrun {args.np}")
            for fkey, dotted, v, action in p["records"]:
                print(f"    {FILES[fkey]:<28} {dotted:<28} {v:<10} {action}")
            continue
        if os.path.isdir(run_dir):
            shutil.rmtree(run_dir)
        samples = []
        ok, wall = run_scene(p, tier, args.np, f"cost {rep}", args.progress_every, samples, poll=0.2)
        w_end = time.time()
        pts = [(w, t) for w, t in samples if t is not None]
        t_final = sim_time(run_dir, content)
        if not ok or len(pts) < 2 or t_final is None or t_final - pts[0][1] <= 0:
            why = "failed" if not ok else "was too short to time (raise --cost-window)"
            print(f"suite.py: the cost run of {rep} {why}: {content} scenes left out "
                  f"(log: {run_dir}/log.suite)", file=sys.stderr)
            failed.append(rep)
            continue
        w0, t0 = pts[0]
        w1 = pts[-1][0] if pts[-1][1] >= t_final else w_end
        sim = t_final - t0
        measured[content] = {"scene": rep, "simulated_s": sim, "wall_s": w1 - w0, "ranks": args.np,
                             "core_s_per_simulated_s": (w1 - w0) * args.np / sim,
                             "size": scene_size(run_dir, {}, content)}
        summary = os.path.join(run_dir, outputs.DEM_SUMMARY)
        if os.path.isfile(summary):  # cost of one grain for one DEM step: compares tiers
            m = measured[content]
            with open(summary) as f:
                m["dem_time_step_s"] = json.load(f).get("time_step_s")
            if m["dem_time_step_s"]:
                m["core_s_per_particle_step"] = m["core_s_per_simulated_s"] * m["dem_time_step_s"] \
                    / m["size"]["particles"]
    if args.dry_run:
        return 0
    out = {"tier": tier.name, "tier_file": tier.path, "machine_cores": os.cpu_count(),
           "measured": measured, "scenes": {},
           "method": "core-seconds per simulated second = wall seconds x ranks / simulated seconds, "
                     "timed from the first time-series row to the last (preparation, settling and "
                     "meshing excluded); per scene scaled by grains (particles, mixtures) or by "
                     "cells x steps (liquids: cells / dx x sqrt(H)), times endTime (+ "
                     f"{SETTLE_ESTIMATE_S} s of settling for particle scenes)",
           "caveats": "particle cost measured on an unsettled (loose) sample: a lower bound; the "
                      "run stops earlier than endTime once arrested (dry), so an upper bound there"}
    total = 0.0
    print(f"\n{'scene':<10} {'content':<10} {'endTime':>8} {'scale':>7} {'core-hours':>11}")
    for s in scenes:
        p = plans[s]
        if p["status"] == "missing" or p["content"] not in measured:
            continue
        m = measured[p["content"]]
        size = scene_size(p["case"], p["texts"], p["content"])
        scale = cost_scale(size, m["size"])
        t_end = float(parse_dict(p["texts"].get(FILES["controlDict"])
                                 or open(os.path.join(p["case"], FILES["controlDict"])).read())["endTime"])
        sim = t_end + (SETTLE_ESTIMATE_S if p["content"] != "liquid" else 0)
        ch = m["core_s_per_simulated_s"] * scale * sim / 3600
        total += ch
        out["scenes"][s] = {"content": p["content"], "end_time_s": t_end, "simulated_s": sim,
                            "scale": scale, "core_hours": ch}
        print(f"{s:<10} {p['content']:<10} {t_end:8g} {scale:7.3f} {ch:11.3g}")
    out["total_core_hours"] = total
    print(f"{'total':<10} {'':<10} {'':>8} {'':>7} {total:11.3g}")
    os.makedirs(work, exist_ok=True)
    with open(os.path.join(work, "cost.json"), "w") as f:
        json.dump(out, f, indent=2)
        f.write("\n")
    print(f"written {os.path.join(work, 'cost.json')}")
    return 1 if failed else 0


# --------------------------------------------------------------------------------------------

def parse_scenes(arg):
    if not arg:
        return list(TABLE1)
    return [s.strip().replace("&", "+") for s in arg.split(",") if s.strip()]


def print_plan(plans, tier, args):
    print(f"tier {tier.name} ({tier.path}): {tier.description}")
    print(f"work {args.work}, {args.np} rank(s), build {run_env()['PATH'].split(os.pathsep)[0]}")
    for i, p in enumerate(plans, 1):
        head = f"[{i}/{len(plans)}] {p['scene']}"
        if p["status"] in ("done", "missing", "error"):
            why = {"done": "finished (.done): skipped", "missing": f"no case {p['case']}: skipped",
                   "error": p.get("error")}[p["status"]]
            print(f"{head}: {why}")
            continue
        print(f"{head} ({p['content']}): {p['status']}: {p['command']} in {p['run_dir']}")
        for fkey, dotted, v, action in p["records"]:
            print(f"    {FILES[fkey]:<28} {dotted:<28} {v:<10} {action}")


def run(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--tier", required=True, help="quick, reference, paper or a tier file")
    ap.add_argument("--np", type=int, default=1, help="MPI ranks per scene (default 1)")
    ap.add_argument("--scenes", help="comma-separated (default: all 14 of Table 1; W&P = W+P)")
    ap.add_argument("--work", help="run directory (default runs/<tier>)")
    ap.add_argument("--cost-only", action="store_true", help="measure and extrapolate the cost only")
    ap.add_argument("--force", action="store_true", help="run tier paper on fewer than 16 cores")
    ap.add_argument("--dry-run", action="store_true", help="print the plan, run nothing")
    ap.add_argument("--progress-every", type=float, default=30, help="s between progress lines")
    ap.add_argument("--cost-window", type=float, help="simulated s of a cost run (default, tier "
                    "paper: 0.01 for particle scenes, 0.02 for liquids; other tiers: 0.3)")
    ap.add_argument("--cost-settle", type=float, default=0.002,
                    help="settling cap (s) of a particle cost run (default 0.002)")
    ap.add_argument("--set", action="append", default=[], metavar="FILE.ENTRY=VALUE",
                    help="override a case entry after the tier's, e.g. couplingProperties."
                    "dragIntegration=implicit (repeatable; recorded in system/tier; needs its own --work)")
    ap.add_argument("--settled-from", metavar="WORK",
                    help="mixture scenes reuse the sample settled in WORK/<scene>/dem (an earlier "
                    "run directory) instead of settling, if settled from the same inputs (mixflowDem "
                    "-reuse checks the fingerprint and stops at the first difference); e.g. a "
                    "--set study of the liquid or the coupling on the same grains")
    args = ap.parse_args(argv)
    try:
        tier = Tier(args.tier)
        tier.set_entries(args.set)
    except DictError as e:
        sys.exit(f"suite.py: {e}")
    args.work = os.path.abspath(args.work or os.path.join(ROOT, "runs", tier.name))
    scenes = parse_scenes(args.scenes)
    if args.np < 1:
        sys.exit("suite.py: --np must be >= 1")
    if tier.name == "paper" and not args.cost_only and (os.cpu_count() or 1) < 16 and not args.force:
        print(f"tier paper on {os.cpu_count()} cores: measuring its cost only (--force runs it)")
        args.cost_only = True
    if args.cost_only:
        return cost_run(args, tier, scenes, args.work)
    settled_from = os.path.abspath(args.settled_from) if args.settled_from else None
    plans = [plan_scene(s, args.work, tier, args.np, settled_from) for s in scenes]
    print_plan(plans, tier, args)
    errors = [p for p in plans if p["status"] == "error"]
    if errors:
        sys.exit("suite.py: " + "; ".join(p["error"] for p in errors))
    if args.dry_run:
        return 0
    os.makedirs(args.work, exist_ok=True)
    failed, walls = [], {}
    todo = [p for p in plans if p["status"] not in ("done", "missing")]
    for i, p in enumerate(plans, 1):
        if p["status"] in ("done", "missing"):
            continue
        label = f"[{i}/{len(plans)}] {p['scene']}"
        print(f"{label}: {p['status']} ({p['command']})", flush=True)
        ok, walls[p["scene"]] = run_scene(p, tier, args.np, label, args.progress_every)
        if not ok:
            failed.append(p["scene"])
        left = [q for q in todo if q["scene"] not in walls]
        if left and walls:
            mean = sum(walls.values()) / len(walls)
            print(f"  {len(left)} scene(s) left: about {hms(mean * len(left))} at the mean pace so far", flush=True)
    done = [s for s in scenes if os.path.isfile(os.path.join(args.work, s, outputs.DONE))]
    missing = [p["scene"] for p in plans if p["status"] == "missing"]
    print(f"finished {len(done)}/{len(scenes)}" + (f"; failed: {', '.join(failed)}" if failed else "")
          + (f"; no case yet: {', '.join(missing)}" if missing else ""))
    return 1 if failed else 0


def main(argv=None):
    try:
        return run(argv)
    except KeyboardInterrupt:
        sys.exit("mixflow suite: interrupted; the same command resumes (docs/suite.md)")


if __name__ == "__main__":
    sys.exit(main())
