"""Plots and boundaries of results/stability from the sweeps' CSVs (stability_dem.py,
stability_drag.py): dem_step.png, drag_interval.png and summary.json (the commands that made the
CSVs and this, and the boundaries).

DEM boundaries, per youngModulusFactor: the largest dt / T_R whose worst restitution error over the
impact set-ups (pair, wall; v_rel 1 and 3.4 m/s) stays within --de (absolute), the same for the
elastic contact's energy error |e^2 - 1| within --energy, and for the settling test the largest
dt / T_R with no grain lost and the first with grains lost.
Drag boundaries, per viscosity and integration: see drag().

  mixflow stability-plots --dir results/stability
"""
import argparse
import csv
import json
import math
import os
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt


COMMANDS = [
    "mixflow stability-dem --work /work/runs-stab/dem "
    "--csv results/stability/dem_step.csv --settle-time 0.6",
    "mixflow stability-drag --bin build/bin --work /work/runs-stab/drag "
    "--csv results/stability/drag_interval.csv --mu 1e-3,10,1e4 --s 0.3,1,1.8,2.2,5,100",
    "mixflow stability-plots --dir results/stability",
]


def f(x):
    try:
        return float(x)
    except (TypeError, ValueError):
        return math.nan


def dem(dirname, de, energy):
    rows = list(csv.DictReader(open(os.path.join(dirname, "dem_step.csv"))))
    factors = sorted({f(r["factor"]) for r in rows}, reverse=True)
    out = {}
    fig, ax = plt.subplots(1, 3, figsize=(15, 4.5))
    for fac in factors:
        mine = [r for r in rows if f(r["factor"]) == fac]
        fr = sorted({f(r["fraction"]) for r in mine})
        worst = {x: max(f(r["error"]) if math.isfinite(f(r["error"])) else math.inf
                        for r in mine if f(r["fraction"]) == x and r["test"] in ("pair", "wall"))
                 for x in fr}
        en = {x: max(abs(f(r["value"]) ** 2 - 1) if math.isfinite(f(r["value"])) else math.inf
                     for r in mine if f(r["fraction"]) == x and r["test"] == "elastic")
              for x in fr}
        tc = {x: max(f(r["dt_over_tc"]) for r in mine if f(r["fraction"]) == x and r["test"] != "settle")
              for x in fr}
        ok_e = [x for x in fr if all(worst[y] <= de for y in fr if y <= x)]
        ok_en = [x for x in fr if all(en[y] <= energy for y in fr if y <= x)]
        b = {"restitution_within": de, "largest_fraction_restitution_ok": max(ok_e) if ok_e else None,
             "its_dt_over_tc": tc[max(ok_e)] if ok_e else None,
             "energy_within": energy, "largest_fraction_energy_ok": max(ok_en) if ok_en else None,
             "worst_restitution_error": {str(x): worst[x] for x in fr},
             "elastic_energy_error": {str(x): en[x] for x in fr},
             "largest_dt_over_tc": {str(x): tc[x] for x in fr}}
        st = sorted((f(r["fraction"]), f(r["error"]), f(r["value"])) for r in mine if r["test"] == "settle")
        if st:
            held = [x for x, lost, _ in st if lost == 0]
            bad = [x for x, lost, _ in st if lost > 0]
            b["settle_largest_fraction_no_loss"] = max((x for x in held if not bad or x < min(bad)),
                                                       default=None)
            b["settle_first_fraction_lost"] = min(bad) if bad else None
            b["settle_lost"] = {str(x): lost for x, lost, _ in st}
            b["settle_max_overlap_over_d"] = {str(x): ov for x, _, ov in st}
            ax[2].plot([x for x, _, _ in st], [max(lost, 0.5) for _, lost, _ in st], "o-",
                       label=f"factor {fac:g}")
        out[f"{fac:g}"] = b
        ax[0].plot(fr, [worst[x] for x in fr], "o-", label=f"factor {fac:g}")
        ax[0].plot(fr, [en[x] for x in fr], "s--", alpha=0.6, label=f"factor {fac:g}, elastic |e²-1|")
        ax[1].plot([tc[x] for x in fr], [worst[x] for x in fr], "o-", label=f"factor {fac:g}")
    ax[0].axhline(de, color="k", lw=0.8)
    ax[0].set(xscale="log", yscale="log", xlabel="dt / T_R", ylabel="worst |e - e_ref| (pair, wall)",
              title="restitution and energy error of one contact")
    ax[1].axhline(de, color="k", lw=0.8)
    ax[1].set(xscale="log", yscale="log", xlabel="dt / t_Hertz (largest over the set-ups)",
              ylabel="worst |e - e_ref|", title="the same against the contact time")
    ax[2].set(xscale="log", yscale="log", xlabel="dt / T_R", ylabel="grains lost of 200 (0 drawn at 0.5)",
              title="pour and settle, 200 grains, 0.6 s")
    for a in ax:
        a.legend(fontsize=7)
        a.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(dirname, "dem_step.png"), dpi=110)
    return out


def drag(dirname, tol):
    """Per viscosity and integration: the largest s whose settling speed stays within tol of the
    reference (every smaller s too), the first s beyond, and whether it diverged. The reference is
    the same viscosity's implicit run at the smallest s: the unresolved set-up's own offset from
    u_t (the grain's momentum source moves its cell's fluid; +0.9 % in water, +5 % at 10 Pa s) is
    the same for every integration there. Speeds of the limited held drag are also compared with
    max(1, s / 0.5) (its clamp)."""
    path = os.path.join(dirname, "drag_interval.csv")
    if not os.path.exists(path):
        return {}
    rows = [r for r in csv.DictReader(open(path)) if not r["status"].startswith("not run")]
    groups = defaultdict(list)
    for r in rows:
        groups[(f(r["mu"]), r["integration"])].append(r)
    out = {}
    mus = sorted({k[0] for k in groups})
    fig, axes = plt.subplots(1, len(mus), figsize=(4.2 * len(mus), 4), squeeze=False)
    for i, mu in enumerate(mus):
        ax = axes[0][i]
        imp = sorted(groups.get((mu, "implicit"), []), key=lambda r: f(r["s"]))
        ref = f(imp[0]["mean_over_ut"]) if imp else 1.0
        for (m, integ), rs in sorted(groups.items()):
            if m != mu:
                continue
            rs.sort(key=lambda r: f(r["s"]))
            s = [f(r["s"]) for r in rs]
            div = [r["status"].startswith("diverged") and not
                   (integ == "held_limited" and math.isfinite(f(r["mean_over_ut"])))
                   for r in rs]
            y = [math.nan if d else f(r["mean_over_ut"]) / ref for r, d in zip(rs, div)]
            ax.plot(s, y, "o-", label=integ)
            for x, d in zip(s, div):
                if d:
                    ax.plot(x, 1, "rx", ms=9)
            good = [not d and abs(v - 1) <= tol for v, d in zip(y, div)]
            ok = []
            for x, g in zip(s, good):
                if not g:
                    break
                ok.append(x)
            bad = [(x, "diverged" if d else f"{100 * (v - 1):+.1f} %")
                   for x, v, d, g in zip(s, y, div, good) if not g]
            entry = {"largest_s_within": max(ok) if ok else None,
                     "first_s_beyond": bad[0][0] if bad else None,
                     "first_beyond_how": bad[0][1] if bad else None,
                     "speed_over_reference": {str(x): v for x, v in zip(s, y)},
                     "diverged_at": [x for x, d in zip(s, div) if d]}
            if integ == "held_limited":
                entry["speed_over_clamp_prediction"] = {
                    str(x): v / max(1.0, x / 0.5) for x, v in zip(s, y)}
            out.setdefault(f"{mu:g}", {"reference_mean_over_ut": ref})[integ] = entry
        ax.axhspan(1 - tol, 1 + tol, color="g", alpha=0.15)
        ax.set(xscale="log", yscale="log", xlabel="s = beta T / m",
               ylabel="settling speed / (implicit at the smallest s)",
               title=f"mu = {mu:g} Pa s (x: diverged)")
        ax.legend(fontsize=7)
        ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(dirname, "drag_interval.png"), dpi=110)
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--dir", default="results/stability")
    ap.add_argument("--de", type=float, default=0.01, help="restitution error bound (absolute)")
    ap.add_argument("--energy", type=float, default=0.01, help="elastic contact energy error bound")
    ap.add_argument("--drag-tol", type=float, default=0.03, help="settling speed bound (relative)")
    a = ap.parse_args()
    res = {"commands": COMMANDS, "dem": dem(a.dir, a.de, a.energy), "drag": drag(a.dir, a.drag_tol)}
    with open(os.path.join(a.dir, "summary.json"), "w") as fh:
        json.dump(res, fh, indent=1, sort_keys=True)
    print(json.dumps({k: {kk: {x: y for x, y in vv.items() if not isinstance(y, dict)}
                          for kk, vv in v.items()} for k, v in res.items() if k != "commands"},
                     indent=1))


if __name__ == "__main__":
    main()
