#!/usr/bin/env python3
"""Benchmark (issue 4): the coupled HB&P scene against the dry P scene with the same particles and
DEM settings: CPU-time ratio of the collapse, and the coupled run's split between DEM (inside
LIGGGHTS runs), coupling (exchanges: locate, void fraction, forces, source) and fluid (the rest).
Target: coupled <= 1.3 x dry.

The scene is cases/W+P-quick with the Herschel-Bulkley liquid of case HB (813 grains, 2-D fluid at
0.06 m, 1.5 s) -- a quick-size HB&P; the dry twin is the same scene with content particles. Both
settle the same sample (same seed); the settling is timed separately and left out of both.

usage: coupled_vs_dry.py [--end 1.0] [--json OUT] [--bin build/bin]
CPU seconds (user + sys of the programs) are compared: wall time also counts waiting for a core."""
import argparse
import csv
import json
import os
import re
import shutil
import sys
import tempfile

sys.dont_write_bytecode = True
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import suite  # noqa: E402  (OpenFOAM-style dictionary editor)
from dem_driver_vs_liggghts import timed as _timed  # noqa: E402


def timed(cmd, cwd):
    """(wall s, CPU s of the command and its children, stdout)."""
    return _timed(cmd, cwd, with_output=True)


def set_entry(path, key, value):
    """Sets a top-level entry with the suite's dictionary editor (scripts/suite.py)."""
    text, _ = suite.edit_dict(open(path).read(), {key: value}, note="bench")
    open(path, "w").write(text)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--end", type=float, default=1.0)
    ap.add_argument("--json")
    ap.add_argument("--bin", default=os.path.join(ROOT, "build", "bin"))
    a = ap.parse_args()
    work = tempfile.mkdtemp(prefix="mixflow-bench-cpl-")
    env_path = a.bin + os.pathsep + os.environ["PATH"]
    os.environ["PATH"] = env_path
    os.environ.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")
    os.environ["MIXFLOW_ROOT"] = ROOT

    # The coupled scene: W+P-quick with case HB's liquid.
    cpl = os.path.join(work, "HB+P-quick")
    shutil.copytree(os.path.join(ROOT, "cases", "W+P-quick"), cpl,
                    ignore=shutil.ignore_patterns("postProcessing", "VTK", "dem", "log.*", "0",
                                                  "processor*", "[0-9]*"))
    sp = os.path.join(cpl, "constant", "sceneProperties")
    text = open(sp).read()
    hb = open(os.path.join(ROOT, "cases", "HB", "constant", "sceneProperties")).read()
    text = text[:text.index("liquid   //")] + hb[hb.index("liquid   //"):]
    open(sp, "w").write(text)
    set_entry(os.path.join(cpl, "system", "controlDict"), "endTime", repr(a.end))
    # The dry twin: same particles, walls, DEM settings; no liquid.
    dry = os.path.join(work, "P-twin")
    os.makedirs(os.path.join(dry, "constant"))
    os.makedirs(os.path.join(dry, "system"))
    dtext = text[:text.index("liquid   //")].replace("content mixture;", "content particles;")
    open(os.path.join(dry, "constant", "sceneProperties"), "w").write(dtext)
    for f in ("demDict", "controlDict"):
        shutil.copy(os.path.join(cpl, "system", f), os.path.join(dry, "system", f))

    mf = lambda p: os.path.join(a.bin, p)  # noqa: E731
    w_settle, c_settle, _ = timed([mf("mixflowDem"), "-case", cpl, "-settleOnly"], cpl)
    timed([mf("mixflowPrepare"), "-case", cpl], cpl)
    timed(["blockMesh", "-case", cpl], cpl)
    w_cpl, c_cpl, out = timed([mf("mixflowCoupled"), "-case", cpl], cpl)
    w_dry_all, c_dry_all, _ = timed([mf("mixflowDem"), "-case", dry], dry)
    c_dry = c_dry_all - c_settle  # the same settling (same seed, same commands)
    m = re.search(r"inside LIGGGHTS runs ([0-9.eE+-]+) s", out)
    dem_s = float(m.group(1)) if m else float("nan")
    with open(os.path.join(cpl, "postProcessing", "coupling", "exchange.csv")) as f:
        rows = list(csv.DictReader(ln for ln in f if not ln.startswith("#")))
    coupling_s = sum(float(r["seconds"]) for r in rows)
    summ = json.load(open(os.path.join(cpl, "postProcessing", "dem", "summary.json")))
    fluid_s = w_cpl - dem_s - coupling_s
    res = {
        "scene": "W+P-quick geometry with case HB's liquid (813 grains, 2-D fluid 0.06 m)",
        "simulated_s": a.end, "particles": summ["settled"]["particles"],
        "settle_cpu_s": c_settle,
        "dry_collapse_cpu_s": c_dry, "coupled_cpu_s": c_cpl,
        "ratio_coupled_over_dry": c_cpl / c_dry, "target_ratio": 1.3,
        "coupled_wall_s": w_cpl, "coupled_split_wall_s": {
            "dem_inside_liggghts": dem_s, "coupling_exchanges": coupling_s, "fluid_and_rest": fluid_s},
        "command": "python3 bench/coupled_vs_dry.py" + (f" --end {a.end}" if a.end != 1.0 else ""),
    }
    print(json.dumps(res, indent=2))
    if a.json:
        with open(a.json, "w") as f:
            json.dump(res, f, indent=2)
            f.write("\n")
    shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
