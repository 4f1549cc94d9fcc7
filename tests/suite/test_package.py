#!/usr/bin/env python3
"""python/mixflow: the shared readers and helpers the result scripts and tests rely on (no simulation).

usage: test_package.py WORKDIR

Checks, each exact (the values are chosen so that the arithmetic is exact in binary):
  1. outputs: a value at a time interpolated between the rows around it (0.25 between 0 and 1 at
     a quarter of the interval), nan outside the series, the nearest row's value (the first of
     two as near), at() with an explicit method; read_series(comments=True) skips '#' lines;
  2. foamcase.set_entry: an existing top-level entry is set with the rest of the file kept byte for
     byte; an absent entry or a block stops with "cannot set KEY in PATH" (exit status 1);
  3. paper: the pure liquids' subcritical times are those of PAPER, '+' -> '&' in the paper's
     names; mixflow suite's DictError and TABLE1 are the package's (report.py catches
     suite.DictError);
  4. outputs.copy_inputs: of a case holding every kind of output a run leaves at its top level
     (postProcessing, VTK, dem, .done, .failed, log.*, previous-run.*, processor*, time
     directories other than 0, resume files) and inputs (Allrun, system/, constant/, 0/, 0.orig/,
     an output-like name inside system/ and 0/), exactly the inputs are copied; keep=("dem",
     "log.mixflowDem") takes dem/ along without its resume state and log, and that one log; an
     existing DST stops the copy (FileExistsError);
  5. the installed package is this checkout's (`import mixflow` from anywhere: mixflow.ROOT), and
     `mixflow --help` and `mixflow VERB --help` of every verb exit 0;
  6. mixflow.schema: the declarations of `mixflowSchema -json` ($MIXFLOW_BUILD) name every
     dictionary file, each default lies in its declared range or words (none where the default
     is required, auto or taken from elsewhere: defaultNote), an entry a dictionary
     does not set takes the declared default (suite's cost estimate with and without
     sample.solidFraction), and a build without mixflowSchema stops with SchemaError;
  7. observables.deposit_tail: on an end profile (bins of d = 0.024 m, L = 0.6 m) whose body
     (packed depth 3 d) ends at 41 d = 0.984 m and whose 4-bin sheet ahead holds d/4 of packed depth
     under column tops of 2 d, the volume front is 0.984 m, the column-top front 45 d = 1.08 m, and
     the sheet's share of the grain volume is (4 x 1/4) / (41 x 3 + 4 x 1/4) = 1/124;
     observables.liquid_over_gate: on four cells of volume 0.5 m3 (x 0.3 / 0.9, y 0.1 / 0.5;
     L = 0.6, H = 0.6) with liquid fractions 1 and void fractions 0.5 / 0.25 at one write, the
     liquid over the gate is the one cell beyond L above H/2: 1 x 0.25 x 0.5 = 0.125 m3;
  8. froude.subcritical_from: rows every 0.05 s to 1 s with Fr 1.5 to 0.3 s, 0.8 at 0.35-0.4 s,
     1.2 at 0.45 s and 0.8 from 0.5 s: the flow turns subcritical at 0.5 s (the dip at 0.35 s
     does not hold for 0.2 s); with Fr 0.8 from 0.9 s only, at 0.9 s (the run's end within the
     hold); never below 1: None;
  9. record.record_scene: of a finished case whose liquid series has a row every 0.5 ms to 1 s
     (front 0.6 + t/5) and a last row cut short, the record keeps 501 rows 2 ms apart ending at
     1 s with their values (7 digits), the snapshots nearest 0.63 and 0.75 s (of 0, 0.62, 0.76,
     0.9 s) with at most two grains per 0.024 m bin and the same granular surface as the full
     snapshot of 3 000 random grains, the deposit whole, not the mesh, and record.json; Scene
     reads it as a finished truth-tier scene with the suite's --set entries; an unfinished case is
     refused and nothing written;
 10. observables.convergence_error (a partner's value minus the run's): scalars, the floats of a
     dict one level down (a drift's median and quantiles, not its bin count), lists of numbers of
     equal length; a series of dicts, None and unequal lists give nothing;
 11. the report's rows with a partner: a row naming B&P gets the partner's value and the
     difference; HB&P's rows (whose name holds "B&P") and rows naming no partner keep none.
"""
import io
import json
import math
import os
import shutil
import subprocess
import sys
from contextlib import redirect_stdout

import numpy as np

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
import mixflow  # noqa: E402
from mixflow.commands import suite  # noqa: E402
from mixflow import cli, foamcase, foamdict, froude, observables, outputs, paper, record, schema  # noqa: E402
from mixflow.synthcase import checker  # noqa: E402

failures = []
check = checker(failures)

work = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else "/tmp/test_package")
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)

# 1. outputs
path = os.path.join(work, "timeSeries.csv")
with open(path, "w") as f:
    f.write("# a comment line\ntime_s,front_bed_m\n0,0\n1,1\n2,4\n")
rows = outputs.read_series(path, comments=True)
check(rows == [{"time_s": 0.0, "front_bed_m": 0.0}, {"time_s": 1.0, "front_bed_m": 1.0},
               {"time_s": 2.0, "front_bed_m": 4.0}], "read_series(comments=True): three rows of floats")
check(outputs.interpolated(rows, "front_bed_m", 0.25) == 0.25, "interpolated at t = 0.25: 0.25")
check(outputs.interpolated(rows, "front_bed_m", 1.5) == 2.5, "interpolated at t = 1.5: 2.5")
check(math.isnan(outputs.interpolated(rows, "front_bed_m", 3.0)), "interpolated after the end: nan")
check(outputs.nearest(rows, "front_bed_m", 1.4) == 1.0, "nearest at t = 1.4: the row at 1 s")
check(outputs.nearest(rows, "front_bed_m", 1.5) == 1.0, "nearest at t = 1.5: the first of two as near")
check(outputs.nearest(rows, "front_bed_m", 9.0) == 4.0, "nearest after the end: the last row")
check(outputs.at(rows, "front_bed_m", 1.5, "interpolate") == 2.5
      and outputs.at(rows, "front_bed_m", 1.5, "nearest") == 1.0, "at() with either method")

# 2. foamcase.set_entry
ctrl = os.path.join(work, "controlDict")
text = ("FoamFile { version 2.0; format ascii; class dictionary; object controlDict; }\n"
        "endTime         1;   // the end\nwriteInterval   0.05;\nfunctions\n{\n    endTime 7;\n}\n")
with open(ctrl, "w") as f:
    f.write(text)
foamcase.set_entry(ctrl, "endTime", 0.4)
with open(ctrl) as f:
    got = f.read()
check(got == text.replace("endTime         1;", "endTime         0.4;", 1),
      "set_entry: the top-level value set, the nested entry and the comment kept")
for key in ("startTime", "functions"):
    out = io.StringIO()
    try:
        with redirect_stdout(out):
            foamcase.set_entry(ctrl, key, 1)
        status = 0
    except SystemExit as e:
        status = e.code
    check(status == 1 and f"cannot set {key} in {ctrl}" in out.getvalue(),
          f"set_entry of {key} ({'absent' if key == 'startTime' else 'a block'}) stops with status 1")

# 3. paper and the names mixflow suite takes from the package
check(paper.PAPER_SUBCRITICAL == {"W": 1.2, "HB": 1.1, "B": 1.0}
      and all(paper.PAPER["subcritical"][k] == v for k, v in paper.PAPER_SUBCRITICAL.items()),
      "paper: the pure liquids' subcritical times")
check(paper.PAPER_NAME["HB+P"] == "HB&P" and len(paper.TABLE1) == 14, "paper: Table 1's 14 scenes")
check(suite.DictError is foamdict.DictError and suite.TABLE1 is paper.TABLE1
      and suite.read_dict is foamdict.read_dict, "suite.py uses the package's reader and scene list")

# 4. outputs.copy_inputs
case = os.path.join(work, "case")
INPUTS = ["Allrun", "system/controlDict", "system/log.notes", "constant/sceneProperties",
          "constant/polyMesh/points", "0/U", "0/dem/keep", "0.orig/U"]
SAMPLE = ["dem/settled.state", "dem/settled.restart", "dem/screen.liggghts"]
RUN_STATE = ["dem/resume.state", "dem/restart_0.bin", "dem/coupled.resume.state",
             "dem/coupled_1.restart", "dem/log.liggghts"]
OUTPUTS = ["postProcessing/dem/timeSeries.csv", "VTK/particles_0.vtk", ".done", ".failed",
           "log.mixflowDem", "log.mixflowCoupled", "previous-run.20250101-120000/log.mixflowDem",
           "processor0/0.1/U", "processor1/constant/polyMesh/points", "0.1/U", "1e-05/U", "10/U",
           "coupled.resume.state", "restart_1.bin"]
for rel in INPUTS + SAMPLE + RUN_STATE + OUTPUTS:
    os.makedirs(os.path.dirname(os.path.join(case, rel)), exist_ok=True)
    with open(os.path.join(case, rel), "w") as f:
        f.write(rel + "\n")


def files(d):
    return sorted(os.path.relpath(os.path.join(r, n), d) for r, _, ns in os.walk(d) for n in ns)


got = files(outputs.copy_inputs(case, os.path.join(work, "inputs")))
check(got == sorted(INPUTS), "copy_inputs: the inputs, none of the outputs"
      + ("" if got == sorted(INPUTS) else f" (copied {sorted(set(got) ^ set(INPUTS))} wrongly)"))
with open(os.path.join(work, "inputs", "0", "U")) as f:
    check(f.read() == "0/U\n", "copy_inputs: a file's content copied")
want = sorted(INPUTS + SAMPLE + ["log.mixflowDem"])
got = files(outputs.copy_inputs(case, os.path.join(work, "kept"), keep=("dem", "log.mixflowDem")))
check(got == want, "copy_inputs keep=(dem, log.mixflowDem): dem/'s sample without its resume state "
      "and log, and that one log"
      + ("" if got == want else f" (wrong: {sorted(set(got) ^ set(want))})"))
got = files(outputs.copy_inputs(case, os.path.join(work, "logs"), keep=("log.*",)))
check(got == sorted(INPUTS + ["log.mixflowDem", "log.mixflowCoupled"]),
      "copy_inputs keep=(log.*,): a pattern keeps the top-level logs")
try:
    outputs.copy_inputs(case, os.path.join(work, "inputs"))
    raised = False
except FileExistsError:
    raised = True
check(raised, "copy_inputs into an existing directory: FileExistsError")
check(not hasattr(suite, "OUTPUT_NAMES"), "mixflow suite has no output list of its own")

# 5. the installed package and its command
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
check(os.path.samefile(mixflow.ROOT, ROOT), f"import mixflow: this checkout's package ({mixflow.ROOT}; "
      "another checkout's is installed when not: run scripts/build.sh here)")
for verb in [None, "bench"] + list(cli.VERBS):
    args = ["--help"] if verb is None else [verb, "--help"]
    r = subprocess.run(cli.command(*args), capture_output=True, text=True, cwd="/")
    check(r.returncode == 0 and "usage" in r.stdout,
          f"mixflow {' '.join(args)}: exit {r.returncode}" + (f" ({r.stderr.strip()[-200:]})" if r.returncode else ""))

# 6. mixflow.schema: the C++ declarations
decl = schema.declarations()
check(set(decl) >= {"constant/sceneProperties", "system/demDict", "system/cfdDict",
                    "constant/mixflowProperties", "constant/couplingProperties",
                    "constant/bulkProperties", "system/extractDict"}, f"schema: files {sorted(decl)}")
bad = []
for file, entries in decl.items():
    for entry, p in entries.items():
        d, r = p["default"], p.get("range")
        if p["type"] in ("scalar", "integer") and d is not None:
            lo = -math.inf if r["lo"] is None else r["lo"]
            hi = math.inf if r["hi"] is None else r["hi"]
            if not ((lo < d if r["loOpen"] else lo <= d) and (d < hi if r["hiOpen"] else d <= hi)):
                bad.append(f"{file} {entry} {d} {r}")
        if p["type"] == "word" and d is not None and p["words"] and d not in p["words"]:
            bad.append(f"{file} {entry} {d} {p['words']}")
check(not bad and sum(map(len, decl.values())) > 100,
      f"schema: {sum(map(len, decl.values()))} entries, every default in its range or words {bad}")
phi = schema.default("constant/sceneProperties", "sample.solidFraction")
scene = ("sample { length 0.2; height 0.1; width 0.05; %s}\nchannel { length 1; height 0.3; }\n"
         "particles { diameter 0.004; }\n")
sizes = []
for extra in ("", f"solidFraction {phi!r}; "):
    case = os.path.join(work, "schema_case" + str(len(sizes)))
    os.makedirs(os.path.join(case, "constant"))
    with open(os.path.join(case, "constant", "sceneProperties"), "w") as f:
        f.write(scene % extra)
    sizes.append(suite.scene_size(case, {}, "particles")["particles"])
check(sizes[0] == sizes[1] and 0 < phi < 1, f"an absent solidFraction is the declared {phi}: "
      f"{sizes[0]:.6g} particles both")
empty = os.path.join(work, "no_build")
os.makedirs(empty)
r = subprocess.run([sys.executable, "-c", "from mixflow import schema; schema.declarations()"],
                   capture_output=True, text=True, env=dict(os.environ, MIXFLOW_BUILD=empty))
check(r.returncode != 0 and "SchemaError: mixflowSchema not found in " + empty in r.stderr,
      f"no mixflowSchema in MIXFLOW_BUILD: SchemaError ({r.stderr.strip().splitlines()[-1]})")

# 7. observables.deposit_tail
case = os.path.join(work, "deposit", "HB+P")
os.makedirs(os.path.join(case, "constant"))
os.makedirs(os.path.join(case, "postProcessing", "dem"))
open(os.path.join(case, ".done"), "w").write("{}")
with open(os.path.join(case, "constant", "sceneProperties"), "w") as f:
    f.write("content mixture;\nsample { length 0.6; height 0.6; width 0.12; }\n")
d = paper.D_P
with open(os.path.join(case, "postProcessing", "dem", "depositProfile.csv"), "w") as f:
    f.write("x_m,h_top_m,h_volume_m,time_s\n")
    for i in range(60):  # bins 0..40: the body; 41..44: the sheet; then empty
        h_top, h_vol = (3 * d, 3 * d) if i <= 40 else (2 * d, d / 4) if i <= 44 else (0, 0)
        f.write(f"{(i + 0.5) * d!r},{h_top!r},{h_vol!r},0.3\n")
tail = observables.deposit_tail(observables.Scene(os.path.dirname(case), "HB+P"))
check(tail is not None and abs(tail["volume_front_m"] - 41 * d) < 1e-12
      and abs(tail["top_front_m"] - 45 * d) < 1e-12
      and abs(tail["volume_beyond_volume_front"] - 1 / 124) < 1e-12,
      f"deposit_tail: volume front 41 d, column-top front 45 d, sheet share 1/124 ({tail})")

scalars = lambda vals: f"dimensions [0 0 0 0 0 0 0];\ninternalField {foamcase.format_scalar_list(vals)};\n"
for name, vals in (("Cx", [0.3, 0.9, 0.3, 0.9]), ("Cy", [0.1, 0.1, 0.5, 0.5]), ("V", [0.5] * 4)):
    foamcase.write_foam_file(case, f"0/{name}", "volScalarField", name, scalars(vals))
foamcase.write_foam_file(case, "0.03/alpha.liquid", "volScalarField", "alpha.liquid", scalars([1.0] * 4))
foamcase.write_foam_file(case, "0.03/voidfraction", "volScalarField", "voidfraction",
                         scalars([0.5, 0.5, 0.5, 0.25]))
over = observables.liquid_over_gate(observables.Scene(os.path.dirname(case), "HB+P"))
check(over == {"0.03": 0.125}, f"liquid_over_gate: 0.125 m3 at 0.03 s ({over})")

# 8. froude.subcritical_from
ts = [round(0.05 * k, 2) for k in range(21)]
fr = lambda t: 1.5 if t <= 0.3 else 0.8 if t <= 0.4 else 1.2 if t <= 0.45 else 0.8
got = [froude.subcritical_from([{"time_s": t, "section_froude": f(t)} for t in ts], 0)
       for f in (fr, lambda t: 0.8 if t >= 0.9 else 1.5, lambda t: 1.5)]
check(got == [0.5, 0.9, None], f"subcritical_from: 0.5 s, 0.9 s at the run's end, None ({got})")

# 9. record.record_scene
case = os.path.join(work, "record_src", "HB+P")
shutil.copytree(os.path.join(work, "deposit", "HB+P"), case)
os.makedirs(os.path.join(case, "system"))
os.makedirs(os.path.join(case, "postProcessing", "liquid"))
os.makedirs(os.path.join(case, "constant", "polyMesh"))
open(os.path.join(case, "system", "tier"), "w").write(
    'tier truth;\ncontent mixture;\nset "couplingProperties.exchangeEvery=3";\n')
with open(os.path.join(case, outputs.LIQUID_SERIES), "w") as f:  # every 0.5 ms over 1 s
    f.write("time_s,front_bed_m\n" + "".join(f"{k * 5e-4!r},{0.6 + k * 1e-4!r}\n" for k in range(2001))
            + "1.0005,0.8")  # a row cut short by a stopped run
rng = np.random.default_rng(3)
pts = np.column_stack([rng.uniform(-0.1, 4.2, 3000), rng.uniform(0, 0.5, 3000), rng.uniform(0, 0.12, 3000)])
os.makedirs(os.path.join(case, "VTK", "particles"))
names = [("particles/particles_0.vtk", 0.0), ("particles/particles_7.vtk", 0.62),
         ("particles/particles_8.vtk", 0.76), ("particles/particles_9.vtk", 0.9)]
for name, _ in names:
    record.write_surface_snapshot(os.path.join(case, "VTK", name), pts)
with open(os.path.join(case, outputs.SNAPSHOT_SERIES), "w") as f:
    json.dump({"files": [{"name": n, "time": t} for n, t in names]}, f)
rec = os.path.join(work, "records")
sizes = record.record_scene(case, os.path.join(rec, "HB+P"))
liq = outputs.read_rows(os.path.join(rec, "HB+P", outputs.LIQUID_SERIES))
times = [r["time_s"] for r in liq]
check(len(liq) == 501 and times[0] == 0 and times[-1] == 1.0
      and all(abs(b - a - 0.002) < 1e-9 for a, b in zip(times, times[1:])),
      f"record: the liquid series every 2 ms with its last row, the cut row left out ({len(liq)} rows)")
check(all(abs(r["front_bed_m"] - (0.6 + r["time_s"] / 5)) < 1e-6 for r in liq),
      "record: the kept rows' values (7 significant digits)")
snaps = observables.vtk_series(os.path.join(rec, "HB+P"))
surf = observables.granular_surface(observables.vtk_points(os.path.join(case, "VTK", names[1][0])), 4.0)[1]
check([t for t, _ in snaps] == [0.62, 0.76] and all(
      np.array_equal(observables.granular_surface(observables.vtk_points(p), 4.0)[1], surf, equal_nan=True)
      and len(observables.vtk_points(p)) <= 2 * 167 for _, p in snaps),
      f"record: the snapshots nearest 0.63 and 0.75 s, at most two grains a bin, the same surface ({snaps})")
sc = observables.Scene(rec, "HB+P")
check(sc.done and sc.tier == "truth" and sc.tier_set == "couplingProperties.exchangeEvery=3"
      and sc.deposit == observables.Scene(os.path.dirname(case), "HB+P").deposit
      and "constant/polyMesh" not in sizes and "record.json" in sizes,
      "record: a finished Scene of its tier, the deposit whole, no mesh, record.json")
os.remove(os.path.join(case, ".done"))
try:
    record.record_scene(case, os.path.join(rec, "x"))
    refused = ""
except ValueError as e:
    refused = str(e)
check("not a finished run" in refused and not os.path.exists(os.path.join(rec, "x")),
      f"record: an unfinished run is refused ({refused})")

run = {"e": 1.0, "lambda_u": {"median": 1.25, "p10": 0.5, "bins": 40}, "w": [1.0, 2.0],
       "basal": [{"excess_Pa": -1.0}], "none": None, "short": [1.0]}
partner = {"e": 1.5, "lambda_u": {"median": 1.0, "p10": 0.75, "bins": 38}, "w": [1.5, 1.0],
           "basal": [{"excess_Pa": -2.0}], "none": 2.0, "short": [1.0, 2.0]}
err = observables.convergence_error(run, partner)
check(err == {"e": 0.5, "lambda_u": {"median": -0.25, "p10": 0.25}, "w": [0.5, -1.0]},
      f"convergence_error: partner minus run where both have numbers ({err})")

from mixflow.commands import report  # noqa: E402
rows = [report.row(q, 1.0, 2.0, "truth", True, note) for q, note in (
    ("B&P: front (m)", ""), ("HB&P: front (m)", ""), ("front order", "HB&P 0.9 m, P 2.0 m"),
    ("Savage ordering", "B&P 0.001, HB&P 0.002"))]
finer = [dict(r, ours=2.5) for r in rows]
got = {r["quantity"]: r.get("convergence_error") for r in report.with_partner(rows, finer, ["B&P"])}
check(got == {"B&P: front (m)": 0.5, "HB&P: front (m)": None, "front order": None,
              "Savage ordering": 0.5}, f"report: rows naming B&P get its partner, HB&P's not ({got})")

print(f"{len(failures)} failed" if failures else "all checks passed")
sys.exit(1 if failures else 0)
