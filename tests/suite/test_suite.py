#!/usr/bin/env python3
"""The dictionary editor (python/mixflow/foamdict.py) and mixflow suite's tier files, plan and
resume bookkeeping (no simulation).

usage: test_suite.py WORKDIR

Checks, each exact:
  1. editor on a temporary copy of cases/P: a top-level value and nested values are replaced
     (comments, other entries and the layout untouched), an absent entry is inserted (top level,
     multi-line block, one-line block), the result parses back to the values set;
  2. errors: an override naming a block the case lacks names the tier file and the entry; a file
     the case lacks is skipped only when the tier lists it in contentSpecific; an unknown
     top-level tier entry is refused; an unbalanced dictionary is refused;
  3. every tier (paper, reference, quick, paper-window, truth) applies to every Table 1 scene present in cases/
     without an error, never touches the channel length/height or the sample's L and H, and sets
     what docs/suite.md says for P, W and HB-I;
  4. `suite.py --tier quick --scenes P-I-I --dry-run` prints the plan and writes nothing;
  5. settled samples: --settled-from and a rerun's own fingerprinted sample are reused by mixture
     scenes only, a missing one refused; a mixture copy with a coupled resume state resumes; a
     finished run asked for a later endTime by --set (the only difference) is extended and
     resumes, an earlier endTime or another --set difference is refused;
  6. the resume helpers: the last time of a CSV, a resumed run's solver CPU summed over its
     attempts, cutting a liquid time series after a restart
     time, the liquid restart time found from written time directories.
"""
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.dont_write_bytecode = True  # no __pycache__ in the source tree
from mixflow.commands import suite  # noqa: E402
from mixflow import foamdict  # noqa: E402

failures = []


def check(cond, what):
    """Prints and records one check."""
    failures.extend([] if cond else [what])
    print(("ok   " if cond else "FAIL ") + what)


work = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else "/tmp/test_suite")
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)


def raises(fn, *words):
    try:
        fn()
    except foamdict.DictError as e:
        msg = str(e)
        return all(w in msg for w in words), msg
    return False, "no error"


# 1. Editor on a copy of cases/P.
case = os.path.join(work, "P")
shutil.copytree(os.path.join(ROOT, "cases", "P"), case)
dem = open(os.path.join(case, "system", "demDict")).read()
new, acts = foamdict.edit_dict(dem, {"youngModulusFactor": "1", "timeStep": "5e-7",
                                  "settle": {"maxTime": "0.5", "relaxTime": "0"},
                                  "velocityProfile": {"time": "0.6"}, "limitForce": "off"},
                            note="tier test")
d = foamdict.parse_dict(new)
check(d["youngModulusFactor"] == "1" and d["timeStep"] == "5e-7", "top-level values replaced")
check(d["settle"] == {"friction": "0.1", "maxTime": "0.5", "relaxTime": "0"},
      "one-line block: value replaced, absent entry inserted, others kept")
check(d["velocityProfile"] == {"x": "0.8", "time": "0.6"}, "one-line nested value replaced")
check(d["limitForce"] == "off" and new.rstrip().endswith("limitForce off;   // tier test"),
      "absent top-level entry appended")
check("youngModulusFactor 1;   // tier test (case: 1e-3)" in new,
      "the changed entry's comment records the tier and the case's value")
check("rayleighFraction   0.1;" in new and "sampleInterval     0.01;   // s between time-series rows" in new,
      "untouched entries keep their layout and comments")
check({a for _, _, a in acts} == {"set", "inserted"} and len(acts) == 6, f"actions {acts}")

sp = open(os.path.join(case, "constant", "sceneProperties")).read()
new, acts = foamdict.edit_dict(sp, {"sample": {"width": "0.072", "newKey": "3"},
                                 "channel": {"sideWalls": "periodic"},
                                 "particles": {"friction": "0.7"}})
d = foamdict.parse_dict(new)
check(d["sample"]["width"] == "0.072" and d["sample"]["length"] == "0.9"
      and d["sample"]["height"] == "0.6", "nested value replaced, siblings kept")
check(d["sample"]["newKey"] == "3" and "    newKey 3;\n}" in new,
      "absent entry inserted at the end of a multi-line block, indented")
check(d["channel"]["sideWalls"] == "periodic" and d["channel"]["length"] == "4.0", "second block")
check(("particles.friction", "0.7", "kept") in acts, "an equal value is reported as kept")
check(new.count("{") == sp.count("{") and new.count("}") == sp.count("}"), "no block added")

ok, msg = raises(lambda: foamdict.edit_dict(sp, {"liquid": {"density": "1000"}}), "liquid", "liquid.density")
check(ok, f"missing block is an error naming the entry: {msg}")
new, acts = foamdict.edit_dict(sp, {"liquid": {"density": "1000"}}, optional=lambda path: path == ("liquid",))
check(new == sp and acts == [("liquid.density", "1000", "skipped")], "optional missing block skipped")
new, _ = foamdict.edit_dict(dem, {"newBlock": {"a": "1", "b": "2"}}, create_blocks=True)
check(foamdict.parse_dict(new)["newBlock"] == {"a": "1", "b": "2"}, "create_blocks inserts a block")
ok, msg = raises(lambda: foamdict.parse_dict("a { b 1; "), "not closed")
check(ok, f"unbalanced dictionary refused: {msg}")
ok, msg = raises(lambda: foamdict.edit_dict(sp, {"sample": "1"}), "block, not an entry")
check(ok, f"a value for a block refused: {msg}")

# 2. Tier errors: a bad tier file in the work directory.
bad = os.path.join(work, "badtier")
with open(bad, "w") as f:
    f.write("FoamFile { object tier; }\ncontentSpecific (demDict);\n"
            "sceneProperties { sampel { width 0.1; } }\n")
tier = suite.Tier(bad)
ok, msg = raises(lambda: suite.tier_edits(os.path.join(ROOT, "cases", "P"), tier, "P"),
                 bad, "sceneProperties", "sampel.width")
check(ok, f"bad entry: error names tier file and entry: {msg}")
with open(bad, "w") as f:
    f.write("cfdDict { cellSize 0.05; }\n")
ok, msg = raises(lambda: suite.tier_edits(os.path.join(ROOT, "cases", "P"), suite.Tier(bad), "P"),
                 bad, "cfdDict.cellSize", "system/cfdDict", "contentSpecific")
check(ok, f"file the case lacks, not content-specific: error: {msg}")
with open(bad, "w") as f:
    f.write("contentSpecific (cfdDict);\ncfdDict { cellSize 0.05; }\n")
texts, recs = suite.tier_edits(os.path.join(ROOT, "cases", "P"), suite.Tier(bad), "P")
check(texts == {} and recs == [("cfdDict", "cellSize", "0.05", "skipped")],
      "file the case lacks, content-specific: skipped")
with open(bad, "w") as f:
    f.write("demdict { youngModulusFactor 1; }\n")
ok, msg = raises(lambda: suite.Tier(bad), bad, "unknown entry 'demdict'")
check(ok, f"unknown tier entry refused: {msg}")

# 3. The real tiers on every scene present.
expect = {("quick", "P"): {"system/demDict": {"youngModulusFactor": "1e-4"},
                           "constant/sceneProperties": {"sample": {"width": "0.072"},
                                                        "channel": {"sideWalls": "periodic"}},
                           "system/controlDict": {"endTime": "1.5"}},
          ("paper", "P"): {"system/demDict": {"youngModulusFactor": "1", "timeStep": "5e-7"},
                           "constant/sceneProperties": {"sample": {"width": "0.6"},
                                                        "channel": {"sideWalls": "walls"}}},
          ("reference", "W"): {"system/cfdDict": {"dimensions": "2", "cellSize": "0.03"}},
          ("paper", "W"): {"system/cfdDict": {"dimensions": "3", "cellSize": "0.03"}},
          ("reference", "HB-I"): {"system/cfdDict": {"dimensions": "2", "cellSize": "0.0065"}},
          ("quick", "B-I"): {"system/controlDict": {"endTime": "10"}},
          ("paper-window", "HB+P"): {"system/demDict": {"youngModulusFactor": "1", "timeStep": "5e-7",
                                                        "settle": {"kineticTolerance": "1e-3"}},
                                     "constant/couplingProperties": {"exchangeEvery": "100"},
                                     "constant/sceneProperties": {"sample": {"width": "0.12"}}},
          ("truth", "B+P"): {"system/demDict": {"youngModulusFactor": "1", "timeStep": "auto",
                                                "settle": {"stiffenFrom": "1e-1"}},
                             "constant/couplingProperties": {"exchangeEvery": "27"},
                             "constant/sceneProperties": {"sample": {"width": "0.12"}}},
          ("truth", "P"): {"system/demDict": {"youngModulusFactor": "1e-3"}}}


def sub(d, want):
    return all(sub(d.get(k, {}), v) if isinstance(v, dict) else d.get(k) == v for k, v in want.items())


for name in ("paper", "reference", "quick", "paper-window", "truth"):
    tier = suite.Tier(name)
    for scene in suite.TABLE1:
        src = os.path.join(ROOT, "cases", scene)
        if not os.path.isdir(src):
            continue
        try:
            texts, recs = suite.tier_edits(src, tier, scene)
        except foamdict.DictError as e:
            check(False, f"tier {name} on {scene}: {e}")
            continue
        before = foamdict.read_dict(os.path.join(src, "constant", "sceneProperties"))
        after = foamdict.parse_dict(texts.get("constant/sceneProperties")
                                 or open(os.path.join(src, "constant", "sceneProperties")).read())
        same = all(before[b][k] == after[b][k] for b, k in
                   (("sample", "length"), ("sample", "height"), ("channel", "length"), ("channel", "height")))
        if not same:
            check(False, f"tier {name} on {scene} changed L, H or the channel")
        if (name, scene) in expect:
            parsed = {rel: foamdict.parse_dict(t) for rel, t in texts.items()}
            check(sub(parsed, expect[(name, scene)]), f"tier {name} on {scene} sets {expect[(name, scene)]}")
    check(True, f"tier {name} applies to every scene present")

# 4. The plan.
runs = os.path.join(work, "runs")
res = subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "suite.py"), "--tier", "quick",
                      "--scenes", "P-I-I", "--work", runs, "--dry-run"], capture_output=True, text=True)
print(res.stdout, res.stderr)
check(res.returncode == 0, "suite.py --dry-run exits 0")
check("[1/1] P-I-I (particles): fresh: ./Allrun 1" in res.stdout, "plan names the scene and command")
check("youngModulusFactor" in res.stdout and "1e-4" in res.stdout and "sample.width" in res.stdout,
      "plan lists the overrides")
check(not os.path.exists(runs), "--dry-run writes nothing")
res = subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "suite.py"), "--tier", "nosuch",
                      "--dry-run"], capture_output=True, text=True)
check(res.returncode != 0 and "no tier 'nosuch'" in res.stderr, "unknown tier refused")

# The run copy: inputs only, the tier applied, system/tier readable, a plan that resumes.
tier = suite.Tier("quick")
texts, recs = suite.tier_edits(os.path.join(ROOT, "cases", "P"), tier, "P")
copy_dir = os.path.join(work, "copy", "P")
suite.make_copy("P", copy_dir, tier, texts, recs, "particles")
rec = foamdict.read_dict(os.path.join(copy_dir, "system", "tier"))
check(rec["tier"] == "quick" and rec["overrides"]["system/demDict"]["youngModulusFactor"] == "1e-4",
      "system/tier records the tier and what it set")
check(foamdict.read_dict(os.path.join(copy_dir, "constant", "sceneProperties"))["sample"]["width"] == "0.072",
      "the copy has the tier's values")
check(sorted(os.listdir(copy_dir)) == ["Allrun", "constant", "system"], "only the inputs are copied")
check("../../scripts" not in open(os.path.join(copy_dir, "Allrun")).read().replace("${MIXFLOW_ROOT:-../..}", ""),
      "the copy's Allrun does not source scripts relative to cases/")
os.makedirs(os.path.join(copy_dir, "dem"))
open(os.path.join(copy_dir, "dem", "resume.state"), "w").close()
p = suite.plan_scene("P", os.path.join(work, "copy"), tier, 2)
check(p["status"] == "resume" and "-resume" in p["command"], "a dry copy with dem/resume.state resumes")
p = suite.plan_scene("P", os.path.join(work, "copy"), suite.Tier("reference"), 2)
check(p["status"] == "error" and "tier 'quick'" in p["error"], "a copy of another tier is refused")
open(os.path.join(copy_dir, ".done"), "w").close()
check(suite.plan_scene("P", os.path.join(work, "copy"), tier, 2)["status"] == "done", ".done is skipped")

# --set: a variant of a tier, applied after it (inserted if absent), recorded, and refused on a
# copy made without it; a malformed or unknown-file --set is refused.
var = suite.Tier("quick")
var.set_entries(["couplingProperties.dragIntegration=implicit",
                 "couplingProperties.dragFluidResponse=continuity", "demDict.youngModulusFactor=2e-4"])
texts, recs = suite.tier_edits(os.path.join(ROOT, "cases", "HB+P"), var, "HB+P")
var_dir = os.path.join(work, "variant", "HB+P")
suite.make_copy("HB+P", var_dir, var, texts, recs, "mixture")
cp = foamdict.read_dict(os.path.join(var_dir, "constant", "couplingProperties"))
check(cp["dragIntegration"] == "implicit" and cp["dragFluidResponse"] == "continuity",
      "--set replaces an entry and inserts a missing one")
check(foamdict.read_dict(os.path.join(var_dir, "system", "demDict"))["youngModulusFactor"] == "2e-4",
      "--set wins over the tier's own value")
rec = foamdict.read_dict(os.path.join(var_dir, "system", "tier"))
check(foamdict.unquote(rec["set"]) == var.set_text and
      rec["overrides"]["constant/couplingProperties"]["dragFluidResponse"] == "continuity",
      "system/tier records --set")
p = suite.plan_scene("HB+P", os.path.join(work, "variant"), suite.Tier("quick"), 1)
check(p["status"] == "error" and "--set" in p["error"], "a copy made with other --set is refused")
# bulkProperties, which a case may lack (every entry has a default), is created by --set.
bulk = suite.Tier("bulk")
bulk.set_entries(["bulkProperties.solidFraction=0.55", "bulkProperties.drifts.lambdaU=1.2"])
texts, recs = suite.tier_edits(os.path.join(ROOT, "cases", "HB+P"), bulk, "HB+P")
bulk_dir = os.path.join(work, "bulk-variant", "HB+P")
suite.make_copy("HB+P", bulk_dir, bulk, texts, recs, "mixture")
bp = foamdict.read_dict(os.path.join(bulk_dir, "constant", "bulkProperties"))
check(bp["solidFraction"] == "0.55" and bp["drifts"]["lambdaU"] == "1.2",
      "--set creates a mixture's bulkProperties with the entries and blocks it names")
check(not os.path.exists(os.path.join(ROOT, "cases", "HB+P", "constant", "bulkProperties")),
      "--set leaves cases/ alone")
# So is mixflowProperties (the fluid's switches, e.g. d(eps_f)/dt in continuity).
noddt = suite.Tier("quick")
noddt.set_entries(["mixflowProperties.continuityVoidfractionRate=off"])
texts, recs = suite.tier_edits(os.path.join(ROOT, "cases", "HB+P"), noddt, "HB+P")
noddt_dir = os.path.join(work, "noddt-variant", "HB+P")
suite.make_copy("HB+P", noddt_dir, noddt, texts, recs, "mixture")
mp = foamdict.read_dict(os.path.join(noddt_dir, "constant", "mixflowProperties"))
check(mp["continuityVoidfractionRate"] == "off",
      "--set creates a mixture's mixflowProperties with the entry it names")
for bad_set, words in (("couplingProperties.dragIntegration", "FILE.entry=VALUE"),
                       ("nosuchFile.x=1", "not a case file")):
    ok, msg = raises(lambda b=bad_set: suite.Tier("quick").set_entries([b]), *words.split("|"))
    check(ok, f"--set '{bad_set}' refused ({msg})")

# A mixture scene reuses a settled sample: --settled-from's (which must hold one), else, rerun
# after a failure, its own when that records a fingerprint; never for a dry scene.
other = os.path.join(work, "other")
os.makedirs(os.path.join(other, "HB+P", "dem"))
with open(os.path.join(other, "HB+P", "dem", "settled.state"), "w") as f:
    f.write('settled { particles 1; fingerprint "0123456789abcdef"; }\n')
p = suite.plan_scene("HB+P", os.path.join(work, "fresh"), suite.Tier("quick"), 1, other)
check(p["status"] == "fresh" and p["settled"] == os.path.join(other, "HB+P", "dem")
      and "reusing" in p["command"], "--settled-from: a fresh mixture copy reuses that sample")
p = suite.plan_scene("B+P", os.path.join(work, "fresh"), suite.Tier("quick"), 1, other)
check(p["status"] == "error" and "B+P/dem/settled.state" in p["error"],
      "--settled-from without that scene's sample is refused, naming the file")
check("settled" not in suite.plan_scene("P", os.path.join(work, "fresh"), suite.Tier("quick"), 1, other),
      "--settled-from leaves a dry scene alone")
own = os.path.join(work, "own")
os.makedirs(os.path.join(own, "HB+P", "dem"))
suite.make_copy("HB+P", os.path.join(own, "HB+P", "copy"), suite.Tier("quick"),
                *suite.tier_edits(os.path.join(ROOT, "cases", "HB+P"), suite.Tier("quick"), "HB+P"),
                "mixture")
for name in os.listdir(os.path.join(own, "HB+P", "copy")):
    shutil.move(os.path.join(own, "HB+P", "copy", name), os.path.join(own, "HB+P", name))
os.rmdir(os.path.join(own, "HB+P", "copy"))
state = os.path.join(own, "HB+P", "dem", "settled.state")
with open(state, "w") as f:
    f.write("settled { particles 1; }\n")
p = suite.plan_scene("HB+P", own, suite.Tier("quick"), 1)
check(p["status"] == "restart" and "settled" not in p, "a rerun settles again without a fingerprint")
with open(state, "w") as f:
    f.write('settled { particles 1; fingerprint "0123456789abcdef"; }\n')
p = suite.plan_scene("HB+P", own, suite.Tier("quick"), 1)
check(p["status"] == "restart" and p["settled"] == os.path.dirname(state),
      "a rerun reuses its own fingerprinted sample")
open(os.path.join(own, "HB+P", "dem", "coupled.resume.state"), "w").close()
p = suite.plan_scene("HB+P", own, suite.Tier("quick"), 1)
check(p["status"] == "resume" and "resumeMixtureCase" in " ".join(suite.resume_command("mixture", 1)),
      "a mixture copy with dem/coupled.resume.state resumes (resumeMixtureCase)")
# A run goes on to a later endTime asked by --set (the only difference): its copy is extended
# and resumed; an earlier endTime or any other difference is refused.
open(os.path.join(own, "HB+P", ".done"), "w").close()
end0 = suite.end_time(os.path.join(own, "HB+P"))
later = suite.Tier("quick")
later.set_entries([f"controlDict.endTime={2 * end0:g}"])
p = suite.plan_scene("HB+P", own, later, 1)
check(p["status"] == "resume" and p.get("extend_to") == 2 * end0 and "endTime ->" in p["command"],
      f"a finished run asked for endTime {2 * end0:g} s (was {end0:g}) resumes to it")
same = suite.Tier("quick")
same.set_entries([f"controlDict.endTime={end0:g}"])
check(suite.plan_scene("HB+P", own, same, 1)["status"] == "done", "the same endTime by --set is done")
check(suite._split_end("demDict.youngModulusFactor=1e-2 couplingProperties.exchangeEvery=10 "
                       "controlDict.endTime=1") ==
      suite._split_end("couplingProperties.exchangeEvery=10 controlDict.endTime=1 "
                       "demDict.youngModulusFactor=1e-2"),
      "the same --set entries in another order are the same run")
for sets, what in (([f"controlDict.endTime={0.5 * end0:g}"], "would shorten"),
                   ([f"controlDict.endTime={2 * end0:g}", "couplingProperties.exchangeEvery=3"],
                    "was made with --set")):
    t = suite.Tier("quick")
    t.set_entries(sets)
    p = suite.plan_scene("HB+P", own, t, 1)
    check(p["status"] == "error" and what in p["error"], f"--set {' '.join(sets)} refused ({what})")
suite.extend_run(os.path.join(own, "HB+P"), later, 2 * end0)
rec = foamdict.read_dict(os.path.join(own, "HB+P", "system", "tier"))
check(suite.end_time(os.path.join(own, "HB+P")) == 2 * end0
      and foamdict.unquote(rec["set"]) == later.set_text
      and float(rec["overrides"]["system/controlDict"]["endTime"]) == 2 * end0
      and not os.path.exists(os.path.join(own, "HB+P", ".done")),
      "the extended copy's controlDict and system/tier carry the new endTime, .done is gone")
p = suite.plan_scene("HB+P", own, later, 1)
check(p["status"] == "resume" and "extend_to" not in p, "the extended copy then resumes as any other")

# 6. Resume helpers.
csvp = os.path.join(work, "ts.csv")
with open(csvp, "w") as f:
    f.write("time_s,x\n0,1\n0.1,2\n0.2,3\n0.30000001,4\n")
check(suite.last_time(csvp) == 0.30000001, "last time of a CSV")
# A resumed run's solver CPU: each attempt appends its own ExecutionTime count from zero.
from types import SimpleNamespace  # noqa: E402
from mixflow import observables  # noqa: E402
cpu_dir = os.path.join(work, "cpu")
os.makedirs(cpu_dir, exist_ok=True)
with open(os.path.join(cpu_dir, "log.mixflowCoupled"), "w") as f:
    f.write("ExecutionTime = 10 s  ClockTime = 11 s\nExecutionTime = 250.5 s  ClockTime = 260 s\n"
            "resume\nExecutionTime = 3 s  ClockTime = 3 s\nExecutionTime = 100 s  ClockTime = 101 s\n")
check(observables.solver_cpu(SimpleNamespace(dir=cpu_dir)) == 350.5,
      "solver CPU sums a resumed run's attempts (250.5 + 100 s)")
os.makedirs(os.path.join(cpu_dir, "postProcessing", "coupling"))
with open(os.path.join(cpu_dir, "postProcessing", "coupling", "stageTimes.csv"), "w") as f:
    f.write("# wall s\ntime,demStep,dem,locate\n0.1,10,100,50\n0.2,20,80,20\n")
st = observables.stage_times(SimpleNamespace(dir=cpu_dir))
check(st == {"dem": 180, "locate": 70, "clock_s": 361, "fluid_and_rest": 111},
      f"stage times: each stage summed, the clock summed over attempts, the rest ({st})")
liq = os.path.join(work, "liq")
for t in ("0", "0.1", "0.2"):
    os.makedirs(os.path.join(liq, t, "uniform", "functionObjects"))
    if t != "0":
        open(os.path.join(liq, t, "uniform", "functionObjects", "functionObjectProperties"), "w").close()
os.makedirs(os.path.join(liq, "0.3"))  # written only in part: no function-object state
open(os.path.join(liq, "log.mixflowFoam"), "w").close()
check(suite.liquid_restart_time(liq, 1) == "0.2", "liquid restart from the latest complete time")
check(suite.liquid_restart_time(liq, 2) is None, "no restart without processor directories")

print(f"{len(failures)} failed" if failures else "all checks passed")
sys.exit(1 if failures else 0)
