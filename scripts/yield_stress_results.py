#!/usr/bin/env python3
"""results/yield_stress/: the drag-viscosity closures against the single-grain references, and
the quick HB&P and B&P under the verified default and under the paper-faithful variants.

usage: python3 scripts/yield_stress_results.py [--work runs/yield_stress] [--out results/yield_stress]
                                               [--skip-grains] [--skip-mixtures]

1. Single grain (tests/coupling/run_yield_sphere.py, the coupling.yield_sphere.* tests) with
   each closure: its settling speed in the paper's Bingham liquid, in the paper's HB liquid, and
   in Bingham liquids at Y = 0.12 and 0.20; each check's measured value, reference, error,
   tolerance and verdict go to summary.json "closures".
2. Mixtures at the quick tier (`suite.py --tier quick --scenes HB+P,B+P,W+P`), then variants of
   HB+P and B+P on the same settled samples (a copy of the run, its dictionaries edited with
   suite.edit_dict, `./Allrun 1 dem`):
     default       dragViscosity auto (slip for these liquids), implicit drag, d(eps)/dt on
     resolved      dragViscosity resolved (the cell's capped viscosity)
     slip_noddt    the default without d(eps_f)/dt in continuity (mixflowProperties
                   continuityVoidfractionRate off)
     held          resolved with the force held over the exchange interval (dragIntegration
                   held, whose dragRelaxationLimit bounds beta <= 0.5 m / T)
     paper         the paper's scheme as far as it is known: resolved, the force held over the
                   exchange interval (dragIntegration held), d(eps_f)/dt off; cap 1e4 Pa s
     paper_cap1e3, paper_cap1e2   the same with viscosityCap 1e3 and 1e2 Pa s (the nu0 sweep)
   Observables at 1.5 s: the granular front, the grains' potential energy released, the liquid
   front, the back-wall surface height / H at 0.5 and 1.0 s (the paper's HB&P: 0.997 -> 0.894),
   and the mean share of grains whose held drag the dragRelaxationLimit bounded (exchange.csv).
   variants.csv and summary.json "paper_faithful". A variant whose log ends with "End" is not
   run again (delete WORK/variants/<scene>-<variant> to redo it).
3. With --packing F:MU,... (e.g. 0.58:0.3,0.56:0.7): W+P and HB+P at the reference tier with
   sample.solidFraction F and the settling friction settle.friction MU (`suite.py --tier
   reference --set sceneProperties.sample.solidFraction=F --set demDict.settle.friction=MU`,
   WORK/packing-F-MU): the target fraction only sets the grain count, the settling friction sets
   the packing (0.1, the default, settles to about 0.61). Against the reference-tier runs in
   --reference-work: the settled sample fraction, fronts at 3 s and the grains' released energy;
   summary.json "packing", packing.csv.
"""

import argparse
import csv
import json
import math
import os
import re
import shutil
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
sys.dont_write_bytecode = True
import suite  # noqa: E402

H = 0.6  # the paper's column height (m)
VARIANTS = {
    "default": {},
    "resolved": {"couplingProperties": {"DiFeliceDragCoeffs": {"dragViscosity": "resolved"}}},
    "slip_noddt": {"mixflowProperties": {"continuityVoidfractionRate": "off"}},
    "held": {"couplingProperties": {"DiFeliceDragCoeffs": {"dragViscosity": "resolved"},
                                    "dragIntegration": "held"}},
    "paper": {"couplingProperties": {"DiFeliceDragCoeffs": {"dragViscosity": "resolved"},
                                     "dragIntegration": "held"},
              "mixflowProperties": {"continuityVoidfractionRate": "off"}},
    "paper_cap1e3": {"couplingProperties": {"DiFeliceDragCoeffs": {"dragViscosity": "resolved"},
                                            "dragIntegration": "held"},
                     "mixflowProperties": {"continuityVoidfractionRate": "off"},
                     "sceneProperties": {"liquid": {"viscosityCap": "1e3"}}},
    "paper_cap1e2": {"couplingProperties": {"DiFeliceDragCoeffs": {"dragViscosity": "resolved"},
                                            "dragIntegration": "held"},
                     "mixflowProperties": {"continuityVoidfractionRate": "off"},
                     "sceneProperties": {"liquid": {"viscosityCap": "1e2"}}},
}
FILES = {"couplingProperties": "constant/couplingProperties",
         "sceneProperties": "constant/sceneProperties",
         "mixflowProperties": "constant/mixflowProperties"}


def run(cmd, cwd=ROOT, env=None):
    print("+ " + " ".join(cmd), flush=True)
    r = subprocess.run(cmd, cwd=cwd, env=env, capture_output=True, text=True)
    if r.returncode != 0:
        print(r.stdout[-3000:] + r.stderr[-3000:])
    return r


def grain_checks(work, build):
    """Runs the single-grain scenarios with both closures; returns summary["closures"]."""
    out = {"slip": {"checks": {}}, "resolved": {"checks": {}}}
    env = dict(os.environ, WM_PROJECT_DIR=os.environ.get("WM_PROJECT_DIR", "/usr/share/openfoam"))
    for liquid in ("bingham", "hb", "threshold"):
        r = run([sys.executable, os.path.join(ROOT, "tests/coupling/run_yield_sphere.py"),
                 "--solver", os.path.join(build, "bin/mixflowCoupled"), "--blockmesh", "blockMesh",
                 "--reference", os.path.join(ROOT, "tests/reference"), "--workdir",
                 os.path.join(work, "grains"), "--liquid", liquid, "--also-resolved"], env=env)
        text = r.stdout
        speeds = {(m.group(1), m.group(2)): float(m.group(3)) for m in re.finditer(
            r"^\s+(\S+), dragViscosity (\w+): settling speed (\S+) m/s", text, re.M)}
        if liquid == "bingham":
            ref = float(re.search(r"reference speed (\S+) m/s", text).group(1))
            for cl in out:
                v = speeds[("bingham", cl)]
                out[cl]["checks"]["bingham_settling_speed"] = {
                    "measured": v, "reference": ref, "error": v / ref - 1, "tolerance": 0.1,
                    "passes": abs(v / ref - 1) <= 0.1, "unit": "m/s",
                    "reference_source": "Ansley & Smith creeping Bingham drag x Di Felice "
                                        "finite-Re factor (tests/reference/bingham_sphere.csv)"}
        elif liquid == "hb":
            free = float(re.search(r"settles at (\S+) m/s", text).group(1))
            for cl in out:
                v = speeds[("hb", cl)]
                out[cl]["checks"]["hb_held"] = {
                    "measured": v, "reference": 0.0, "error": v / free, "tolerance": 1e-3,
                    "passes": abs(v) <= 1e-3 * free, "unit": "m/s",
                    "reference_source": "Beris et al. 1985: held for Y > 0.143 (Y = 0.255); "
                                        "error = speed / speed without the yield stress"}
        else:
            free = float(re.search(r"tau_y = 0 speed (\S+) m/s", text).group(1))
            for cl in out:
                lo, hi = speeds[("Y0.12", cl)], speeds[("Y0.2", cl)]
                out[cl]["checks"]["threshold_Y0.12_settles"] = {
                    "measured": lo, "reference": free, "error": lo / free, "tolerance": 0.1,
                    "passes": lo >= 0.1 * free, "unit": "m/s",
                    "reference_source": "Beris et al. 1985: settles for Y < 0.143; error = "
                                        "speed / speed without the yield stress (>= tolerance)"}
                out[cl]["checks"]["threshold_Y0.20_held"] = {
                    "measured": hi, "reference": 0.0, "error": hi / free, "tolerance": 1e-3,
                    "passes": abs(hi) <= 1e-3 * free, "unit": "m/s",
                    "reference_source": "Beris et al. 1985: held for Y > 0.143"}
    return out


def series(path):
    with open(path) as f:
        return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]


def at(rows, key, t):
    return min(rows, key=lambda r: abs(r["time_s"] - t))[key]


def observables(run_dir):
    dem = series(os.path.join(run_dir, "postProcessing/dem/timeSeries.csv"))
    liq = series(os.path.join(run_dir, "postProcessing/liquid/timeSeries.csv"))
    with open(os.path.join(run_dir, "postProcessing/coupling/exchange.csv")) as f:
        ex = [{k: float(v) for k, v in r.items()}
              for r in csv.DictReader(line for line in f if not line.startswith("#"))]
    limited = sum(r["dragLimited"] / r["particles"] for r in ex) / len(ex)
    return {"simulated_to_s": dem[-1]["time_s"],
            "drag_limited_share": limited,
            "granular_front_m": dem[-1]["front_x_m"],
            "grain_pe_released_J": dem[0]["pe_J"] - dem[-1]["pe_J"],
            "grain_pe_initial_J": dem[0]["pe_J"],
            "liquid_front_m": liq[-1]["front_bed_m"],
            "back_wall_surface_0.5s_H": at(liq, "back_wall_surface_m", 0.5) / H,
            "back_wall_surface_1.0s_H": at(liq, "back_wall_surface_m", 1.0) / H}


def variant(base, dst, edits):
    """A copy of the finished run BASE with its settled sample and edited dictionaries."""
    shutil.rmtree(dst, ignore_errors=True)
    keep = shutil.ignore_patterns("postProcessing", "VTK", "log.*", "processor*", ".done",
                                  "previous-run.*", "coupled.resume.state", "restart_*")
    shutil.copytree(base, dst, ignore=keep)
    for d in os.listdir(dst):
        if re.fullmatch(r"[0-9.eE+-]+", d) and d != "0":
            shutil.rmtree(os.path.join(dst, d))
    for fkey, tree in edits.items():
        path = os.path.join(dst, FILES[fkey])
        if not os.path.exists(path):
            with open(path, "w") as f:
                f.write("FoamFile { version 2.0; format ascii; class dictionary; "
                        f"object {os.path.basename(path)}; }}\n")
        with open(path) as f:
            text = f.read()
        new, _ = suite.edit_dict(text, tree, note="yield_stress_results", create_blocks=True)
        with open(path, "w") as f:
            f.write(new)


def mixtures(work):
    quick = os.path.join(work, "quick")
    r = run([sys.executable, os.path.join(ROOT, "scripts/suite.py"), "--tier", "quick",
             "--scenes", "HB+P,B+P,W+P", "--work", quick])
    if r.returncode != 0:
        sys.exit("suite.py failed")
    env = suite.run_env()
    env["MIXFLOW_ROOT"] = ROOT
    out = {"W&P": {"default": observables(os.path.join(quick, "W+P"))}}
    for scene, label in (("HB+P", "HB&P"), ("B+P", "B&P")):
        base = os.path.join(quick, scene)
        out[label] = {"default": observables(base)}
        for name, edits in VARIANTS.items():
            if name == "default":
                continue
            dst = os.path.join(work, "variants", f"{scene}-{name}")
            log = os.path.join(dst, "log.mixflowCoupled")
            if os.path.exists(log) and re.search(r"^End", open(log).read(), re.M):
                out[label][name] = observables(dst)
                continue
            variant(base, dst, edits)
            r = run(["bash", "Allrun", "1", "dem"], cwd=dst, env=env)
            out[label][name] = (observables(dst) if r.returncode == 0
                                else {"failed": r.stderr.strip().splitlines()[-1:]})
    return out


def settled_fraction(run_dir):
    with open(os.path.join(run_dir, "dem", "settled.state")) as f:
        return float(re.search(r"sampleFraction\s+([0-9.eE+-]+);", f.read()).group(1))


def packing(work, fractions, reference_work):
    out = {}
    runs = {"0.6056:0.1": reference_work}
    for item in fractions:
        frac, mu = item.split(":")
        d = os.path.join(work, f"packing-{frac}-{mu}")
        r = run([sys.executable, os.path.join(ROOT, "scripts/suite.py"), "--tier", "reference",
                 "--scenes", "W+P,HB+P", "--work", d, "--set",
                 f"sceneProperties.sample.solidFraction={frac}", "--set",
                 f"demDict.settle.friction={mu}"])
        if r.returncode != 0:
            sys.exit("suite.py failed")
        runs[item] = d
    for frac, d in runs.items():
        for scene, label in (("W+P", "W&P"), ("HB+P", "HB&P")):
            rd = os.path.join(d, scene)
            if not os.path.isdir(rd):
                continue
            obs = observables(rd)
            obs["settled_sample_fraction"] = settled_fraction(rd)
            out.setdefault(label, {})[frac] = obs
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--work", default=os.path.join(ROOT, "runs", "yield_stress"))
    ap.add_argument("--out", default=os.path.join(ROOT, "results", "yield_stress"))
    ap.add_argument("--skip-grains", action="store_true")
    ap.add_argument("--skip-mixtures", action="store_true")
    ap.add_argument("--packing", help="comma-separated FRACTION:SETTLE_FRICTION (stage 3)")
    ap.add_argument("--reference-work", default=os.path.join(ROOT, "runs", "reference"),
                    help="the reference-tier suite run at the cases' own solidFraction")
    a = ap.parse_args()
    work, out = os.path.abspath(a.work), os.path.abspath(a.out)
    build = os.environ.get("MIXFLOW_BUILD", os.path.join(ROOT, "build"))
    os.makedirs(work, exist_ok=True)
    os.makedirs(out, exist_ok=True)
    path = os.path.join(out, "summary.json")
    summary = json.load(open(path)) if os.path.exists(path) else {}
    summary["default"] = "slip"
    summary["default_rule"] = ("dragViscosity auto: slip for a yield-stress or power-law liquid "
                               "(passes the single-grain checks), resolved for a Newtonian one "
                               "(identical there)")
    summary["command"] = "python3 scripts/yield_stress_results.py"
    if not a.skip_grains:
        summary["closures"] = grain_checks(work, build)
    if not a.skip_mixtures:
        summary["paper_faithful"] = {
            "tier": "quick", "variants": {k: v for k, v in VARIANTS.items()},
            "paper": {"back_wall_surface_H": {"HB&P": [0.997, 0.894]},
                      "front_order": "HB > HB&P > P"},
            "runs": mixtures(work)}
        with open(os.path.join(out, "variants.csv"), "w", newline="") as f:
            w = csv.writer(f)
            keys = ["granular_front_m", "grain_pe_released_J", "liquid_front_m",
                    "back_wall_surface_0.5s_H", "back_wall_surface_1.0s_H", "drag_limited_share"]
            w.writerow(["scene", "variant"] + keys)
            for scene, runs in summary["paper_faithful"]["runs"].items():
                for name, obs in runs.items():
                    w.writerow([scene, name] + [obs.get(k, "") for k in keys])
    if a.packing:
        summary["packing"] = packing(work, a.packing.split(","), os.path.abspath(a.reference_work))
        with open(os.path.join(out, "packing.csv"), "w", newline="") as f:
            w = csv.writer(f)
            keys = ["settled_sample_fraction", "granular_front_m", "grain_pe_released_J",
                    "grain_pe_initial_J", "liquid_front_m", "back_wall_surface_1.0s_H"]
            w.writerow(["scene", "target_solid_fraction:settle_friction"] + keys)
            for scene, runs in summary["packing"].items():
                for frac, obs in sorted(runs.items()):
                    w.writerow([scene, frac] + [obs.get(k, "") for k in keys])
    with open(path, "w") as f:
        json.dump(summary, f, indent=1, sort_keys=True)
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
