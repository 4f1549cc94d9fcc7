"""Report of the Table 1 scenes run by mixflow suite (docs/suite.md).

usage: report.py [--work runs/reference[,runs/quick,...]] [--out results/li_zhao_2018]
                 [--bulk-work runs/bulk] [--partner WORK[,WORK...]]

Reads the finished scenes (WORK/<scene>/.done; with several work directories, each scene from the
first one where it finished, so a report can take each scene from the best tier that ran it) and
writes OUT/report.md, OUT/*.png and
OUT/summary.json: liquid and granular fronts, relative velocities, kinetic energies, E_pd and E_fc
(Eqs. 13-14), fluid-particle forces, Froude and Savage numbers, profiles at t = 0.63 and 0.75 s,
dry deposits and the runout law, HB-I/B-I normalised fronts, and the table "the paper says / we
get" for the numbers of docs/model.md §8. A scene that is not finished is listed as such; a
figure or number that the finished scenes do not allow says so instead of stopping the report.
With the bulk model's runs of the mixtures (--bulk-work, the suite's bulk tier), a section puts
its numbers beside the CFD-DEM ones. With --partner (the mixtures again with one speed knob one
step finer), every row that a mixture enters is built again from the partner's runs: the row
carries the partner's value and their difference (its convergence error), and a verdict that
the partner's runs turn over is no verdict ("not converged").
"""

import argparse
import csv
import functools
import json
import os
import re
import sys
import traceback

import numpy as np

from mixflow.commands import suite  # (scene list, dictionary reader)
from mixflow import outputs, schema
from mixflow.froude import HOLD_S
from mixflow.observables import (
    clean, col, fmt, first_finished, Scene, vtk_series, vtk_points, granular_surface, liquid_front,
    granular_front, subcritical, subcritical_volume_depth, back_wall_key,
    back_wall, particle_energies, energy_excess, e_pd, e_fc, savage,
    collision_interval, stage_change, outflow_start, runout_law)
from mixflow.paper import (DRY_SERIES, L_SLUMP, LIQUIDS, MIXTURES, PAPER,  # noqa: F401
                           PAPER_NAME, PROFILE_TIMES, SECTION_X, T_SLUMP)

STYLE = {"W": ("C0", "-"), "HB": ("C1", "-"), "B": ("C2", "-"), "P": ("k", "-"),
         "W+P": ("C0", "--"), "HB+P": ("C1", "--"), "B+P": ("C2", "--"),
         "HB-I": ("C1", "-"), "B-I": ("C2", "-")}


# --------------------------------------------------------------------------------------------
# Figures

class Figures:
    """Each figure is made by one function; what cannot be drawn is recorded, not raised."""

    def __init__(self, out):
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        self.plt, self.out = plt, out
        self.made, self.skipped = [], []

    def make(self, name, title, fn):
        try:
            fig = fn()
        except Exception as e:  # noqa: BLE001  a report never stops on one figure
            self.skipped.append((name, f"error: {e}"))
            traceback.print_exc()
            return
        if isinstance(fig, str) or fig is None:
            self.skipped.append((name, fig or "no data"))
            return
        fig.tight_layout()
        fig.savefig(os.path.join(self.out, name), dpi=110)
        self.plt.close(fig)
        self.made.append((name, title))

    def axes(self, n=1, w=6.4, h=4.2):
        fig, ax = self.plt.subplots(1, n, figsize=(w * n if n > 1 else w, h), squeeze=False)
        return fig, ax[0]


def label(s):
    return f"{s.paper_name} ({s.tier})"


def draw(ax, items, labels, hline=None):
    """One line per (scene, t, y) of ITEMS on AX; LABELS = (xlabel, ylabel, title)."""
    for s, t, y in items:
        c, ls = STYLE.get(s.name, (None, "-"))
        ax.plot(t, y, ls, color=c, label=label(s))
    if hline is not None:
        ax.axhline(hline, color="grey", lw=0.6)
    ax.set(xlabel=labels[0], ylabel=labels[1], title=labels[2])
    legend(ax)


def plot_curves(F, items, xlabel, ylabel, title, hline=None, ylim=None):
    """items: [(scene, t, y)]; one line each. None when there are none."""
    if not items:
        return None
    fig, (ax,) = F.axes()
    draw(ax, items, (xlabel, ylabel, title), hline)
    if ylim:
        ax.set_ylim(*ylim)
    return fig


def plot_pair(F, left, right, left_axes, right_axes, hline=None):
    """Two panels side by side; LEFT/RIGHT: [(scene, t, y)]; *_AXES: (xlabel, ylabel, title).
    None when both are empty."""
    if not left and not right:
        return None
    fig, axs = F.axes(2)
    draw(axs[0], left, left_axes, hline)
    draw(axs[1], right, right_axes, hline)
    return fig


def fig_profiles(F, scenes, times):
    """Liquid surface h(x) (profiles.csv, nearest write time) and granular surface (nearest
    particle snapshot) at each of TIMES, normalised by H."""
    fig, axs = F.axes(len(times))
    drawn = 0
    for ax, t in zip(axs, times):
        for s in scenes.values():
            if not s.done:
                continue
            c, ls = STYLE.get(s.name, (None, "-"))
            if s.profiles and s.name not in ("HB-I", "B-I"):
                tw = sorted({r["time_s"] for r in s.profiles}, key=lambda v: abs(v - t))[0]
                if abs(tw - t) <= 0.06:
                    rows = [r for r in s.profiles if r["time_s"] == tw]
                    key = "surface_m" if "surface_m" in rows[0] else "depth_m"
                    ax.plot(col(rows, "x_m"), col(rows, key) / s.H, ls, color=c,
                            label=f"{s.paper_name} liquid, t = {tw:.2f} s")
                    drawn += 1
            if s.content in ("particles", "mixture") and s.name in ("P",) + tuple(MIXTURES):
                snaps = vtk_series(s.dir)
                if snaps:
                    tw, path = min(snaps, key=lambda e: abs(e[0] - t))
                    if abs(tw - t) <= 0.06:
                        x, h = granular_surface(vtk_points(path), 4.0)
                        ax.plot(x, h / s.H, ":" if s.content == "mixture" else "-", color=c, lw=1.2,
                                label=f"{s.paper_name} grains, t = {tw:.2f} s")
                        drawn += 1
        ax.set(xlabel="x (m)", ylabel="h / H", title=f"surfaces near t = {t} s", xlim=(0, 4))
        legend(ax)
    return fig if drawn else "no profile written within 0.06 s of these times"


def make_figures(F, sc, fin, law):
    liq = [sc[n] for n in LIQUIDS + MIXTURES if sc[n].done and sc[n].liquid]
    gran = [sc[n] for n in ["P"] + MIXTURES if sc[n].done and sc[n].dem]
    mix = [sc[n] for n in MIXTURES if sc[n].done]
    F.make("fronts_liquid.png", "Liquid fronts (bed row, alpha >= 0.5)", lambda: plot_curves(
        F, [(s, *liquid_front(s)) for s in liq], "t (s)", "liquid front x_f (m)", "Liquid fronts"))
    F.make("fronts_granular.png", "Granular fronts (largest connected cluster)", lambda: plot_curves(
        F, [(s, *granular_front(s)) for s in gran], "t (s)", "granular front (m)", "Granular fronts"))

    def relvel():
        pairs = [(s, te, {c: np.interp(te, col(s.liquid, "time_s"), col(s.liquid, f"mean_u{c}_m_s"))
                          - col(s.exchange, f"meanV{c}") for c in "xy"})
                 for s in mix if s.liquid and s.exchange for te in [col(s.exchange, "time")]]
        return plot_pair(F, [(s, t, dv["x"]) for s, t, dv in pairs], [(s, t, dv["y"]) for s, t, dv in pairs],
                         ("t (s)", "mean u_x liquid - mean v_x particles (m/s)", "relative velocity, x"),
                         ("t (s)", "mean u_y liquid - mean v_y particles (m/s)", "relative velocity, y"),
                         hline=0) or "needs a finished mixture scene (liquid time series and coupling/exchange.csv)"
    F.make("relative_velocity.png", "Mean liquid minus mean particle velocity (mixtures)", relvel)

    F.make("kinetic_energies.png", "Kinetic energies of particles and liquid (per metre of width)",
           lambda: plot_pair(
               F, [(s, *particle_energies(s)[:2]) for s in gran],
               [(s, col(s.liquid, "time_s"), col(s.liquid, "kinetic_energy_J") / s.width) for s in liq],
               ("t (s)", "E_kp per metre of width (J/m)", "particles"),
               ("t (s)", "E_kf per metre of width (J/m)", "liquid")))

    def epd_efc():
        left = []
        if sc["P"].done:
            left = [(s, *r) for s in mix for r in [e_pd(s, sc["P"])] if r is not None and len(r[0])]
        return plot_pair(F, left, [(s, *e_fc(s)) for s in liq],
                         ("t (s)", "E_pd (Eq. 13)", "particle energy dissipation vs dry P"),
                         ("t (s)", "E_fc (Eq. 14)", "liquid energy consumed"))
    F.make("epd_efc.png", "E_pd (Eq. 13, mixtures against dry P) and E_fc (Eq. 14)", epd_efc)

    F.make("interaction_forces.png", "Total fluid-particle force on the liquid (x, y)", lambda: plot_pair(
        F, [(s, col(s.exchange, "time"), col(s.exchange, "Ff_x")) for s in mix if s.exchange],
        [(s, col(s.exchange, "time"), col(s.exchange, "Ff_y")) for s in mix if s.exchange],
        ("t (s)", "force on the liquid, x (N)", "x"), ("t (s)", "force on the liquid, y (N)", "y"))
        or "needs a finished mixture scene (coupling/exchange.csv)")

    def froude():
        items = []
        for s in liq:
            t0, _ = subcritical(s)
            if t0 is not None:
                t = col(s.liquid, "time_s")
                m = t >= t0
                items.append((s, t[m] - t0, col(s.liquid, "section_froude")[m]))
        return plot_curves(F, items, "t - t0 (s)", f"Fr at x = {SECTION_X} m", "Froude number", 1, (0, 5)) \
            or f"no liquid front reached x = {SECTION_X} m"
    F.make("froude.png", f"Froude number at x = {SECTION_X} m vs time after the front's arrival", froude)

    def sav():
        items = [(s, *savage(s)[:2]) for s in gran if savage(s)]
        if not items:
            return "no time series with a Savage-number column (mixture scenes write one)"
        fig = plot_curves(F, items, "t (s)", "N_sav (Eq. 16, d_p form)", "Savage number at x = 0.8 m", 0.1)
        fig.axes[0].set_yscale("log")
        return fig
    F.make("savage.png", "Savage number of the particles (0.1: friction/collision limit)", sav)
    F.make("profiles.png", "Liquid and granular surfaces near t = 0.63 s and 0.75 s",
           lambda: fig_profiles(F, sc, PROFILE_TIMES))

    def deposits():
        dry = [sc[n] for n in DRY_SERIES + ["P"] if sc[n].done and sc[n].deposit]
        if not dry:
            return "no finished dry scene"
        fig, axs = F.axes(2)
        for s in dry:
            axs[0].plot(col(s.deposit, "x_m"), col(s.deposit, "h_top_m") / s.H, label=label(s))
        axs[0].set(xlabel="x (m)", ylabel="h / H (top of the deposit)", title="dry deposits")
        legend(axs[0])
        if law.get("alpha") is not None:
            a = np.array([r["a"] for r in law["rows"]])
            grid = np.linspace(a.min() * 0.95, a.max() * 1.05, 50)
            axs[1].loglog(a, [r["runout"] for r in law["rows"]], "o", label="cluster front")
            axs[1].loglog(grid, law["lambda"] * grid ** law["alpha"], "-",
                          label=f"fit λ = {law['lambda']:.3f}, α = {law['alpha']:.3f}")
            axs[1].loglog(a, [r["thick"] for r in law["rows"]], "s", label="one-grain-thick front")
            axs[1].loglog(grid, law["lambda_thickness"] * grid ** law["alpha_thickness"], "-",
                          label=f"fit λ = {law['lambda_thickness']:.3f}, α = {law['alpha_thickness']:.3f}")
            axs[1].loglog(grid, 1.2 * grid, "--", color="grey",
                          label="Lube et al. 2005: 1.2 a")
            axs[1].set(xlabel="a = H/L (settled)", ylabel="(l∞ − L)/L", title="runout law (Eq. 12)")
            legend(axs[1])
        else:
            axs[1].text(0.5, 0.5, "runout law: fewer than two P-I scenes finished", ha="center")
            axs[1].set_axis_off()
        return fig
    F.make("deposits_runout.png", "Dry deposits and the runout law (P-I-I ... P-I-V)", deposits)

    def slumps():
        items = []
        for n in ("HB-I", "B-I"):
            s = sc[n]
            if s.done and s.liquid:
                t = col(s.liquid, "time_s")
                m = t > 0
                items.append((s, t[m] / T_SLUMP[n], col(s.liquid, "front_bed_m")[m] / L_SLUMP[n]))
        fig = plot_curves(F, items, "t / T", "X_f / L", "HB-I and B-I normalised fronts")
        if fig:
            fig.axes[0].set_xscale("log")
        return fig
    F.make("slumps_normalised.png", "HB-I and B-I fronts X_f/L against t/T", slumps)

    def velprof():
        items = [sc[n] for n in ("P-I-II", "P") if sc[n].done and sc[n].velocity]
        if not items:
            return "no finished P-I-II or P"
        fig, (ax,) = F.axes()
        for s in items:
            ax.plot(col(s.velocity, "u_x_m_s"), col(s.velocity, "y_m"), "o-", ms=3, label=label(s))
        ax.set(xlabel="u_x (m/s)", ylabel="y (m)", title="u(y) at x = 0.8 m, t = 0.5 s")
        legend(ax)
        return fig
    F.make("velocity_profile.png", "Velocity profile u(y) at x = 0.8 m, t = 0.5 s", velprof)


# --------------------------------------------------------------------------------------------
# The table "the paper says / we get"

FIDELITY = {  # (tier, content) -> what the tier changes that may explain a difference
    ("quick", "particles"): "quick tier: grains softened 1e4x in a 3 d periodic slice (no side walls), run cut at 1.5 s",
    ("quick", "liquid"): "quick tier: 2-D (no side-wall friction) on H/12 cells, run cut at 1.5 s",
    ("quick", "mixture"): "quick tier: 3 d periodic slice, 2-D fluid on 0.075 m cells, grains softened 1e4x, "
                          "run cut at 1.5 s",
    ("reference", "particles"): "reference tier: grains softened 1000x",
    ("reference", "liquid"): "reference tier: 2-D, no side-wall friction",
    ("reference", "mixture"): "reference tier: 0.12 m periodic slice, 2-D fluid, grains softened 1000x",
    ("truth", "particles"): "truth tier (the reference tier's dry scenes): grains softened 1000x",
    ("truth", "liquid"): "truth tier (the reference tier's liquids): 2-D, no side-wall friction",
    ("truth", "mixture"): "truth tier: 0.12 m periodic slice, 2-D fluid on 0.075 m cells sampled "
                          "per cell (the paper's stiffness, a converged exchange interval); no "
                          "side walls, whose friction takes 10-49 % of the energy the mixtures "
                          "release on the slice at the quick tier (results/convergence/README.md, "
                          "\"Geometry\")",
}


def fidelity(*scenes):
    """What the tiers of SCENES change against the paper (empty for the paper tier)."""
    return "; ".join(sorted({FIDELITY.get((s.tier, s.content), "") for s in scenes if s.done} - {""}))


@functools.lru_cache(maxsize=None)  # read once per report: locked() asks for every row
def mobility_rows():
    """results/convergence/mobility.csv (the quick yield-stress mixtures' sampling and cell-size
    runs) by variant, or {}."""
    path = os.path.join(suite.ROOT, "results", "convergence", "mobility.csv")
    try:
        with open(path) as f:
            return {r["variant"] + "/" + r["exchangeEvery"]: r for r in csv.DictReader(f)}
    except OSError:
        return {}


@functools.lru_cache(maxsize=None)
def truth_sampling(scene):
    """Energy released by 0.5 s (J/m) with `cell` and `cellPoint` sampling at the truth tier
    (results/convergence/summary.json, ladder interpolation_truth), or None."""
    path = os.path.join(suite.ROOT, "results", "convergence", "summary.json")
    try:
        with open(path) as f:
            values = json.load(f)["ladders"]["interpolation_truth"][scene]["values"]
        return {v: values[v]["0.5s"]["particle_pe_released_J_per_m"] for v in ("cell", "cellPoint")}
    except (OSError, KeyError, ValueError):
        return None


def locked(s):
    """For a yield-stress mixture run with the verified (implicit) drag: how much its mobility
    owes to the fluid sampling (results/convergence/mobility.csv; '' where not measured)."""
    if s.name not in ("HB+P", "B+P") or not s.done:
        return ""
    try:
        cp = suite.read_dict(os.path.join(s.dir, "constant", "couplingProperties"))
    except (OSError, suite.DictError):
        return ""
    if schema.value(cp, "constant/couplingProperties", "dragIntegration") == "held":
        return ""
    truth = truth_sampling(s.name)
    if truth:
        return ("verified drag (dragViscosity slip, implicit: passes the single-grain, power-law "
                "sphere and bed checks, results/yield_stress/); not converged in the fluid "
                f"sampling: at the truth tier {s.paper_name} releases {truth['cell']:.3g} J/m by "
                f"0.5 s with `cell` sampling and {truth['cellPoint']:.3g} J/m with `cellPoint` "
                "(results/convergence/README.md, \"At the truth tier\"), so this number is the "
                "`cell` closure's")
    rows = mobility_rows()
    tag = "hb" if s.name == "HB+P" else "b"
    def energy(variant):
        r = rows.get(f"{tag}_{variant}/2")
        return None if r is None else float(r["released_J"])
    e = {v: energy(v) for v in ("cell_0.06", "cellPoint_0.06", "cell_0.03", "cellPoint_0.03")}
    if None in e.values():
        return ""
    return ("verified drag (dragViscosity slip, implicit: passes the single-grain, power-law "
            "sphere and bed checks, results/yield_stress/); not converged in the fluid sampling "
            f"or the cell size: the quick {s.paper_name} releases {e['cell_0.06']:.2f} J by 0.5 s "
            f"with `cell` sampling and {e['cellPoint_0.06']:.2f} J with `cellPoint` on 0.06 m "
            f"cells, {e['cell_0.03']:.2f} / {e['cellPoint_0.03']:.2f} J on 0.03 m cells "
            "(results/convergence/README.md, \"What holds the yield-stress mixtures\")")


def tiers_of(*scenes):
    return ",".join(sorted({s.tier or "?" for s in scenes if s.done})) or "-"


def row(quantity, paper, ours, tier, agree, note):
    return {"quantity": quantity, "paper": paper, "ours": ours, "tier": tier,
            "agrees": None if agree is None else bool(agree), "note": note}


def with_partner(rows, partner_rows, partner_names):
    """Each row a partner scene enters gets the partner's value ("finer") and, for numbers, their
    difference ("convergence_error"); where the two verdicts differ the row has none."""
    by_q = {r["quantity"]: r for r in partner_rows}
    # a scene's name as a word: "B&P" does not name HB&P's rows
    named = re.compile("|".join(rf"(?<![\w&]){re.escape(n)}" for n in partner_names) or "$^")
    for r in rows:
        p = by_q.get(r["quantity"])
        if p is None or not named.search(f"{r['quantity']} {r['note']}"):
            continue
        r["finer"] = p["ours"]
        if isinstance(r["ours"], (int, float)) and isinstance(p["ours"], (int, float)):
            r["convergence_error"] = round(p["ours"] - r["ours"], 4)
        if r["agrees"] is not None and p["agrees"] != r["agrees"]:
            r["note"] = (f"not converged: one step finer the verdict is "
                         f"{ {True: 'agrees', False: 'differs', None: 'none'}[p['agrees']] } "
                         f"({fmt(p['ours'])}); " + r["note"])
            r["agrees"] = None
    return rows


def legend(ax):
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=7)


def table(sc, law):
    rows = []
    for n in LIQUIDS + MIXTURES:
        s, paper = sc[n], PAPER["subcritical"][n]
        q = f"{s.paper_name}: Fr < 1 at x = {SECTION_X} m, t − t0 (s)"
        if not s.done:
            rows.append(row(q, paper, None, "-", None, "scene not finished"))
            continue
        t0, dt = subcritical(s)
        if t0 is None:
            note = f"the liquid front never reached x = {SECTION_X} m before the run ended"
            if locked(s):
                note += "; " + locked(s)
            rows.append(row(q, paper, None, s.tier, False, note))
        elif dt is None:
            note = (f"still supercritical when the run ended at {s.t_end():.2f} s (t0 = {t0:.2f} s); "
                    + fidelity(s) + ("; " + locked(s) if locked(s) else ""))
            rows.append(row(q, paper, None, s.tier, False, note))
        else:
            agree = abs(dt - paper) <= max(0.1, 0.15 * paper)
            if agree:
                note = f"agrees within {max(0.1, 0.15 * paper):.2f} s (t0 = {t0:.2f} s; rule: Fr < 1 held {HOLD_S} s)"
            elif dt > paper:
                note = (f"later than the paper: {fidelity(s)}" +
                        ("; not side-wall friction: W in 3-D with walls turns subcritical when "
                         "it does in 2-D (results/pure_liquids/side_walls.json)" if n == "W" else ""))
            else:
                note = ("earlier than the paper: " + fidelity(s) +
                        ("; coarse cells smear the thinning tail at the section" if s.tier == "quick" else ""))
            if n in MIXTURES:
                alt = subcritical_volume_depth(s)
                note += ("; h = liquid surface height (froudeDepth surface); with h = liquid "
                         "volume depth: " + ("never" if alt is None else f"{alt:.2f} s"))
            rows.append(row(q, paper, round(dt, 2), s.tier, agree, note))

    # Front orders.
    def order(names, fronts, t):
        have = [n for n in names if sc[n].done and fronts(sc[n]) is not None]
        if len(have) < len(names):
            return None, f"needs {', '.join(PAPER_NAME[n] for n in names if n not in have)} finished"
        tmax = min(fronts(sc[n])[0][-1] for n in names)
        tt = min(t, tmax)
        xs = {n: float(np.interp(tt, *fronts(sc[n]))) for n in names}
        got = " > ".join(PAPER_NAME[n] for n in sorted(names, key=lambda n: -xs[n]))
        return got, f"at t = {tt:.2f} s: " + ", ".join(f"{PAPER_NAME[n]} {xs[n]:.2f} m" for n in names)
    got, where = order(LIQUIDS, liquid_front, 2.0)
    rows.append(row("front order, pure liquids", "W > HB > B", got, tiers_of(*(sc[n] for n in LIQUIDS)),
                    None if got is None else got == "W > HB > B",
                    where if got is None else f"liquid fronts {where}"))

    def mixed_front(s):
        return liquid_front(s) if s.content in ("liquid", "mixture") else granular_front(s)
    got, where = order(["HB", "HB+P", "P"], mixed_front, 1.0)
    rows.append(row("front order HB, HB&P, P", "HB > HB&P > P", got, tiers_of(sc["HB"], sc["HB+P"], sc["P"]),
                    None if got is None else got == "HB > HB&P > P",
                    where if got is None else f"liquid fronts (HB, HB&P) and granular front (P) {where}"
                    + ("; " + locked(sc["HB+P"]) if locked(sc["HB+P"]) else "")))

    # Runout law: fitted over the scenes of one tier (law["tier"]).
    fitted = [sc[r["scene"]] for r in law["rows"]] or [sc[n] for n in DRY_SERIES]
    tier = tiers_of(*fitted)
    left = (f"; not fitted: {', '.join(law['left_out'])} (another tier)" if law.get("left_out")
            else "")
    if law.get("alpha") is None:
        rows.append(row("runout exponent α (P-I-I … P-I-V)", PAPER["alpha"], None, tier, None,
                        f"needs at least two of P-I-I … P-I-V finished ({len(law['rows'])} now)"))
        rows.append(row("runout coefficient λ", "not given (Lube et al. 2005: 1.2)", None, tier, None, "as above"))
    else:
        a, lam = law["alpha"], law["lambda"]
        agree = abs(a - PAPER["alpha"]) <= 0.1
        stopped = {r["stop_reason"] for r in law["rows"]}
        se = law.get("alpha_standard_error")
        spread = (f"fit standard error ± {se:.2f}, so the paper's value is "
                  f"{abs(a - PAPER['alpha']) / se:.1f} standard errors away; " if se else "")
        note = (f"agrees within 0.1 (cluster front, {spread}one-grain-thick front: α = "
                f"{law['alpha_thickness']:.3f})"
                if agree else
                f"cluster front, {spread}one-grain-thick front gives α = {law['alpha_thickness']:.3f}. "
                + ("Runs cut at endTime before arrest, so runouts are not final; " if "endTime" in stopped else "")
                + fidelity(*fitted)) + left
        rows.append(row(f"runout exponent α ({len(law['rows'])} of P-I-I … P-I-V)", PAPER["alpha"],
                        round(a, 3), tier, agree, note))
        rows.append(row("runout coefficient λ", "not given (Lube et al. 2005: 1.2)", round(lam, 3), tier, None,
                        f"one-grain-thick front: λ = {law['lambda_thickness']:.3f}; the paper gives no λ"))

    # Back wall.
    for n in ("HB", "HB+P"):
        s = sc[n]
        for t, paper in zip((0.5, 1.0), PAPER["back_wall"][n]):
            q = f"{s.paper_name}: max height at the back wall / H, t = {t} s"
            if not s.done:
                rows.append(row(q, paper, None, "-", None, "scene not finished"))
                continue
            v = back_wall(s, t)
            if v is None:
                rows.append(row(q, paper, None, s.tier, False, f"the run ended at {s.t_end():.2f} s"))
                continue
            agree = abs(v - paper) <= 0.05
            what = ("liquid surface height of the first cell column" if
                    back_wall_key(s) == "back_wall_surface_m" else
                    "liquid volume depth of the first cell column (the run predates the surface "
                    "height; in a mixture about eps_f times it)")
            note = (f"agrees within 0.05 ({what})" if agree else
                    what + "; " + fidelity(s) +
                    ("; the column slumps more at the wall" if v < paper else
                     "; " + (locked(s) or "the regularised liquid (cap 1e4 Pa s) and coarse "
                                          "cells hold more at the wall")))
            rows.append(row(q, paper, round(v, 3), s.tier, agree, note))

    # Savage interval of B&P and the ordering.
    s = sc["B+P"]
    q = "B&P collision-dominated (N_sav > 0.1), s"
    sv = savage(s) if s.done else None
    if not s.done:
        rows.append(row(q, "0.28 – 1.1", None, "-", None, "scene not finished"))
    elif sv is None:
        rows.append(row(q, "0.28 – 1.1", None, s.tier, None, "no Savage column in the time series"))
    else:
        iv = collision_interval(sv[0], sv[1])
        ours = None if iv is None else f"{iv[0]:.2f} – {iv[1]:.2f}"
        agree = iv is not None and abs(iv[0] - 0.28) <= 0.1 and abs(iv[1] - 1.1) <= 0.15
        rows.append(row(q, "0.28 – 1.1", ours, s.tier, agree,
                        f"column {sv[2]}" + ("" if agree else "; " + fidelity(s)
                                             + ("; never above 0.1" if iv is None else "")
                                             + ("; " + locked(s) if locked(s) else ""))))
    names = ["B+P", "P", "HB+P", "W+P"]
    have = [n for n in names if sc[n].done and savage(sc[n])]
    if len(have) == len(names):
        means = {}
        for n in names:
            t, v, _ = savage(sc[n])
            m = (t >= 0.2) & (t <= 1.2) & np.isfinite(v)
            means[n] = float(np.mean(v[m])) if m.any() else float("nan")
        got = " > ".join(PAPER_NAME[n] for n in sorted(names, key=lambda n: -means[n]))
        rows.append(row("Savage ordering (mean over 0.2-1.2 s)", "B&P > P ≈ HB&P > W&P", got,
                        tiers_of(*(sc[n] for n in names)), None,
                        ", ".join(f"{PAPER_NAME[n]} {means[n]:.3g}" for n in names) +
                        " (the paper's P ≈ HB&P allows either order of those two)"))
    else:
        lack = [PAPER_NAME[n] for n in names if n not in have]
        rows.append(row("Savage ordering", "B&P > P ≈ HB&P > W&P", None, "-", None,
                        f"needs the Savage column of {', '.join(lack)} (not finished or none written)"))

    # Stage changes (mixtures: the paper's Fig. of the W&P/HB&P/B&P fronts).
    for kind, fronts, paper in (("liquid", liquid_front, PAPER["liquid_stage_change_s"]),
                                ("granular", granular_front, PAPER["granular_stage_change_s"])):
        got = {}
        for n in MIXTURES:
            if sc[n].done and fronts(sc[n]) is not None:
                got[n] = stage_change(*fronts(sc[n]))
        q = f"{kind}-front stage change, mixtures (s)"
        if not got:
            rows.append(row(q, paper, None, "-", None, "needs a finished mixture scene"))
            continue
        ours = ", ".join(f"{PAPER_NAME[n]} {fmt(v)}" for n, v in got.items())
        vals = [v for v in got.values() if v is not None]
        agree = bool(vals) and all(abs(v - paper) <= 0.2 * paper for v in vals)
        tier = tiers_of(*(sc[n] for n in got))
        note = "rule: the front speed (0.05 s differences) first falls below half its peak"
        if not agree:
            ended = max(sc[n].t_end() or 0 for n in got)
            note += (f"; the runs ended at {ended:.2f} s, before the paper's change" if ended < paper
                     else "; " + fidelity(*(sc[n] for n in got)))
        rows.append(row(q, paper, ours, tier, agree, note))

    # Outflow start (docs/model.md §1: the channel-length calibration).
    for n in ("W", "W+P"):
        s, paper = sc[n], PAPER["outflow_starts_s"][n]
        q = f"{s.paper_name}: liquid starts leaving the channel (s)"
        if not s.done:
            rows.append(row(q, paper, None, "-", None, "scene not finished"))
            continue
        v = outflow_start(s)
        agree = v is not None and abs(v - paper) <= 0.1
        rows.append(row(q, paper, None if v is None else round(v, 2), s.tier, agree if v is not None else False,
                        "outflow > 0.1 % of the liquid; the channel length 5.86 m was calibrated on 2-D W "
                        "(results/pure_liquids)" + ("" if agree else
                                                    f"; no outflow before {s.t_end():.2f} s" if v is None
                                                    else "; " + fidelity(s))))
    return rows


# --------------------------------------------------------------------------------------------

def write_report(out, work, sc, F, rows, law, command, bulk_lines=()):
    fin = [n for n in suite.TABLE1 if sc[n].done]
    lines = ["# Li & Zhao (2018) scenes: the paper says / we get", "",
             f"Made by `{command}` from `{work}` (mixflow suite runs, docs/suite.md). "
             f"{len(fin)} of {len(suite.TABLE1)} scenes finished.", "",
             "| scene | status | tier | content | simulated to (s) |", "|---|---|---|---|---|"]
    for n in suite.TABLE1:
        s = sc[n]
        status = "finished" if s.done else ("failed (log.suite)" if s.failed else
                                            "started, not finished" if s.exists else "not run")
        lines.append(f"| {s.paper_name} | {status} | {s.tier or '-'} | {s.content or '-'} | "
                     f"{fmt(s.t_end()) if s.done else '-'} |")
    tiers = sorted({sc[n].tier for n in fin if sc[n].tier})
    if tiers:
        lines += ["", "Tiers used (cases/tiers/<tier>):"]
        for t in tiers:
            try:
                lines.append(f"- **{t}**: {suite.Tier(t).description}")
            except suite.DictError:
                lines.append(f"- **{t}**")
    lines += ["", "## The paper says / we get", "",
              "| quantity | paper | ours | one step finer | tier | agrees | note |",
              "|---|---|---|---|---|---|---|"]
    for r in rows:
        ag = {True: "yes", False: "no", None: "-"}[r["agrees"]]
        finer = fmt(r["finer"]) if "finer" in r else "-"
        lines.append(f"| {r['quantity']} | {r['paper']} | {fmt(r['ours'])} | {finer} | {r['tier']} | "
                     f"{ag} | {r['note']} |")
    lines += ["", "Definitions: liquid front = largest x where the bed cell row holds α ≥ 0.5; "
              "granular front = largest x of the largest connected cluster (gap ≤ 0.5 d); "
              f"t0 = arrival of the liquid front at x = {SECTION_X} m, Fr = v / √(g h) with v the mean liquid velocity and h the liquid surface height there (the pores of a saturated granular layer counted full; runs before that column: the liquid volume depth), subcritical = Fr < 1 held for {HOLD_S} s; back-wall height = the liquid surface height of the first cell column; "
              "energies per metre of width (scenes of different widths compare); E_pd = "
              "([E_pp0 − E_pp − E_kp]_mixture − [same]_dry)/[same]_dry with E_kp translational + "
              "rotational; E_fc = (E_pf0 − (E_pf + E_kf))/E_pf0.", "", "## Figures", ""]
    for name, title in F.made:
        lines += [f"### {title}", "", f"![{title}]({name})", ""]
    if F.skipped:
        lines += ["Not drawn:", ""] + [f"- `{n}`: {why}" for n, why in F.skipped] + [""]
    budget = [(n, sc[n], energy_excess(sc[n])) for n in fin]
    budget = [b for b in budget if b[2] is not None]
    if budget:
        lines += ["## Energy budget", "",
                  "Largest excess of kinetic energy over released potential energy (grains and liquid "
                  "together, J per metre of width): a closed dam break only dissipates, so a positive "
                  "value is the elastic energy stored in the settled sample's contacts (the dry scene P "
                  "has only that) or energy a numerical scheme made (coupling/README.md, \"Energy "
                  "budget\").", "",
                  "| scene | tier | excess (J/m) | at t (s) | kinetic (J/m) | released (J/m) |",
                  "|---|---|---|---|---|---|"]
        for n, s, e in budget:
            lines.append(f"| {s.paper_name} | {s.tier or '-'} | {fmt(e['excess_J_per_m'])} | "
                         f"{fmt(e['t_s'])} | {fmt(e['kinetic_J_per_m'])} | {fmt(e['released_J_per_m'])} |")
        lines.append("")
    lines += list(bulk_lines)
    lines += yield_stress_section()
    if law.get("rows"):
        lines += ["## Dry runouts", "", "| scene | a (settled) | (l∞ − L)/L cluster | one-grain-thick | stop |",
                  "|---|---|---|---|---|"]
        for r in law["rows"]:
            lines.append(f"| {r['scene']} | {r['a']:.3f} | {r['runout']:.3f} | {r['thick']:.3f} | "
                         f"{r['stop_reason']} at {r['end_time_s']:.2f} s |")
        lines.append("")
    with open(os.path.join(out, "report.md"), "w") as f:
        f.write("\n".join(lines) + "\n")


def front_at(front, t):
    """A front (t, x) at time T, None if the run ended before it by more than
    outputs.END_TOLERANCE_S (then its last value stands for T)."""
    if front is None or front[0][-1] < t - outputs.END_TOLERANCE_S:
        return None
    return float(np.interp(t, *front))


def bulk_rows(sc, bulk):
    """The mixtures' numbers from the CFD-DEM runs (SC) beside the bulk model's runs (BULK, the
    suite's bulk tier: the same case directories run by mixflowBulkFoam), with the paper's where
    it gives one; None where a run does not allow the number."""
    rows = []
    for n in MIXTURES:
        s, b = sc[n], bulk[n]
        if not b.done:
            continue
        # An unfinished CFD-DEM scene has no series: its numbers come out None.
        items = [("Fr < 1 at x = %g m, t − t0 (s)" % SECTION_X, PAPER["subcritical"][n],
                  subcritical(s)[1], subcritical(b)[1])]
        for t in (1.0, 3.0):
            items.append((f"liquid front at {t:g} s (m)", None,
                          front_at(liquid_front(s), t), front_at(liquid_front(b), t)))
            items.append((f"granular front at {t:g} s (m); bulk: the mixture's front", None,
                          front_at(granular_front(s), t), front_at(liquid_front(b), t)))
        if n in PAPER["back_wall"]:
            for t, paper in zip((0.5, 1.0), PAPER["back_wall"][n]):
                items.append((f"back-wall height at {t:g} s / H", paper, back_wall(s, t),
                              back_wall(b, t)))
        for q, paper, ours, model in items:
            rows.append({"scene": s.paper_name, "quantity": q, "paper": paper,
                         "cfd_dem": ours, "cfd_dem_tier": s.tier, "bulk": model,
                         "bulk_tier": b.tier})
    return rows


def bulk_section(rows, bulk_work):
    if not rows:
        return []
    lines = ["## The bulk model beside CFD-DEM", "",
             f"The quasi two-phase bulk model (docs/bulk_model.md) on the same cases, from `{bulk_work}` "
             "(`mixflow suite --tier bulk --scenes W+P,HB+P,B+P`; its calibration stage and "
             "errors: results/bulk_model/). The bulk model has one mixture phase: its front is the "
             "mixture's.", "",
             "| scene | quantity | paper | CFD-DEM | tier | bulk model | tier |", "|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['scene']} | {r['quantity']} | {fmt(r['paper'])} | {fmt(r['cfd_dem'])} | "
                     f"{r['cfd_dem_tier'] or '-'} | {fmt(r['bulk'])} | {r['bulk_tier'] or '-'} |")
    return lines + [""]


def yield_stress_section():
    """HB&P and B&P: the verified drag against the paper's scheme (results/yield_stress/)."""
    path = os.path.join(suite.ROOT, "results", "yield_stress", "summary.json")
    if not os.path.exists(path):
        return []
    with open(path) as f:
        ys = json.load(f)
    runs = ys.get("paper_faithful", {}).get("runs", {})
    lines = ["## HB&P and B&P: the verified drag against the paper's scheme", "",
             f"From results/yield_stress/summary.json (`{ys.get('command', '')}`; quick tier, same "
             "settled sample, the plain void-fraction split whose jumps moved these mixtures with "
             "the exchange interval, results/convergence/README.md). The default drag viscosity (`slip`) passes the single-grain checks "
             "that `resolved` fails; the paper's scheme as far as it is known (held drag, resolved "
             "viscosity, d(eps)/dt off) lets the columns flow only because the held drag's "
             "stability bound caps most grains' drag. The evidence supports the default.", "",
             "| scene | scheme | granular front at 1.5 s (m) | grains' energy released (J) | "
             "back-wall surface 0.5 / 1.0 s (H) | drag capped by the bound |",
             "|---|---|---|---|---|---|"]
    for scene in ("HB&P", "B&P"):
        for name, what in (("default", "verified (slip, implicit)"),
                           ("paper", "paper-faithful (resolved, held, d(eps)/dt off)")):
            o = runs.get(scene, {}).get(name)
            if not o or "failed" in o:
                continue
            lines.append(f"| {scene} | {what} | {fmt(o['granular_front_m'])} | "
                         f"{fmt(o['grain_pe_released_J'])} | "
                         f"{fmt(o['back_wall_surface_0.5s_H'])} / {fmt(o['back_wall_surface_1.0s_H'])} "
                         f"| {fmt(100 * o.get('drag_limited_share', 0), 2)} % |")
    lines += ["", "The paper's HB&P back-wall surface: 0.997 / 0.894 H.", ""]
    pw = ys.get("paper_faithful", {}).get("paper_window", {})
    if pw:
        lines += ["At the paper's stiffness and steps (HB&P, paper-window tier: E = 70/700 GPa, DEM "
                  "step 5e-7 s, exchange every 100; the same grains for both schemes):", "",
                  "| scheme | granular front 0.5 / 1.0 s (m) | grains' energy released by 1.0 s (J) "
                  "| back-wall surface 0.5 / 1.0 s (H) |", "|---|---|---|---|"]
        for name, what in (("default", "verified (slip, implicit)"),
                           ("paper", "paper-faithful (resolved, held, d(eps)/dt off)")):
            at = pw.get(name, {}).get("at", {})
            if "0.5" in at and "1" in at:
                lines.append(f"| {what} | {fmt(at['0.5']['granular_front_m'])} / "
                             f"{fmt(at['1']['granular_front_m'])} | "
                             f"{fmt(at['1']['grain_pe_released_J'])} | "
                             f"{fmt(at['0.5']['back_wall_surface_H'])} / "
                             f"{fmt(at['1']['back_wall_surface_H'])} |")
        lines.append("")
    return lines


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--work", default="runs/reference",
                    help="suite.py's work directory, or several, comma-separated, in order of "
                    "preference")
    ap.add_argument("--out", default="results/li_zhao_2018")
    ap.add_argument("--partner", default="",
                    help="work directories with the mixtures one speed knob one step finer "
                    "(each row's convergence error)")
    ap.add_argument("--bulk-work", default="runs/bulk",
                    help="the suite's bulk-tier work directory (the bulk model's column; skipped "
                    "where its scenes are not finished)")
    args = ap.parse_args(argv)
    def absolute(p):
        return p if os.path.isabs(p) else os.path.join(suite.ROOT, p)
    works, out = [absolute(p) for p in args.work.split(",")], absolute(args.out)
    work = ", ".join(works)
    os.makedirs(out, exist_ok=True)
    sc = {n: first_finished(works, n) for n in suite.TABLE1}
    fin = [n for n in suite.TABLE1 if sc[n].done]
    law = runout_law(sc)
    F = Figures(out)
    make_figures(F, sc, fin, law)
    rows = table(sc, law)
    partners = [absolute(p) for p in args.partner.split(",") if p]
    if partners:
        finer = {n: first_finished(partners, n) for n in MIXTURES}
        finer = {n: s for n, s in finer.items() if s.done}
        rows = with_partner(rows, table({**sc, **finer}, law), [PAPER_NAME[n] for n in finer])
    bulk = {n: Scene(absolute(args.bulk_work), n) for n in MIXTURES}
    brows = bulk_rows(sc, bulk)
    command = (f"mixflow report --work {args.work} --out {args.out}"
               + (f" --partner {args.partner}" if partners else "")
               + (f" --bulk-work {args.bulk_work}" if brows else ""))
    write_report(out, work, sc, F, rows, law, command, bulk_section(brows, args.bulk_work))
    summary = {"command": command, "work": work,
               "scenes": {n: {"status": "finished" if sc[n].done else ("unfinished" if sc[n].exists else "not run"),
                              "tier": sc[n].tier, "content": sc[n].content,
                              "simulated_to_s": sc[n].t_end() if sc[n].done else None} for n in suite.TABLE1},
               "paper_vs_ours": rows,
               "bulk_model": brows,
               "runout_law": {k: v for k, v in law.items()},
               "subcritical_after_arrival_s": {n: subcritical(sc[n])[1] for n in LIQUIDS + MIXTURES if sc[n].done},
               "energy_excess": {n: energy_excess(sc[n]) for n in fin},
               "figures": [n for n, _ in F.made], "figures_not_drawn": dict(F.skipped)}
    outputs.write_json(os.path.join(out, "summary.json"), clean(summary), indent=2)
    print(f"report: {len(fin)} of {len(suite.TABLE1)} scenes finished; {len(F.made)} figures; "
          f"{sum(1 for r in rows if r['agrees'])} of {sum(1 for r in rows if r['agrees'] is not None)} "
          f"compared numbers agree; {os.path.join(out, 'report.md')}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
