"""results/yield_stress/: the drag-viscosity closures against the single-grain references, and
the quick HB&P and B&P under the verified default and under the paper-faithful variants.

usage: mixflow yield-stress-results [--work runs/yield_stress] [--out results/yield_stress]
                                               [--skip-grains] [--skip-mixtures]
                                               [--skip-beds | --only-beds]

1. Single grain (tests/coupling/run_yield_sphere.py, the coupling.yield_sphere.* tests) with
   each closure: its settling speed in the paper's Bingham liquid, in the paper's HB liquid, and
   in Bingham liquids at Y = 0.12 and 0.20; each check's measured value, reference, error,
   tolerance and verdict go to summary.json "closures".
1b. Non-Newtonian fixed bed and power-law sphere (tests/coupling/run_ergun.py --liquid
   powerlaw|bingham, run_yield_sphere.py --liquid powerlaw) with each closure: the bed gradient
   against Christopher & Middleman, the Bingham bed's zero-velocity gradient against the
   threshold, the grain's speed against the X(n) drag; summary.json "closures" (bed_*, sphere_*).
   --only-beds runs just these (about 2 min).
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
   WORK/packing-F-MU): the packing control (demDict settle.packingControl friction) settles the
   sample to F within settle.packingTolerance, starting from the settling friction MU (with
   packingControl off, --set demDict.settle.packingControl=off, F sets the grain count only and
   MU the packing). Against the reference-tier runs in
   --reference-work: the settled sample fraction, fronts at 3 s and the grains' released energy;
   summary.json "packing" (merged: packings not rerun keep their recorded entries), packing.csv.
4. With --paper-window NAME=DIR,... (read only): finished paper-window runs of HB+P (made by
   `suite.py --tier cases/tiers/paper-window --scenes HB+P --work DIR [--set ...]`, e.g. the
   paper's scheme and the default): granular and liquid fronts, the grains' released energy, the
   back-wall surface / H every 0.1 s up to 1 s and the share of grains the held drag's bound limited;
   summary.json "paper_faithful" "paper_window", paper_window.csv.
"""

import argparse
import csv
import json
import os
import re
import shutil
import subprocess
import sys

from mixflow.cli import command
from mixflow.commands import suite
from mixflow import ROOT, outputs
from mixflow.outputs import nearest as at, read_series as series

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
        # Settling speeds against Ansley & Smith's Bingham-sphere drag, one check per Bingham
        # number: the paper's liquid (bingham) and raised yield stresses (bingham_Y*).
        for row in result_lines(text, "bingham_sphere"):
            key = ("bingham_settling_speed" if row["name"] == "bingham"
                   else f"{row['name']}_speed")
            c = check(row["measured"], row["reference"], row["tolerance"], "m/s",
                      "Ansley & Smith creeping Bingham drag x Di Felice finite-Re factor "
                      "(tests/reference/bingham_sphere.csv)")
            c.update(yield_number=row["Y"], bingham_number=row["Bi"])
            out[row["closure"]]["checks"][key] = c
        if liquid == "hb":
            free = float(re.search(r"settles at (\S+) m/s", text).group(1))
            for cl in out:
                v = speeds[("hb", cl)]
                out[cl]["checks"]["hb_held"] = {
                    "measured": v, "reference": 0.0, "error": v / free, "tolerance": 1e-3,
                    "passes": abs(v) <= 1e-3 * free, "unit": "m/s",
                    "reference_source": "Beris et al. 1985: held for Y > 0.143 (Y = 0.255); "
                                        "error = speed / speed without the yield stress"}
        elif liquid == "threshold":
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


def result_lines(text, tag):
    """The RESULT <tag> key=value lines of a test driver's output, as dicts of floats."""
    out = []
    for m in re.finditer(rf"^RESULT {tag} (.*)$", text, re.M):
        out.append({k: (float(v) if re.fullmatch(r"[-+0-9.eE]+", v) else v)
                    for k, v in (kv.split("=") for kv in m.group(1).split())})
    return out


def check(measured, reference, tolerance, unit, source, error=None):
    error = measured / reference - 1 if error is None else error
    return {"measured": measured, "reference": reference, "error": error, "tolerance": tolerance,
            "passes": abs(error) <= tolerance, "unit": unit, "reference_source": source}


def failed_check(reference, tolerance, unit, source, why):
    return {"measured": None, "reference": reference, "error": None, "tolerance": tolerance,
            "passes": False, "unit": unit, "reference_source": source, "failed": why}


def why(r):
    """A failed driver's reason: the solver's exception if it threw, else its last line."""
    text = r.stdout + r.stderr
    return ([ln.strip() for ln in text.splitlines() if "what():" in ln][-1:] or
            text.strip().splitlines()[-1:])


def bed_sphere_checks(work, build, closures):
    """The fixed bed in a power-law and a Bingham liquid (tests/coupling/run_ergun.py --liquid,
    GidaspowDrag) and a lone grain in the power-law liquid (run_yield_sphere.py --liquid
    powerlaw) with each closure; merged into closures[<closure>]["checks"]."""
    env = dict(os.environ, WM_PROJECT_DIR=os.environ.get("WM_PROJECT_DIR", "/usr/share/openfoam"))
    common = ["--solver", os.path.join(build, "bin/mixflowCoupled"), "--blockmesh", "blockMesh",
              "--reference", os.path.join(ROOT, "tests/reference")]
    cm_src = ("Christopher & Middleman 1965 Blake-Kozeny power-law form "
              "(tests/reference/powerlaw_bed_christopher_middleman.csv); GidaspowDrag bed")
    th_src = ("capillary-bundle threshold 12.5 (1 - eps) tau_y / (eps d) "
              "(tests/reference/yield_stress_bed_threshold.csv; Chevalier et al. 2013's coefficient "
              "not reachable); intercept of a line through G(U) at U = 5e-6, 1e-5, 2e-5 m/s")
    x_src = ("creeping power-law sphere drag with X(n) (tests/reference/"
             "powerlaw_sphere_drag_correction.csv) x Di Felice finite-Re factor")
    for cl in ("slip", "resolved"):
        checks = closures.setdefault(cl, {"checks": {}})["checks"]
        r = run([sys.executable, os.path.join(ROOT, "tests/coupling/run_ergun.py")] + common +
                ["--workdir", os.path.join(work, "beds", f"powerlaw_{cl}"), "--liquid", "powerlaw",
                 "--drag-viscosity", cl], env=env)
        rows = result_lines(r.stdout, "christopher_middleman")
        if rows:
            for row in rows:
                checks[f"bed_powerlaw_U{row['U']:g}_christopher_middleman"] = check(
                    row["measured"], row["reference"], 0.1, "Pa/m", cm_src)
        else:
            with open(os.path.join(ROOT, "tests/reference/powerlaw_bed_christopher_middleman.csv")) as f:
                for row in csv.DictReader(x for x in f if not x.startswith("#")):
                    checks[f"bed_powerlaw_U{float(row['U_superficial_m_s']):g}_christopher_middleman"] = \
                        failed_check(float(row["dpdx_CM_Pa_m"]), 0.1, "Pa/m", cm_src, why(r))
        r = run([sys.executable, os.path.join(ROOT, "tests/coupling/run_ergun.py")] + common +
                ["--workdir", os.path.join(work, "beds", f"bingham_{cl}"), "--liquid", "bingham",
                 "--drag-viscosity", cl], env=env)
        rows = result_lines(r.stdout, "threshold")
        if rows:
            row = rows[0]
            checks["bed_bingham_threshold"] = check(row["measured"], row["reference"], 0.2, "Pa/m",
                                                    th_src)
            checks["bed_bingham_threshold"]["flow_curve_slope"] = row["slope"]
            checks["bed_bingham_threshold"]["ergun_slope_mu_p"] = row["ergun_slope"]
        r = run([sys.executable, os.path.join(ROOT, "tests/coupling/run_yield_sphere.py")] +
                common + ["--workdir", os.path.join(work, "grains"), "--liquid", "powerlaw",
                          "--closure", cl], env=env)
        rows = result_lines(r.stdout, "powerlaw_sphere")
        ref = float(re.search(r"reference speed (\S+) m/s", r.stdout).group(1))
        if rows:
            checks["sphere_powerlaw_speed"] = check(rows[0]["measured"], ref, 0.1, "m/s", x_src)
            checks["sphere_powerlaw_speed"]["closure_prediction"] = rows[0]["closure_prediction"]
        else:
            checks["sphere_powerlaw_speed"] = failed_check(ref, 0.1, "m/s", x_src, why(r))
    return closures


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
    outputs.copy_inputs(base, dst, keep=("dem",))
    for fkey, tree in edits.items():
        path = os.path.join(dst, suite.FILES[fkey])
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
    r = run(command("suite") + ["--tier", "quick",
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


def paper_window(items, times=(0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0)):
    """Finished paper-window runs NAME=DIR (DIR/HB+P): the observables at TIMES (those the run
    reached) and the share of grains whose held drag the stability bound limited."""
    out = {}
    for item in items:
        name, d = item.split("=", 1)
        rd = os.path.join(os.path.abspath(d), "HB+P")
        dem = series(os.path.join(rd, outputs.DEM_SERIES))
        liq = series(os.path.join(rd, outputs.LIQUID_SERIES))
        ex = series(os.path.join(rd, outputs.EXCHANGE), comments=True)
        t_end = dem[-1][outputs.TIME]
        rec = {"run": os.path.relpath(rd, ROOT), "simulated_to_s": t_end,
               "grain_pe_initial_J": dem[0]["pe_J"], "at": {}}
        for t in times:
            if t > t_end + 0.5 * (dem[1][outputs.TIME] - dem[0][outputs.TIME]):
                continue  # beyond the run (half a sample interval: the last row's rounding)
            upto = [r for r in ex if r["time"] <= t + 1e-9]
            rec["at"][f"{t:g}"] = {
                "granular_front_m": at(dem, "front_x_m", t),
                "grain_pe_released_J": dem[0]["pe_J"] - at(dem, "pe_J", t),
                "liquid_front_m": at(liq, "front_bed_m", t),
                "back_wall_surface_H": at(liq, "back_wall_surface_m", t) / H,
                "drag_limited_share": (sum(r["dragLimited"] / r["particles"] for r in upto)
                                       / len(upto)) if upto else None}
        out[name] = rec
    return out


def settled_fraction(run_dir, key="sampleFraction"):
    """The settled sample's fraction (dem/settled.state: sampleFraction or bulkFraction)."""
    with open(os.path.join(run_dir, "dem", "settled.state")) as f:
        return float(re.search(key + r"\s+([0-9.eE+-]+);", f.read()).group(1))


def packing(work, fractions, reference_work):
    out = {}
    runs = {"0.6056:0.1": reference_work}
    for item in fractions:
        frac, mu = item.split(":")
        d = os.path.join(work, f"packing-{frac}-{mu}")
        r = run(command("suite") + ["--tier", "reference",
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
    ap.add_argument("--skip-beds", action="store_true",
                    help="skip the non-Newtonian bed and power-law sphere checks")
    ap.add_argument("--only-beds", action="store_true",
                    help="only the non-Newtonian bed and power-law sphere checks (about 2 min)")
    ap.add_argument("--packing", help="comma-separated FRACTION:SETTLE_FRICTION (stage 3)")
    ap.add_argument("--paper-window", help="comma-separated NAME=DIR of finished paper-window "
                    "runs of HB+P (stage 4: read only)")
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
    summary["command"] = "mixflow yield-stress-results"
    if a.only_beds:
        a.skip_grains = a.skip_mixtures = True
    if not a.skip_grains:
        beds = {cl: {k: v for k, v in c["checks"].items() if k.startswith(("bed_", "sphere_"))}
                for cl, c in summary.get("closures", {}).items()}
        summary["closures"] = grain_checks(work, build)
        for cl, kept in beds.items():
            summary["closures"].setdefault(cl, {"checks": {}})["checks"].update(kept)
    if not a.skip_beds:
        summary["closures"] = bed_sphere_checks(work, build, summary.get("closures", {}))
    if not a.skip_mixtures:
        # The paper-window runs (stage 4) are kept: they are not rerun here.
        summary["paper_faithful"] = {
            "tier": "quick", "variants": {k: v for k, v in VARIANTS.items()},
            "paper": {"back_wall_surface_H": {"HB&P": [0.997, 0.894]},
                      "front_order": "HB > HB&P > P"},
            "runs": mixtures(work),
            **{k: v for k, v in summary.get("paper_faithful", {}).items() if k == "paper_window"}}
        with open(os.path.join(out, "variants.csv"), "w", newline="") as f:
            w = csv.writer(f)
            keys = ["granular_front_m", "grain_pe_released_J", "liquid_front_m",
                    "back_wall_surface_0.5s_H", "back_wall_surface_1.0s_H", "drag_limited_share"]
            w.writerow(["scene", "variant"] + keys)
            for scene, runs in summary["paper_faithful"]["runs"].items():
                for name, obs in runs.items():
                    w.writerow([scene, name] + [obs.get(k, "") for k in keys])
    if a.packing:
        # Merged into the earlier entries: a packing whose runs are no longer on disk keeps its
        # recorded observables.
        for scene, runs in packing(work, a.packing.split(","),
                                   os.path.abspath(a.reference_work)).items():
            summary.setdefault("packing", {}).setdefault(scene, {}).update(runs)
        with open(os.path.join(out, "packing.csv"), "w", newline="") as f:
            w = csv.writer(f)
            keys = ["settled_sample_fraction", "granular_front_m", "grain_pe_released_J",
                    "grain_pe_initial_J", "liquid_front_m", "back_wall_surface_1.0s_H"]
            w.writerow(["scene", "target_solid_fraction:settle_friction"] + keys)
            for scene, runs in summary["packing"].items():
                for frac, obs in sorted(runs.items()):
                    w.writerow([scene, frac] + [obs.get(k, "") for k in keys])
    if a.paper_window:
        pw = paper_window(a.paper_window.split(","))
        summary.setdefault("paper_faithful", {})["paper_window"] = pw
        with open(os.path.join(out, "paper_window.csv"), "w", newline="") as f:
            w = csv.writer(f)
            keys = ["granular_front_m", "grain_pe_released_J", "liquid_front_m",
                    "back_wall_surface_H", "drag_limited_share"]
            w.writerow(["variant", "time_s"] + keys)
            for name, rec in pw.items():
                for t, obs in rec["at"].items():
                    w.writerow([name, t] + [obs.get(k, "") for k in keys])
    with open(path, "w") as f:
        json.dump(summary, f, indent=1, sort_keys=True)
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
