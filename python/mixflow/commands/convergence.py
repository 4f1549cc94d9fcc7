"""Convergence ladders: one knob at a time on one scene, every run on the same settled grains
(results/convergence/README.md).

usage: mixflow convergence --scene HB+P --knob couplingProperties.exchangeEvery
           --values 25,10,4,2 [--label NAME] [--tier reference] [--set FILE.ENTRY=VALUE ...]
           [--end 0.5] [--work runs/convergence] [--out results/convergence]
           [--settled-from WORK] [--against WORK] [--report-only]

Each value runs `mixflow suite --tier TIER --scenes SCENE --work WORK/LABEL/VALUE --set ... --set
KNOB=VALUE --set controlDict.endTime=END`, the first value settling the grains and the others
starting from its sample (--settled-from; with --settled-from WORK every value starts from WORK's
sample, e.g. another ladder's first value), so only the knob differs. A value whose run finished
is not rerun (the ladder resumes); a later --end takes the finished runs on to it. The observables
at 0.25, 0.5, 1, 2, 3 s (those the runs reach: fronts, the grains' released potential energy, the
liquid front (also at depth d/2), the back-wall height; scripts/tier_trade.py) and the CPU seconds
of each run (cpu_s: the suite command with its children, WORK/LABEL/VALUE/rusage.SCENE.json;
solver_cpu_s: the solver process's ExecutionTime; stage_wall_s: where the solver's wall time went,
obs.stage_times) go to OUT/summary.json under ladders.LABEL.SCENE.VALUE, with each observable's
change against the finest value (the last listed) under ladders.LABEL.SCENE.change_against_finest.
A ladder has converged when its second-finest value is within 5 % of the finest in the released
energy and within 0.05 m in the fronts at every time both reach (ladders.LABEL.SCENE.converged);
beside them, the end's deposit profile h(x) against the finest's (relative L1,
change_against_finest.VALUE.deposit_h_relative_l1) and the body's front
(granular_thickness_front_m, where the deposit thins below d); with --against WORK each value's
change against that run (change_against_base: a noise-floor run against the run it perturbs).
converged.SCENE is true once every ladder of the scene has (a one-value ladder, a noise-floor run,
is none); truth_tier is cases/tiers/truth with its interval halving per scene (ladder
interval_E1: null where it has not run); packing lists each ladder's sample solid fraction
against the target, and the grains' critical packing (results/critical_packing). The static beds'
measurements (OUT/static_bed/*.json, tests/coupling/run_settled_bed.py --json) are gathered into
static_bed.
"""
import argparse
import glob
import json
import os
import sys

from mixflow import ROOT, schema
from mixflow import observables as obs
from mixflow.cli import command
from mixflow.commands import suite
from mixflow.paper import MIXTURES
from mixflow.commands.tier_trade import observables
from mixflow.timing import recorded_run

TIMES = (0.1, 0.2, 0.25, 0.5, 1.0, 2.0, 3.0)
ENERGY_TOL = 0.05  # relative, released energy
FRONT_TOL = 0.05  # m, granular and liquid fronts
FRONTS = ("granular_front_m", "liquid_front_m")
ENERGY = "particle_pe_released_J_per_m"
TRUTH_LADDER = "interval_E1_smoothed"  # the truth tier's intervals against every DEM step


def within(row, ref):
    """The ladder's convergence rule between two values' observables; False when they share no
    time (nothing compared is not converged)."""
    compared = 0
    for t, o in ref.items():
        if not isinstance(o, dict) or not isinstance(row.get(t), dict):
            continue
        for k in FRONTS:
            if isinstance(o.get(k), float) and abs(row[t][k] - o[k]) > FRONT_TOL:
                return False
        e, e_ref = row[t].get(ENERGY), o.get(ENERGY)
        if isinstance(e_ref, float) and abs(e - e_ref) > ENERGY_TOL * abs(e_ref):
            return False
        compared += 1
    return compared > 0


def difference(row, ref, s, s_ref):
    """Each observable's change from ref to row at the times both reach, and the end's deposit
    profile h(x) against ref's (relative L1)."""
    d = {}
    for t, o in row.items():
        r = ref.get(t)
        if isinstance(o, dict) and isinstance(r, dict):
            d[t] = {k: o[k] - r[k] for k in o
                    if isinstance(o.get(k), float) and isinstance(r.get(k), float)}
    d["deposit_h_relative_l1"] = obs.deposit_difference(s, s_ref)
    return d


def cost_file_name(scene):
    return f"rusage.{scene}.json"


def scene_cost_file(work, scene):
    """The file with the CPU of SCENE's run in WORK: its own, or WORK/rusage.json where WORK holds
    that scene alone (a shared one sums the scenes run there); None otherwise."""
    own = os.path.join(work, cost_file_name(scene))
    if os.path.isfile(own):
        return own
    shared = os.path.join(work, "rusage.json")
    scenes = [d for d in os.listdir(work) if os.path.isfile(os.path.join(work, d, ".done"))] \
        if os.path.isdir(work) else []
    return shared if os.path.isfile(shared) and len(scenes) == 1 else None


def run_value(args, value, first_dir):
    work = os.path.join(args.work, args.label, str(value))
    cmd = command("suite", "--tier", args.tier, "--scenes", args.scene, "--work", work, "--np",
                  str(args.np))
    for s in args.set:
        cmd += ["--set", s]
    cmd += ["--set", f"{args.knob}={value}", "--set", f"controlDict.endTime={args.end}"]
    if first_dir and first_dir != work:
        cmd += ["--settled-from", first_dir]
    print("+", " ".join(cmd), flush=True)
    return recorded_run(cmd, work, name=cost_file_name(args.scene)), work


def collect(args):
    rows, scenes = {}, {}
    for value in args.values:
        work = os.path.join(args.work, args.label, str(value))
        s = obs.Scene(work, args.scene)
        if not s.done:
            continue
        scenes[str(value)] = s
        row = observables(s, TIMES)
        cost_file = scene_cost_file(work, args.scene)
        if cost_file:
            with open(cost_file) as f:
                row["cpu_s"] = json.load(f)["cpu_s"]
        row["solver_cpu_s"] = obs.solver_cpu(s)
        row["stage_wall_s"] = obs.stage_times(s)
        row["end_deposit"] = obs.deposit_tail(s)
        row["liquid_over_gate_m3"] = obs.liquid_over_gate(s)
        dem_summary = os.path.join(s.dir, "postProcessing", "dem", "summary.json")
        if os.path.exists(dem_summary):
            with open(dem_summary) as f:
                d = json.load(f)
            row["sample_solid_fraction"] = d.get("settled", {}).get("sample_solid_fraction")
            row["target_solid_fraction"] = d.get("sample", {}).get("target_solid_fraction")
        rows[str(value)] = obs.clean(row)
    finest = str(args.values[-1])
    change = {}
    if finest in rows:
        change = {value: difference(row, rows[finest], scenes[value], scenes[finest])
                  for value, row in rows.items() if value != finest}
    against = {}
    if args.against:
        base = obs.Scene(args.against, args.scene)
        if base.done:
            base_row = obs.clean(observables(base, TIMES))
            against = {value: difference(row, base_row, scenes[value], base)
                       for value, row in rows.items()}
    done = [str(v) for v in args.values if str(v) in rows]
    converged = (len(done) >= 2 and done[-1] == finest and within(rows[done[-2]], rows[finest]))
    return {"knob": args.knob, "set": args.set, "tier": args.tier, "end_s": args.end,
            "values": rows, "change_against_finest": change, "finest": finest,
            "converged": converged,
            **({"against": args.against, "change_against_base": against} if args.against else {})}


# The truth tier's settings summary.json names: (key, case file, entry, type).
TRUTH_SETTINGS = (("youngModulusFactor", "demDict", "youngModulusFactor", float),
                  ("exchangeEvery", "couplingProperties", "exchangeEvery", int),
                  ("cellSize", "cfdDict", "cellSize", float),
                  ("interpolation", "couplingProperties", "interpolation", str),
                  ("voidSmoothing", "couplingProperties", "dividedCoeffs.smoothing", float),
                  ("viscosityCap", "sceneProperties", "liquid.viscosityCap", float))


def truth_tier(ladders):
    """The truth tier (cases/tiers/truth): its settings as each mixture's case takes them (the
    tier's entry, else the case's, else the declared default; one value where the mixtures
    agree), and per scene whether its exchange interval keeps every observable within the rule of
    an exchange every DEM step at its stiffness (the TRUTH_LADDER ladder: None where the ladder
    lacks either value). The ladders at
    softer stiffnesses and longer intervals that moved by more than the rule are why this tier is
    the paper's stiffness (results/convergence/README.md)."""
    tier = suite.Tier("truth")
    per_scene = {}
    for scene in MIXTURES:
        src = os.path.join(suite.CASES, scene)
        texts, _ = suite.tier_edits(src, tier, scene)
        row = {}
        for key, fkey, entry, cast in TRUTH_SETTINGS:
            v = schema.value(suite.tier_file_tree(src, texts, fkey), suite.FILES[fkey], entry)
            row[key] = cast(float(v)) if cast is int else cast(v)  # int of "3" or 3.0
        per_scene[scene] = row
    out = {"tier": os.path.relpath(tier.path, ROOT)}
    for key, *_ in TRUTH_SETTINGS:
        values = {sc: s[key] for sc, s in per_scene.items()}
        out[key] = next(iter(values.values())) if len(set(values.values())) == 1 else values
    lad = ladders.get(TRUTH_LADDER, {})

    def tier_within_finest(sc):
        rows = lad.get(sc, {}).get("values", {})
        mine, finest = rows.get(str(per_scene[sc]["exchangeEvery"])), rows.get(lad.get(sc, {}).get("finest"))
        return within(mine, finest) if mine and finest else None

    # The ladders made at the truth tier itself (tier truth): per scene, whether the tier's value
    # lies within the rule of the ladder's other value (None where not measured).
    at_tier = {}
    for label, ld in ladders.items():
        for sc, lad_sc in ld.items():
            if label != TRUTH_LADDER and sc in per_scene and lad_sc.get("tier") == "truth":
                mine, other = values_pair(lad_sc, per_scene[sc])
                if mine is not None:
                    at_tier.setdefault(label, {})[sc] = within(mine, other)
    return dict(out, interval_ladder=TRUTH_LADDER,
                interval_converged={sc: tier_within_finest(sc) for sc in MIXTURES},
                interval_compared_to_s={sc: lad[sc]["end_s"] for sc in lad},
                converged_at_tier=at_tier)


def values_pair(ladder, setting):
    """The observables of the tier's own value in LADDER (SETTING: the tier's settings of the
    scene, by TRUTH_SETTINGS key) and of the ladder's first other value (these ladders have
    two), or (None, None)."""
    knob = ladder["knob"].split(".")[-1]
    key = next((k for k, _, entry, _ in TRUTH_SETTINGS if entry.split(".")[-1] == knob), None)
    if key is None:
        return None, None
    rows = ladder["values"]
    mine = next((v for v in rows if str(v) == str(setting[key])
                 or _same_number(v, setting[key])), None)
    other = next((v for v in rows if v != mine), None)
    return (rows[mine], rows[other]) if mine is not None and other is not None else (None, None)


def _same_number(a, b):
    try:
        return abs(float(a) - float(b)) <= 1e-12 * max(1.0, abs(float(b)))
    except (TypeError, ValueError):
        return False


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scene", required=True)
    ap.add_argument("--knob", required=True, help="FILE.ENTRY the ladder changes")
    ap.add_argument("--values", required=True, help="comma-separated, coarsest first")
    ap.add_argument("--label", help="name of the ladder (default: the knob's entry)")
    ap.add_argument("--tier", default="reference")
    ap.add_argument("--set", action="append", default=[], metavar="FILE.ENTRY=VALUE")
    ap.add_argument("--end", type=float, default=0.5, help="endTime of every run (s)")
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("--work", default=os.path.join(ROOT, "runs", "convergence"))
    ap.add_argument("--out", default=os.path.join(ROOT, "results", "convergence"))
    ap.add_argument("--settled-from", metavar="WORK", help="the settled sample of every value")
    ap.add_argument("--against", metavar="WORK",
                    help="also each value's change against this finished run of the scene "
                    "(e.g. a noise-floor run against the run it perturbs)")
    ap.add_argument("--report-only", action="store_true")
    ap.add_argument("--made-by", metavar="COMMAND",
                    help="with --report-only: the command that made WORK/LABEL/<value>/SCENE, "
                    "recorded as the ladder's command (a ladder whose values differ in more than "
                    "one entry, e.g. results/convergence/geometry.sh)")
    args = ap.parse_args(argv)
    if args.made_by and not args.report_only:
        ap.error("--made-by records the command of runs made elsewhere: it needs --report-only")
    args.values = [v.strip() for v in args.values.split(",") if v.strip()]
    args.label = args.label or args.knob.split(".")[-1]
    if not args.report_only:
        first = args.settled_from or os.path.join(args.work, args.label, args.values[0])
        for value in args.values:
            rc, _ = run_value(args, value, first)
            if rc != 0:
                print(f"convergence.py: {args.scene} at {args.knob}={value} failed (exit {rc}); "
                      f"rerun the same command to resume", file=sys.stderr)
                return rc
    os.makedirs(args.out, exist_ok=True)
    summary_file = os.path.join(args.out, "summary.json")
    summary = {}
    if os.path.exists(summary_file):
        with open(summary_file) as f:
            summary = json.load(f)
    ladder = collect(args)
    # The command that makes the ladder: --report-only only re-reads the runs it made.
    ladder["command"] = args.made_by or " ".join(
        ["mixflow convergence"] + [a for a in (argv or sys.argv[1:]) if a != "--report-only"])
    summary.setdefault("ladders", {}).setdefault(args.label, {})[args.scene] = ladder
    # A scene is converged once every ladder of it is; a one-value ladder (a noise-floor run
    # beside a ladder's value) is no ladder.
    summary["converged"] = {
        scene: all(lad[scene]["converged"] for lad in summary["ladders"].values()
                   if scene in lad and len(lad[scene]["values"]) >= 2)
        for scene in {sc for lad in summary["ladders"].values() for sc in lad}}
    beds = {}
    for path in sorted(glob.glob(os.path.join(args.out, "static_bed", "*.json"))):
        with open(path) as f:
            beds[os.path.splitext(os.path.basename(path))[0]] = json.load(f)
    summary["static_bed"] = beds
    # The packing each ladder ran at (its sample's solid fraction against the target).
    summary["packing"] = {
        "target": next((r.get("target_solid_fraction") for lad in summary["ladders"].values()
                        for sc in lad.values() for r in sc["values"].values()), None),
        "achieved": {f"{label}/{scene}": sorted({r.get("sample_solid_fraction")
                                                 for r in sc["values"].values()} - {None})
                     for label, lad in summary["ladders"].items() for scene, sc in lad.items()}}
    # The critical packing of these grains (results/critical_packing: steady plane shear, the
    # bulk fraction as I -> 0): a sample denser than it is dense.
    crit = os.path.join(ROOT, "results", "critical_packing", "critical_packing.json")
    if os.path.isfile(crit):
        with open(crit) as f:
            c = json.load(f)
        summary["packing"]["critical"] = {"phi_c": c["phi_c"], "phi_c_error": c["phi_c_error"],
                                          "wall_margin_3d": c["fit_margin_3d"]["phi_c"],
                                          "file": os.path.relpath(crit, ROOT)}
    summary["truth_tier"] = truth_tier(summary["ladders"])
    with open(summary_file, "w") as f:
        json.dump(summary, f, indent=1, sort_keys=True)
    for value, row in ladder["values"].items():
        print(value, json.dumps({t: o for t, o in row.items() if t.endswith("s")}))
    return 0


if __name__ == "__main__":
    sys.exit(main())
