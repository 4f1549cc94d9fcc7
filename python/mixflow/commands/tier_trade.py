"""The speed/accuracy trade of one scene across fidelity tiers (docs/suite.md).

usage: tier_trade.py [--scene HB+P] [--tiers quick=runs/quick,reference=runs/reference]
                     [--times 0.1,0.2,0.3,0.5,1,1.5]
                     [--paper-cost results/li_zhao_2018/cost_paper.json]
                     [--paper-physics results/bench/coupled_vs_dry_paper_dem.json]
                     [--out results/li_zhao_2018]

For each tier whose run of the scene finished (mixflow suite writes WORK/<scene>/.done): the
wall time, ranks and core-seconds per simulated second, and the observables of the report at
the --times (fronts, the grains' released potential energy and kinetic energy per metre of
width, the liquid's E_fc, the back-wall height / H, the subcritical time). Then how far each
observable moves from each tier to the next one listed (list them from cheapest to dearest). A
short window (cases/tiers/paper-window: the paper's stiffness and steps, 0.3 s) has rows up to
its end only. The full paper tier cannot run here (26 core-hours per mixture): its row is the
measured cost per simulated second and the extrapolated core-hours (mixflow suite --tier
paper), and, if given, the bench run with the
paper's modulus, DEM step and exchange interval on the quick bench geometry
(bench/coupled_vs_dry.py --young-modulus-factor 1 --dem-step 5e-7 --exchange-every 100).
Writes OUT/tier_trade.json and OUT/tier_trade.md.
"""
import argparse
import json
import os
import shlex
import sys

import numpy as np

from mixflow import observables as obs
from mixflow.outputs import interpolated as at

TIMES = (0.1, 0.2, 0.3, 0.5, 1.0, 1.5)  # default --times
SCALARS = ("arrival_at_1.38m_s", "subcritical_after_arrival_s", "energy_excess_J_per_m")


def read(rows, key, label):
    """rows[key] at t = label, or at the last row if the series ends within 0.01 s before it."""
    return at(rows, key, min(label, rows[-1]["time_s"]))


def observables(s, times):
    """Observables of one finished scene at times (a time the run does not reach is left out)."""
    out = {}
    pe = obs.particle_energies(s)
    efc = obs.e_fc(s)
    t_end = s.t_end()
    for label in times:
        # A run that ended within 0.01 s of a time (endTime 1.5 s stops at 1.4994 s) counts as
        # reaching it, read at its last row.
        if t_end is None or t_end < label - 0.01:
            continue
        t = min(label, t_end)
        o = {}
        if s.liquid:
            o["liquid_front_m"] = read(s.liquid, "front_bed_m", t)
            o["liquid_depth_front_m"] = obs.liquid_depth_front(s, t)
            o["back_wall_height_over_H"] = obs.back_wall(s, t)
        if efc is not None:
            o["E_fc"] = float(np.interp(t, *efc))
        if s.dem:
            o["granular_front_m"] = read(s.dem, "front_x_m", t)
            # The body's front (where the mean column top falls below d): blind to single grains
            # run ahead on a wide sample, not on a slice of 2-3 columns (obs.deposit_tail).
            o["granular_thickness_front_m"] = read(s.dem, "front_thickness_x_m", t)
        if pe is not None:
            tt, ek, ep = pe
            o["particle_pe_released_J_per_m"] = float(ep[0] - np.interp(t, tt, ep))
            o["particle_ke_J_per_m"] = float(np.interp(t, tt, ek))
        out[f"{label:g}s"] = o
    t0, sub = obs.subcritical(s)
    out["arrival_at_1.38m_s"] = t0
    out["subcritical_after_arrival_s"] = sub
    # The energy the run made (obs.energy_excess): a scheme that is not converged in the
    # tier's step or interval shows here first.
    ex = obs.energy_excess(s)
    out["energy_excess_J_per_m"] = None if ex is None else ex["excess_J_per_m"]
    return out


def tier_row(work, scene, times):
    s = obs.Scene(work, scene)
    if not s.done:
        return None
    with open(os.path.join(s.dir, ".done")) as f:
        done = json.load(f)
    sim = done.get("simulated_s") or s.t_end()
    return {"work": work, "tier": s.tier, "width_m": s.width, "wall_s": done["wall_s"],
            "ranks": done["ranks"], "simulated_s": sim,
            "core_s_per_simulated_s": done["wall_s"] * done["ranks"] / sim,
            "observables": observables(s, times)}


def changes(base, other):
    """other - base for every observable both have (same time key)."""
    d = {}
    for tk, ob in other["observables"].items():
        if not isinstance(ob, dict) or tk not in base["observables"]:
            continue
        for k, v in ob.items():
            b = base["observables"][tk].get(k)
            if v is not None and b is not None:
                d.setdefault(tk, {})[k] = v - b
    for k in SCALARS:
        a, b = other["observables"].get(k), base["observables"].get(k)
        d[k] = None if a is None or b is None else a - b
    return d


def markdown(res):
    tiers = [t for t in res["tiers"] if res["tiers"][t]]
    lines = [f"# {res['scene']} across fidelity tiers", "",
             f"Made by `{res['command']}`.", "",
             "| tier | ranks | wall (s) | simulated (s) | core-s per simulated s |",
             "|---|---|---|---|---|"]
    for t in tiers:
        r = res["tiers"][t]
        lines.append(f"| {t} | {r['ranks']} | {r['wall_s']:.0f} | {r['simulated_s']:.3g} | "
                     f"{r['core_s_per_simulated_s']:.3g} |")
    p = res.get("paper")
    if p:
        lines.append(f"| paper (not run: estimate) | {p['measured_ranks']} | - | "
                     f"{p['end_time_s']:g} | {p['core_s_per_simulated_s']:.3g} "
                     f"({p['core_hours']:.1f} core-h for the scene) |")
    lines += ["", "| observable | t | " + " | ".join(tiers) + " | change |",
              "|---|---|" + "---|" * (len(tiers) + 1)]
    steps = [f"{b}_minus_{a}" for a, b in zip(tiers, tiers[1:])]
    for tk in [f"{t:g}s" for t in res["times_s"]]:
        keys = sorted({k for t in tiers for k in res["tiers"][t]["observables"].get(tk, {})})
        for k in keys:
            vals = [res["tiers"][t]["observables"].get(tk, {}).get(k) for t in tiers]
            ch = [res["changes"].get(st, {}).get(tk, {}).get(k) for st in steps]
            lines.append(f"| {k} | {tk} | " + " | ".join(obs.fmt(v) for v in vals) + " | " +
                         ", ".join(obs.fmt(c) for c in ch) + " |")
    for k in SCALARS:
        vals = [res["tiers"][t]["observables"].get(k) for t in tiers]
        ch = [res["changes"].get(st, {}).get(k) for st in steps]
        lines.append(f"| {k} | - | " + " | ".join(obs.fmt(v) for v in vals) + " | " +
                     ", ".join(obs.fmt(c) for c in ch) + " |")
    pp = res.get("paper_physics_on_bench_geometry")
    if pp:
        lines += ["", "Paper modulus, DEM step and exchange interval on the bench's quick geometry "
                  f"(`{pp['command']}`): see the JSON; it answers what the softening and the "
                  "interval do, not what the full-width scene gives."]
    lines += ["", "Change: each tier minus the one listed before it (" + ", ".join(
        f"{b} - {a}" for a, b in zip(tiers, tiers[1:])) + "); '-' where either lacks the "
        "value (a window ends before the time). Energies per metre of width (the tiers' "
        "slices differ in width)."]
    return "\n".join(lines) + "\n"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scene", default="HB+P")
    ap.add_argument("--tiers", default="quick=runs/quick,reference=runs/reference")
    ap.add_argument("--times", default=",".join(f"{t:g}" for t in TIMES),
                    help="comma-separated times (s) of the observables")
    ap.add_argument("--paper-cost", default="results/li_zhao_2018/cost_paper.json")
    ap.add_argument("--paper-physics", help="a bench/coupled_vs_dry.py JSON run at the paper's "
                    "modulus and steps")
    ap.add_argument("--out", default="results/li_zhao_2018")
    a = ap.parse_args(argv)
    times = [float(t) for t in a.times.split(",")]
    res = {"scene": a.scene, "times_s": times, "tiers": {}, "changes": {},
           "command": shlex.join(["mixflow", "tier-trade"] + (argv or sys.argv[1:]))}
    for spec in a.tiers.split(","):
        name, work = spec.split("=")
        res["tiers"][name] = tier_row(work, a.scene, times)
    done = [t for t in res["tiers"] if res["tiers"][t]]
    if not done:
        sys.exit(f"tier_trade.py: no finished {a.scene} in {a.tiers}")
    for lo, hi in zip(done, done[1:]):
        res["changes"][f"{hi}_minus_{lo}"] = changes(res["tiers"][lo], res["tiers"][hi])
    if a.paper_cost and os.path.isfile(a.paper_cost):
        with open(a.paper_cost) as f:
            cost = json.load(f)
        sc = cost["scenes"].get(a.scene)
        content = sc["content"] if sc else None
        m = cost["measured"].get(content) if content else None
        if sc and m:
            res["paper"] = {"source": a.paper_cost, "core_hours": sc["core_hours"],
                            "end_time_s": sc["end_time_s"], "measured_scene": m["scene"],
                            "measured_ranks": m["ranks"],
                            "core_s_per_simulated_s": sc["core_hours"] * 3600 / sc["simulated_s"]}
    if a.paper_physics:
        with open(a.paper_physics) as f:
            res["paper_physics_on_bench_geometry"] = json.load(f)
    os.makedirs(a.out, exist_ok=True)
    with open(os.path.join(a.out, "tier_trade.json"), "w") as f:
        json.dump(obs.clean(res), f, indent=2)
        f.write("\n")
    with open(os.path.join(a.out, "tier_trade.md"), "w") as f:
        f.write(markdown(res))
    print(markdown(res))


if __name__ == "__main__":
    main()
