#!/usr/bin/env python3
"""Collects coupled_vs_dry.py results into one table of the HB&P answer against the exchange
interval T (coupling/README.md, "Exchange interval").

usage: interval_table.py [JSON ...] [--out results/bench/interval_convergence]

Default inputs: results/bench/coupled_vs_dry*.json with case HB's liquid. Writes OUT.csv (one
row per coupled run: scheme, DEM step, steps per exchange N, T = N x DEM step, Young's modulus
factor, the observables at 1 s, CPU ratio against the dry twin) and OUT.png (the grains' released
potential energy and mean x at 1 s against T, one series per scheme and modulus).
"""
import argparse
import csv
import glob
import json
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
T_R_SOFT = 3.92507786459e-4  # Rayleigh time of the bench's grains at youngModulusFactor 1e-3 (s)
KEYS = ("particle_pe_released_J_at_1s", "particle_mean_x_m_at_1s", "granular_front_m_at_1s",
        "liquid_front_m_at_1s", "particle_ke_J_at_1s")


def dem_settings(res):
    """(Young's modulus factor, DEM step) of a result; older files name only rayleigh_fraction."""
    dd = res.get("dem_dict", {})
    factor = float(dd.get("youngModulusFactor", 1e-3))
    step = dd.get("timeStep", "auto")
    if step != "auto":
        return factor, float(step)
    rf = float(dd.get("rayleighFraction", res.get("rayleigh_fraction", 0.1)))
    return factor, rf * T_R_SOFT * (factor / 1e-3) ** -0.5


def rows_of(path):
    with open(path) as f:
        res = json.load(f)
    if "case HB's liquid" not in res.get("scene", ""):
        return []
    factor, step = dem_settings(res)
    out = []
    for r in res["runs"]:
        dt = r.get("dem_step_s", step)
        row = {"file": os.path.relpath(path, ROOT),
               "scheme": res.get("drag_fluid_response", "none"),
               "drag_integration": res.get("drag_integration", "implicit"),
               "young_modulus_factor": factor, "dem_step_s": dt,
               "exchange_every": r["exchange_every"], "exchange_interval_s": r["exchange_every"] * dt,
               "ratio_coupled_over_dry": r["ratio_coupled_over_dry"]}
        row.update({k: r["observables"].get(k) for k in KEYS})
        out.append(row)
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("files", nargs="*")
    ap.add_argument("--out", default=os.path.join(ROOT, "results", "bench", "interval_convergence"))
    a = ap.parse_args()
    files = a.files or sorted(glob.glob(os.path.join(ROOT, "results", "bench", "coupled_vs_dry*.json")))
    rows = [r for p in files for r in rows_of(p) if r["drag_integration"] == "implicit"]
    rows.sort(key=lambda r: (r["scheme"], r["young_modulus_factor"], r["exchange_interval_s"]))
    with open(a.out + ".csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    series = sorted({(r["scheme"], r["young_modulus_factor"]) for r in rows})
    for scheme, factor in series:
        pts = [r for r in rows if (r["scheme"], r["young_modulus_factor"]) == (scheme, factor)]
        t = [r["exchange_interval_s"] for r in pts]
        lab = f"dragFluidResponse {scheme}, E x {factor:g}"
        for ax, key in zip(axes, KEYS[:2]):
            ax.semilogx(t, [r[key] for r in pts], "o-" if factor != 1 else "s", label=lab)
    for ax, yl in zip(axes, ("grains' potential energy released by 1 s (J)",
                             "mean grain x at 1 s (m)")):
        ax.set_xlabel("exchange interval T = N x DEM step (s)")
        ax.set_ylabel(yl)
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.suptitle("Quick HB&P bench scene (813 grains): the answer against the exchange interval")
    fig.tight_layout()
    fig.savefig(a.out + ".png", dpi=110)
    for r in rows:
        print(f"{r['scheme']:5s} E x {r['young_modulus_factor']:<6g} dt {r['dem_step_s']:.3g} "
              f"N {r['exchange_every']:4d} T {r['exchange_interval_s']:.3g} s: "
              f"PE {r['particle_pe_released_J_at_1s']:.3g} J, mean x "
              f"{r['particle_mean_x_m_at_1s']:.3f} m, ratio {r['ratio_coupled_over_dry']:.3g}")


if __name__ == "__main__":
    main()
