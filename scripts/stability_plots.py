#!/usr/bin/python3
"""Plots and boundaries of results/stability from the sweeps' CSVs (stability_dem.py,
stability_drag.py): dem_step.png, drag_interval.png and the boundaries in boundaries.json.

DEM boundaries, per youngModulusFactor: the largest dt / T_R whose worst restitution error over the
impact set-ups (pair, wall; v_rel 1 and 3.4 m/s) stays within --de (absolute), the same for the
elastic contact's energy error |e^2 - 1| within --energy, and for the settling test the largest
dt / T_R with no grain lost and the first with grains lost.
Drag boundaries, per viscosity and integration: the largest s that is 'ok' with every smaller s
'ok', and the first s that is not.

  /usr/bin/python3 scripts/stability_plots.py --dir results/stability
"""
import argparse
import csv
import json
import math
import os
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


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


def drag(dirname):
    path = os.path.join(dirname, "drag_interval.csv")
    if not os.path.exists(path):
        return {}
    rows = list(csv.DictReader(open(path)))
    groups = defaultdict(list)
    for r in rows:
        groups[(f(r["mu"]), r["integration"])].append(r)
    out = {}
    mus = sorted({k[0] for k in groups})
    fig, axes = plt.subplots(1, len(mus), figsize=(4.2 * len(mus), 4), squeeze=False)
    for i, mu in enumerate(mus):
        ax = axes[0][i]
        for (m, integ), rs in sorted(groups.items()):
            if m != mu:
                continue
            rs.sort(key=lambda r: f(r["s"]))
            s = [f(r["s"]) for r in rs]
            y = [f(r["mean_over_ut"]) if r["status"] not in ("diverged", "diverged (run stopped)")
                 else math.nan for r in rs]
            ax.plot(s, y, "o-", label=integ)
            for r in rs:
                if r["status"].startswith("diverged"):
                    ax.plot(f(r["s"]), 1, "rx", ms=9)
            ok = []
            for r in rs:
                if r["status"] != "ok":
                    break
                ok.append(f(r["s"]))
            first_bad = next((f(r["s"]) for r in rs if r["status"] != "ok"), None)
            out.setdefault(f"{mu:g}", {})[integ] = {
                "largest_s_ok": max(ok) if ok else None, "first_s_not_ok": first_bad,
                "status": {r["s"]: r["status"] for r in rs}}
        ax.axhspan(0.97, 1.03, color="g", alpha=0.15)
        ax.set(xscale="log", xlabel="s = beta T / m", ylabel="settling speed / u_t",
               title=f"mu = {mu:g} Pa s (x: diverged)", ylim=(0, 3))
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
    a = ap.parse_args()
    res = {"dem": dem(a.dir, a.de, a.energy), "drag": drag(a.dir)}
    with open(os.path.join(a.dir, "boundaries.json"), "w") as fh:
        json.dump(res, fh, indent=1, sort_keys=True)
    print(json.dumps({k: {kk: {x: y for x, y in vv.items() if not isinstance(y, dict)}
                          for kk, vv in v.items()} for k, v in res.items()}, indent=1))


if __name__ == "__main__":
    main()
