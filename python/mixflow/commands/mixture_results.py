"""results/mixtures/: fronts, Froude and Savage numbers of the three mixture scenes from a
suite work directory, and summary.json with the paper's numbers beside ours.

    mixflow mixture-results [--work runs/reference] [--out results/mixtures] [--partner WORK]

--work and --partner take several directories, comma-separated: each scene is read from the
first where it finished. --partner holds the same scenes with one speed knob one step finer (for
the truth tier: the exchange interval); each scene's observables then carry their convergence
error, the partner's value minus this one's (summary.json: scenes.<scene>.observables and
.convergence_error). The drifts beside OUT are carried into summary.json: lambdas.json (mixflow
mixture-lambdas) as `lambdas`, and lambda_convergence/<scene>-every<N>.json (the drifts of a
shorter run and of its partner one exchange step finer, results/mixtures/truth/lambda_pairs.sh)
as `lambdas_convergence`, with the convergence error once both are there.

Rules (the same as mixflow report's, from mixflow.observables):
  - subcritical after arrival: t0 = the liquid front (bed row, alpha >= 0.5) reaching x = 1.38 m;
    the first time after t0 from which Fr < 1 holds for HOLD_S (python/mixflow/froude.py), minus t0.
    Coarse mixture meshes thin the front below alpha = 0.5 before the section; then the arrival is
    the first time the section holds liquid (a defined Froude number), labelled as such.
  - Savage collisional interval: the longest run of savage_paper > 0.1 at x = 0.8 m (Eq. 16 as
    printed, d_p); Iverson's form (d_p^2/h) is plotted beside it.
"""

import argparse
import glob
import json
import math
import os

import numpy as np

from mixflow import observables as obs
from mixflow.commands import mixture_lambdas as ml
from mixflow.commands import suite
from mixflow.commands.tier_trade import observables
from mixflow.froude import first_time, subcritical_from
from mixflow.paper import MIXTURES, PAPER, PAPER_NAME, SECTION_X

PAPER_SUBCRITICAL = {PAPER_NAME[n]: PAPER["subcritical"][n] for n in MIXTURES}
PAPER_SAVAGE_B = list(PAPER["savage_interval_BP"])
TIMES = (0.5, 1.0, 2.0, 3.0)  # the and the paper's observation times (s)


def savage_window(s):
    """The longest run of N_sav > 0.1 at x = 0.8 m (Eq. 16 as printed), None without one."""
    sv = obs.savage(s)
    return obs.collision_interval(sv[0], np.nan_to_num(sv[1], nan=0.0)) if sv else None


def scene_observables(s):
    """Fronts, energies and back-wall height at TIMES, arrival, subcritical time and the longest
    Savage collisional interval at x = 0.8 m."""
    row = observables(s, TIMES)
    window = savage_window(s)
    row["savage_interval_s"] = list(window) if window else None
    return row


def arrival_and_subcritical(s):
    rows = s.liquid
    rule = "liquid front (bed row, alpha >= 0.5) at x = 1.38 m"
    t0 = first_time(rows, lambda r: r["front_bed_m"] >= SECTION_X)
    if t0 is None:
        rule = "first liquid at the section x = 1.38 m (the bed-row front stays below alpha = 0.5)"
        t0 = first_time(rows, lambda r: not math.isnan(r["section_froude"]))
    if t0 is None:
        return None, None, rule
    ts = subcritical_from(rows, t0)
    return t0, (None if ts is None else ts - t0), rule


def write_observables_csv(path, scenes):
    """One row per scene, time and observable with its convergence error (empty without one)."""
    with open(path, "w") as f:
        f.write("scene,time_s,observable,value,convergence_error\n")
        for p, rec in scenes.items():
            o, e = rec["observables"], rec.get("convergence_error", {})
            for key, v in o.items():
                if isinstance(v, dict):
                    for q, x in v.items():
                        err = e.get(key, {}).get(q, "")
                        f.write(f"{p},{key[:-1]},{q},{x},{err}\n")
                elif isinstance(v, float):
                    f.write(f"{p},,{key},{v},{e.get(key, '')}\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--work", default="runs/reference")
    ap.add_argument("--out", default="results/mixtures")
    ap.add_argument("--partner", default="",
                    help="the same scenes with one speed knob one step finer (convergence error)")
    a = ap.parse_args()

    def absolute(p):
        return p if os.path.isabs(p) else os.path.join(suite.ROOT, p)
    works, out = [absolute(w) for w in a.work.split(",")], absolute(a.out)
    partners = [absolute(w) for w in a.partner.split(",") if w]
    os.makedirs(out, exist_ok=True)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    scenes = {n: obs.first_finished(works, n) for n in MIXTURES}
    done = {n: s for n, s in scenes.items() if s.done}
    command = (f"mixflow mixture-results --work {a.work} --out {a.out}"
               + (f" --partner {a.partner}" if a.partner else ""))
    summary = {"command": command, "work": ", ".join(works), "partner": ", ".join(partners),
               "scenes": {}, "subcritical_after_arrival_s": {},
               "subcritical_arrival_rule": {}, "savage_collisional_interval_s": {},
               "paper": {"subcritical_after_arrival_s": PAPER_SUBCRITICAL,
                         "savage_collisional_interval_s": {"B&P": PAPER_SAVAGE_B},
                         "savage_order": "B&P > P ~ HB&P > W&P"}}
    fig, ax = plt.subplots(1, 3, figsize=(15, 4.2))
    for n, s in done.items():
        p = PAPER_NAME[n]
        t0, sub, rule = arrival_and_subcritical(s)
        summary["subcritical_after_arrival_s"][p] = sub
        summary["subcritical_arrival_rule"][p] = rule
        t, x = obs.granular_front(s)
        tl, xl = obs.liquid_front(s)
        ax[0].plot(tl, xl, label=f"{p} liquid")
        ax[0].plot(t, x, "--", label=f"{p} granular")
        tf = obs.col(s.liquid, "time_s")
        ax[1].plot(tf - (t0 or 0), obs.col(s.liquid, "section_froude"), label=p)
        sv = obs.savage(s)
        iv = obs.col(s.dem, "savage_iverson")
        if sv:
            ax[2].plot(sv[0], sv[1], label=f"{p} (Eq. 16, d)")
            ax[2].plot(sv[0], iv, ":", label=f"{p} (Iverson, d²/h)")
            summary["savage_collisional_interval_s"][p] = savage_window(s)
        summary["scenes"][p] = {
            "tier": s.tier, "case": n, "width_m": s.width,
            "simulated_to_s": s.t_end(), "liquid_arrival_at_1.38m_s": t0,
            "granular_front_end_m": float(x[-1]), "liquid_front_end_m": float(xl[-1]),
            "liquid_outflow_m3": s.liquid[-1]["volume_outlet_m3"],
            "liquid_volume_balance_worst": float(np.nanmax(np.abs(obs.col(s.liquid, "volume_balance")))),
            "sample_solid_fraction": (s.summary or {}).get("settled", {}).get("sample_solid_fraction"),
            "observables": scene_observables(s),
        }
        partner = obs.first_finished(partners, n) if partners else None
        if partner is not None and partner.done:
            rec = summary["scenes"][p]
            rec["partner_tier_set"] = partner.tier_set
            rec["convergence_error"] = obs.convergence_error(rec["observables"], scene_observables(partner))
    ax[0].set(xlabel="t (s)", ylabel="front x (m)", title="liquid and granular fronts")
    ax[1].axhline(1, color="k", lw=0.8)
    ax[1].set(xlabel="t - t0 (s)", ylabel="Fr at x = 1.38 m", title="liquid Froude number", ylim=(0, 5))
    ax[2].axhline(0.1, color="k", lw=0.8)
    ax[2].set(xlabel="t (s)", ylabel="N_sav at x = 0.8 m", yscale="log", title="Savage number")
    for a_ in ax:
        a_.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "mixtures.png"), dpi=110)
    summary["missing"] = [PAPER_NAME[n] for n in scenes if n not in done]
    # The drifts of the same runs (mixflow mixture-lambdas --out OUT/lambdas.json), kept beside
    # the observables whether the drifts or the observables were made last.
    lam = os.path.join(out, "lambdas.json")
    if os.path.isfile(lam):
        with open(lam) as f:
            drifts = json.load(f)
        summary["lambdas"], summary["lambdas_command"] = drifts["scenes"], drifts["command"]
    # The drifts' convergence error: per scene a run and its partner one exchange step finer,
    # each's drifts in lambda_convergence/<scene>-every<N>.json (lambda_pairs.sh there).
    pairs = {}
    for path in glob.glob(os.path.join(out, "lambda_convergence", "*-every*.json")):
        every = int(os.path.splitext(path)[0].rsplit("-every", 1)[1])
        with open(path) as f:
            drifts = json.load(f)
        for name, rec in drifts["scenes"].items():
            pairs.setdefault(name, {})[every] = dict(rec, command=drifts["command"])
    for name, runs in sorted(pairs.items()):
        coarse, fine = max(runs), min(runs)
        entry = {f"every{n}": runs[n] for n in sorted(runs)}
        if fine < coarse:
            entry["convergence_error"] = ml.drifts_error(runs[coarse], runs[fine])
            entry["convergence_error_of"] = f"every{fine} minus every{coarse}"
        summary.setdefault("lambdas_convergence", {})[name] = entry
    write_observables_csv(os.path.join(out, "observables.csv"), summary["scenes"])
    with open(os.path.join(out, "summary.json"), "w") as f:
        json.dump(obs.clean(summary), f, indent=2)
        f.write("\n")
    print(json.dumps(obs.clean({k: summary[k] for k in
                                   ("subcritical_after_arrival_s", "savage_collisional_interval_s",
                                    "missing")})))


if __name__ == "__main__":
    main()
