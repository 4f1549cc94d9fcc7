"""Cost against accuracy of each fidelity knob alone around the quick tier (docs/suite.md,
"Choosing a tier"; results/trade/README.md).

usage: mixflow knob-trade [--runs /work/runs-trade] [--out results/trade]
                                              [--only TAG,...] [--skip TAG,...] [--budget CPU_S]
                                              [--report-only] [--lambdas]

Each run is `nice -n 15 mixflow suite --tier quick --scenes SCENE --work RUNS/TAG
--set ...` (one at a time; a scene with .done is skipped, so the plan resumes). Its cost is the
CPU time of suite.py and its children (getrusage RUSAGE_CHILDREN, user + sys), accumulated over
attempts in RUNS/TAG/rusage.json, with the wall time beside it. --budget stops starting runs
once the CPU spent by all runs of the plan exceeds it.

The report (also --report-only, which reads finished runs only): per knob and scene the
observables of mixflow tier-trade's observables() plus the Savage window (the longest
interval with N_sav > 0.1) and, with --lambdas, the drift coefficients of every finished mixture
run (mixflow mixture-lambdas, under a second of CPU a run; cached in RUNS/TAG/lambdas.json);
the change of each against the knob's reference (its finest run that finished), the CPU cost and
its ratio to the reference's. Writes OUT/summary.json, OUT/table.md, OUT/trade.png.
"""
import argparse
import copy
import json
import os
import resource
import time

from mixflow import ROOT
from mixflow.cli import command
from mixflow import observables as obs
from mixflow.commands.tier_trade import observables
from mixflow.timing import recorded_run

TIMES = (0.25, 0.5, 1.0, 1.5)
SCENES = {"P": "P", "W+P": "WP"}  # scene -> tag suffix of its run directories
QUICK = "quick"  # the value label of the quick tier's run (knob None in PLAN)

# knob -> scenes, values (label -> --set entries; QUICK: none) and the reference (the finest
# setting). Labels are the knob's value as written in the case files.
KNOBS = {
    "youngModulusFactor": {
        "entry": "demDict youngModulusFactor", "scenes": ["P", "W+P"], "quick": "1e-4",
        "values": {"1e-3": ["demDict.youngModulusFactor=1e-3"]}, "reference": "1e-3"},
    "rayleighFraction": {
        "entry": "demDict rayleighFraction (timeStep auto)", "scenes": ["P", "W+P"],
        "quick": "0.1",
        "values": {"0.05": ["demDict.rayleighFraction=0.05"],
                   "0.2": ["demDict.rayleighFraction=0.2"]}, "reference": "0.05"},
    "exchangeEvery": {
        "entry": "couplingProperties exchangeEvery", "scenes": ["W+P"], "quick": "10",
        "values": {"5": ["couplingProperties.exchangeEvery=5"],
                   "25": ["couplingProperties.exchangeEvery=25"]}, "reference": "5"},
    "cellSize": {
        "entry": "cfdDict cellSize (m)", "scenes": ["W+P"], "quick": "0.075",
        "values": {"0.05": ["cfdDict.cellSize=0.05"], "0.1": ["cfdDict.cellSize=0.1"]},
        "reference": "0.05"},
    "voidFractionModel": {
        "entry": "couplingProperties voidFractionModel", "scenes": ["W+P"], "quick": "divided",
        "values": {"centre": ["couplingProperties.voidFractionModel=centre"]},
        "reference": "divided"},
    "width": {
        "entry": "sceneProperties sample.width (m), channel.sideWalls", "scenes": ["P", "W+P"],
        "quick": "0.072 periodic",
        "values": {"0.144 periodic": ["sceneProperties.sample.width=0.144"],
                   "0.6 walls": ["sceneProperties.sample.width=0.6",
                                 "sceneProperties.channel.sideWalls=walls"]},
        "reference": ["0.6 walls", "0.144 periodic"]},
    "dimensions": {
        "entry": "cfdDict dimensions", "scenes": ["W+P"], "quick": "2",
        "values": {"3": ["cfdDict.dimensions=3"]}, "reference": "3"},
    # The noise floor: the same run again, and another loose fill (its jitter's seed) settled
    # into another packing of the same column.
    "repeat": {
        "entry": "none (again), demDict settle.seed (quick: 12345)", "scenes": ["P", "W+P"],
        "quick": "quick", "values": {"again": [], "seed 54321": ["demDict.settle.seed=54321"]},
        "reference": "quick"},
}
# Runs in order of priority (cheap and informative first); (knob, value, scene). The quick runs
# come first: they size the rest.
PLAN = [(None, QUICK, "P"), (None, QUICK, "W+P"),
        ("rayleighFraction", "0.2", "P"), ("rayleighFraction", "0.2", "W+P"),
        ("rayleighFraction", "0.05", "P"), ("width", "0.144 periodic", "P"),
        ("exchangeEvery", "25", "W+P"), ("exchangeEvery", "5", "W+P"),
        ("cellSize", "0.1", "W+P"), ("cellSize", "0.05", "W+P"),
        ("voidFractionModel", "centre", "W+P"), ("youngModulusFactor", "1e-3", "P"),
        ("repeat", "again", "P"), ("repeat", "again", "W+P"),
        ("repeat", "seed 54321", "P"), ("repeat", "seed 54321", "W+P"),
        ("rayleighFraction", "0.05", "W+P"), ("width", "0.144 periodic", "W+P"),
        ("dimensions", "3", "W+P"), ("youngModulusFactor", "1e-3", "W+P"),
        ("width", "0.6 walls", "P")]
# Observables of the table and the figure (time key or None, name).
MAIN = [("1.5s", "granular_front_m"), ("1.5s", "liquid_front_m"),
        ("1.5s", "particle_pe_released_J_per_m"), ("0.5s", "particle_ke_J_per_m"),
        ("1s", "back_wall_height_over_H"), (None, "arrival_at_1.38m_s"),
        (None, "subcritical_after_arrival_s"), (None, "energy_excess_J_per_m"),
        (None, "savage_window_end_s")]


def tag(knob, value, scene):
    name = "base" if knob is None else f"{knob}-{value.replace(' ', '-')}"
    return f"{name}-{SCENES[scene]}"


def sets(knob, value):
    return [] if knob is None else KNOBS[knob]["values"][value]


def suite_cmd(knob, value, scene, work):
    cmd = command("suite") + ["--tier", "quick", "--scenes", scene, "--work", work]
    for s in sets(knob, value):
        cmd += ["--set", s]
    return cmd


def read_json(path):
    if not os.path.isfile(path):
        return None
    with open(path) as f:
        return json.load(f)


def spent(runs):
    total = 0.0
    for knob, value, scene in PLAN:
        r = read_json(os.path.join(runs, tag(knob, value, scene), "rusage.json"))
        total += r["cpu_s"] if r else 0.0
    return total


def run_one(knob, value, scene, runs):
    work = os.path.join(runs, tag(knob, value, scene))
    if os.path.isfile(os.path.join(work, scene, ".done")) or \
            os.path.isfile(os.path.join(work, scene, ".failed")):
        return
    cmd = ["nice", "-n", "15"] + suite_cmd(knob, value, scene, work)
    print("running:", " ".join(cmd), flush=True)
    with open(os.path.join(runs, tag(knob, value, scene) + ".log"), "a") as log:
        rc = recorded_run(cmd, work, cwd=ROOT, stdout=log)
    rec = read_json(os.path.join(work, "rusage.json"))
    print(f"  rc {rc}, cpu {rec['cpu_s']:.0f} s, wall {rec['wall_s']:.0f} s", flush=True)


def refusal(work, scene):
    """The lines of a failed run's log that say why (the input check's message)."""
    log = os.path.join(work, scene, "log.suite")
    if not os.path.isfile(log):
        return None
    with open(log, errors="replace") as f:
        lines = [ln.strip() for ln in f if ln.strip()]
    hits = [ln for ln in lines if "rror" in ln or "refus" in ln or "must" in ln]
    return (hits or lines)[-3:]


def lambdas(work, scene, compute):
    """Summary of the drift coefficients of a finished mixture run (cached in lambdas.json)."""
    path = os.path.join(work, "lambdas.json")
    rec = read_json(path)
    if rec is None and compute:
        from mixflow.commands import mixture_lambdas as ml
        t0 = time.time()
        r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
        ml.extract(os.path.join(work, scene), os.environ.get(
            "MIXFLOW_BUILD", os.path.join(ROOT, "build")))
        r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
        rec = ml.summarise(os.path.join(work, scene, "postProcessing", "mixture", "mixture.h5"))
        rec = {"extract_cpu_s": r1.ru_utime + r1.ru_stime - r0.ru_utime - r0.ru_stime,
               "extract_wall_s": time.time() - t0,
               "lambda_u_median": rec["lambda_u"]["median"],
               "lambda_w_median": rec["lambda_w"]["median"],
               "lambda_p_density_median": rec.get("lambda_p_density", {}).get("median"),
               "lambda_u_wls_slope": rec["lambda_u_wls_slope"],
               "lambda_w_wls_slope": rec["lambda_w_wls_slope"], "flowing_bins": rec["flowing_bins"]}
        with open(path, "w") as f:
            json.dump(obs.clean(rec), f, indent=1)
    return rec


def measure(knob, value, scene, runs, compute_lambdas):
    work = os.path.join(runs, tag(knob, value, scene))
    s = obs.Scene(work, scene)
    cost = read_json(os.path.join(work, "rusage.json"))
    if not s.done:
        if s.failed or (cost and cost.get("rc")):
            return {"status": "failed", "message": refusal(work, scene),
                    "cpu_s": cost and cost["cpu_s"], "wall_s": cost and cost["wall_s"]}
        return None
    o = observables(s, TIMES)
    sav = obs.savage(s)
    win = obs.collision_interval(sav[0], sav[1]) if sav else None
    o["savage_window_start_s"], o["savage_window_end_s"] = win if win else (None, None)
    if s.content == "mixture":
        lam = lambdas(work, scene, compute_lambdas)
        if lam:
            o.update({k: v for k, v in lam.items() if k.startswith("lambda")})
    return {"status": "done", "work": work, "cpu_s": cost["cpu_s"] if cost else None,
            "wall_s": cost["wall_s"] if cost else None, "simulated_s": s.t_end(),
            "command": " ".join(suite_cmd(knob, value, scene, work)), "observables": o}


def flat(o):
    out = {}
    for k, v in o.items():
        if isinstance(v, dict):
            out.update({f"{k}/{kk}": vv for kk, vv in v.items()})
        else:
            out[k] = v
    return out


def change(o, ref):
    """o - ref per observable both have; relative where |ref| is not small (times, lengths and
    energies relative, void-ish quantities absolute)."""
    d = {}
    fo, fr = flat(o), flat(ref)
    for k, v in fo.items():
        b = fr.get(k)
        if v is None or b is None:
            continue
        d[k] = {"abs": v - b, "rel": (v - b) / abs(b) if abs(b) > 1e-9 else None}
    return d


def key(tk, name):
    return name if tk is None else f"{tk}/{name}"


def report(runs, out, compute_lambdas):
    res = {"command": "mixflow knob-trade --runs " + runs +
           (" --lambdas" if compute_lambdas else ""), "times_s": list(TIMES),
           "cost": "CPU s (user + sys of suite.py and its children, getrusage)",
           "change": "value minus the reference's (abs) and that over |reference| (rel)",
           "reference": {}, "knobs": {}}
    base = {sc: measure(None, QUICK, sc, runs, compute_lambdas) for sc in SCENES}
    for knob, kd in KNOBS.items():
        res["knobs"][knob] = {"entry": kd["entry"]}
        for sc in kd["scenes"]:
            rows = {kd["quick"]: copy.deepcopy(base[sc])}
            for v in kd["values"]:
                if (knob, v, sc) not in PLAN:
                    continue
                rows[v] = measure(knob, v, sc, runs, compute_lambdas)
            refs = kd["reference"] if isinstance(kd["reference"], list) else [kd["reference"]]
            ref = next((r for r in refs if rows.get(r) and rows[r]["status"] == "done"), None)
            res["reference"].setdefault(sc, {})[knob] = ref
            for v, r in rows.items():
                if r and r["status"] == "done" and ref:
                    rr = rows[ref]
                    r["cost_ratio"] = r["cpu_s"] / rr["cpu_s"] if r["cpu_s"] and rr["cpu_s"] \
                        else None
                    r["change"] = change(r["observables"], rr["observables"])
            res["knobs"][knob][sc] = {v: r for v, r in rows.items()}
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "summary.json"), "w") as f:
        json.dump(obs.clean(res), f, indent=1)
        f.write("\n")
    with open(os.path.join(out, "table.md"), "w") as f:
        f.write(markdown(res))
    figure(res, os.path.join(out, "trade.png"))
    print(markdown(res))


def markdown(res):
    lines = ["# Each knob alone around the quick tier", "", f"Made by `{res['command']}`. "
             "Cost: CPU seconds of the run (settling included), ratio to the knob's reference "
             "(the finest setting that finished, marked **ref**). Change: the value minus the "
             "reference's; relative (%) for fronts, energies and times; back-wall height in "
             "units of H; '-' where either lacks it; 'not run' where the budget did not reach "
             "it.", ""]
    names = [key(tk, n) for tk, n in MAIN]
    lines.append("| knob | scene | value | CPU s | wall s | cost / ref | " +
                 " | ".join(names) + " |")
    lines.append("|---" * (6 + len(names)) + "|")
    for knob, kd in res["knobs"].items():
        for sc in SCENES:
            if sc not in kd:
                continue
            for v, r in kd[sc].items():
                lab = v + (" **ref**" if res["reference"][sc][knob] == v else "") + \
                    (" (quick)" if v == KNOBS[knob]["quick"] else "")
                if r is None:
                    lines.append(f"| {knob} | {sc} | {lab} | not run |" + " |" * (2 + len(names)))
                    continue
                if r["status"] != "done":
                    msg = "; ".join(r["message"] or [])[:300].replace("|", "/")
                    lines.append(f"| {knob} | {sc} | {lab} | failed: {msg} |" +
                                 " |" * (2 + len(names)))
                    continue
                cells = []
                for k in names:
                    c = (r.get("change") or {}).get(k)
                    val = flat(r["observables"]).get(k)
                    if val is None:
                        cells.append("-")
                    elif c is None:
                        cells.append(obs.fmt(val))
                    elif "back_wall" in k or c["rel"] is None:
                        cells.append(f"{obs.fmt(val)} ({c['abs']:+.3f})")
                    else:
                        cells.append(f"{obs.fmt(val)} ({100 * c['rel']:+.1f}%)")
                ratio = r.get("cost_ratio")
                lines.append(f"| {knob} | {sc} | {lab} | {r['cpu_s']:.0f} | {r['wall_s']:.0f} | "
                             f"{obs.fmt(ratio)} | " + " | ".join(cells) + " |")
    lam = [(knob, sc, v, r) for knob, kd in res["knobs"].items() for sc in SCENES if sc in kd
           for v, r in kd[sc].items() if r and r["status"] == "done"
           and "lambda_u_median" in r["observables"]]
    if lam:
        lines += ["", "Drift coefficients of W+P (mixflow mixture-lambdas: medians over the "
                  "flowing bins, and the weighted least-squares slopes):", "",
                  "| knob | value | lambda_u | lambda_w | lambda_p (density) | u slope | w slope |",
                  "|---|---|---|---|---|---|---|"]
        seen = set()
        for knob, sc, v, r in lam:
            o = r["observables"]
            if (r["work"]) in seen:
                continue
            seen.add(r["work"])
            lines.append(f"| {knob if v != KNOBS[knob]['quick'] else 'quick'} | {v} | " +
                         " | ".join(obs.fmt(o.get(k)) for k in (
                             "lambda_u_median", "lambda_w_median", "lambda_p_density_median",
                             "lambda_u_wls_slope", "lambda_w_wls_slope")) + " |")
    return "\n".join(lines) + "\n"


def size(c, k):
    """|change| as plotted: relative, but in H for the back-wall height."""
    return abs(c["abs"] if "back_wall" in k or c["rel"] is None else c["rel"])


def figure(res, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.ticker import NullFormatter
    names = [key(tk, n) for tk, n in MAIN]
    fig, axes = plt.subplots(3, 3, figsize=(13, 11))
    marks = {"P": "o", "W+P": "s"}
    colours = dict(zip(KNOBS, plt.rcParams["axes.prop_cycle"].by_key()["color"]))
    for ax, k in zip(axes.flat, names):
        for knob, kd in res["knobs"].items():
            for sc in SCENES:
                pts = [(r["cost_ratio"], max(size(r["change"][k], k), 1e-4), v)
                       for v, r in kd.get(sc, {}).items()
                       if r and r["status"] == "done" and r.get("cost_ratio")
                       and k in r.get("change", {}) and v != res["reference"][sc][knob]]
                if not pts:
                    continue
                if knob == "repeat":  # the noise floor: a horizontal line per run
                    for _, y, v in pts:
                        ax.axhline(y, color="grey", ls="--" if sc == "P" else ":", lw=1,
                                   label=f"{sc} {v} (noise floor)")
                    continue
                ax.plot([p[0] for p in pts], [p[1] for p in pts], marks[sc],
                        color=colours[knob], label=f"{knob} {sc}")
                for x, y, v in pts:
                    ax.annotate(v, (x, y), fontsize=7)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.xaxis.set_minor_formatter(NullFormatter())
        ax.set_title(k, fontsize=9)
        ax.set_xlabel("CPU cost / reference's")
        ax.set_ylabel("|change| (relative; back wall: H)")
        ax.grid(True, which="both", alpha=0.3)
    handles, labels = [], []
    for ax in axes.flat:
        for h, lab in zip(*ax.get_legend_handles_labels()):
            if lab not in labels:
                handles.append(h)
                labels.append(lab)
    fig.legend(handles, labels, loc="lower center", ncol=4, fontsize=8)
    fig.suptitle("Each knob alone around the quick tier: change against the knob's finest "
                 "run vs cost (results/trade)")
    fig.tight_layout(rect=(0, 0.08, 1, 0.96))
    fig.savefig(path, dpi=110)


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--runs", default="/work/runs-trade", help="parent of the run directories")
    ap.add_argument("--out", default=os.path.join(ROOT, "results", "trade"))
    ap.add_argument("--only", help="comma-separated run tags (e.g. base-P,cellSize-0.05-WP)")
    ap.add_argument("--skip", help="comma-separated run tags not to start")
    ap.add_argument("--budget", type=float, default=5400, help="CPU s of all runs (default 5400)")
    ap.add_argument("--report-only", action="store_true", help="read finished runs, run nothing")
    ap.add_argument("--lambdas", action="store_true",
                    help="extract the drift coefficients of the finished mixture runs")
    a = ap.parse_args()
    runs = os.path.abspath(a.runs)
    if not a.report_only:
        only = set(a.only.split(",")) if a.only else None
        skip = set(a.skip.split(",")) if a.skip else set()
        for knob, value, scene in PLAN:
            t = tag(knob, value, scene)
            if (only and t not in only) or t in skip:
                continue
            if spent(runs) > a.budget:
                print(f"budget of {a.budget:.0f} CPU s spent: {t} not started", flush=True)
                continue
            os.makedirs(runs, exist_ok=True)
            run_one(knob, value, scene, runs)
    report(runs, a.out, a.lambdas and not a.report_only)


if __name__ == "__main__":
    main()
