"""Loose against dense collapse in a viscous Newtonian liquid (Rondon, Pouliquen & Aussillous
2011, Phys. Fluids 23, 073301): viscous_packing.csv and the "viscous_packing" entry of OUT's
summary.json (and, with --convergence-summary, the issue's "loose_dense" entry there).

usage: mixflow viscous-packing [--viscosity 4] [--end 3] [--set FILE.ENTRY=VALUE ...]
                               [--loose-set FILE.ENTRY=VALUE ...] [--work runs/yield_stress]
                               [--out results/yield_stress] [--convergence-summary FILE]
                               [--settled-from WORK]

W+P at the reference tier with the liquid made Newtonian at --viscosity (Pa s; 4 is the paper's
Bingham liquid's plastic viscosity, Stokes number sqrt(rho_p (rho_p - rho_f) g d^3) / (18 sqrt(2)
mu) = 0.22: the viscous regime of Courrech du Pont et al. 2003, as Rondon's), --set entries on
both runs (e.g. demDict.youngModulusFactor=1e-2), settled dense (the case's preparation: the
packing control to sample.solidFraction) and loose (the case with the --loose-set entries; by
default a gentle sedimentation at high friction, LOOSE below). Each sample's bulk fraction is
judged against the grains' critical packing PHI_C (results/critical_packing): a loose sample must
lie below it, a dense one above. For each: the runout (granular front - L) at the end, the grains'
potential energy released by 0.5, 1, 2 and 3 s, and the basal pore pressure under the initial
column against hydrostatic per 0.1 s window (mixflow mixture-lambdas, which needs
/usr/bin/python3 with numpy and h5py).

Rondon's columns stand in a tank of the liquid: `--set sceneProperties.channel.liquidDepth=0.9`
immerses the scene's column (a closed tank, still liquid to 0.9 m = 1.5 H over the whole floor);
without it the column is saturated in air and its pore liquid drains through the open gate.

What Rondon et al. measured and this checks: the dense column collapses more slowly and runs
less far than the loose one (runouts about 1 : 2), with a basal pore pressure below hydrostatic
while it dilates; the loose column's base is above hydrostatic while it compacts.
"""

import argparse
import json
import os
import subprocess
import sys

from mixflow.cli import command
from mixflow import ROOT, foamdict, outputs
from mixflow.commands import mixture_lambdas
from mixflow.commands.yield_stress_results import observables, settled_fraction

RUNOUT_RATIO = 2.0  # loose / dense runout, Rondon et al. 2011 (about)
RATIO_MIN = 1.5  # the check: the loose column runs at least 1.5 x the dense one's runout
PHI_C = 0.5653  # critical bulk fraction of these grains, results/critical_packing
# The loose preparation: the grain count of a 0.55 sample, settled once at friction 2 with the
# grains' own rolling friction while a drag holds every grain below 0.1 m/s (demDict
# settle.sedimentationSpeed), as a sedimented bed: bulk 0.526 at E x 1e-2 (results/critical_packing).
LOOSE = ("sceneProperties.sample.solidFraction=0.55", "demDict.settle.packingControl=off",
         "demDict.settle.friction=2", "demDict.settle.rollingFriction=0.1",
         "demDict.settle.sedimentationSpeed=0.1", "demDict.settle.maxTime=8")


def run(cmd):
    print("+ " + " ".join(cmd), flush=True)
    r = subprocess.run(cmd, cwd=ROOT)
    if r.returncode != 0:
        sys.exit(f"failed: {' '.join(cmd)}")


def released(run_dir, times=(0.5, 1.0, 2.0, 3.0)):
    """The grains' potential energy released by each of TIMES (J), and whether the column still
    moved at the end (more than 5 % of what it released came in the last 0.5 s)."""
    dem = outputs.read_series(os.path.join(run_dir, outputs.DEM_SERIES))
    pe0, t_end = dem[0]["pe_J"], dem[-1][outputs.TIME]
    # A run's last row may fall a fraction of a CFD step short of its endTime: it counts as there.
    out = {f"{t:g}": pe0 - outputs.interpolated(dem, "pe_J", min(t, t_end))
           for t in times if t <= t_end + 1e-3}
    late = outputs.interpolated(dem, "pe_J", t_end - 0.5) - dem[-1]["pe_J"]
    return out, late > 0.05 * (pe0 - dem[-1]["pe_J"])


# The column's lower interior, where a loose sample compacts and a dense one dilates.
COLUMN = {"x": (0.0, 0.45), "y": (0.0, 0.3)}  # m


def column_alpha(run_dir):
    """The mean alpha_s over COLUMN's bins per 0.1 s window (the extraction of mixture-lambdas):
    whether the column compacts or dilates."""
    d = mixture_lambdas.load(os.path.join(run_dir, "postProcessing", "mixture", "mixture.h5"))
    xe, ye = d["grid"]["x_edges"], d["grid"]["y_edges"]
    xc, yc = 0.5 * (xe[1:] + xe[:-1]), 0.5 * (ye[1:] + ye[:-1])
    cols = (xc > COLUMN["x"][0]) & (xc < COLUMN["x"][1])
    rows = (yc > COLUMN["y"][0]) & (yc < COLUMN["y"][1])
    alpha = d["fields"]["alpha_s"][:, rows][:, :, cols]
    t0, t1 = d["windows"]["t0"], d["windows"]["t1"]
    return {f"{a:.1f}-{b:.1f}": float(alpha[k].mean()) for k, (a, b) in enumerate(zip(t0, t1))}


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--viscosity", default="4")
    ap.add_argument("--end", type=float, default=3.0, help="endTime of both runs (s)")
    ap.add_argument("--set", action="append", default=[], metavar="FILE.ENTRY=VALUE",
                    help="an entry of both runs (repeatable)")
    ap.add_argument("--loose-set", action="append", default=None, metavar="FILE.ENTRY=VALUE",
                    help="the loose preparation's entries (repeatable; default: " +
                    " ".join(LOOSE) + ")")
    ap.add_argument("--work", default=os.path.join(ROOT, "runs", "yield_stress"))
    ap.add_argument("--out", default=os.path.join(ROOT, "results", "yield_stress"))
    ap.add_argument("--convergence-summary", default=None,
                    help="also write the loose_dense entry of this summary.json")
    ap.add_argument("--np", default="1")
    ap.add_argument("--settled-from", default=None, metavar="WORK",
                    help="reuse the samples settled in WORK/viscous-VISCOSITY-{dense,loose} "
                    "(an earlier --work of this command; mixflow suite --settled-from)")
    a = ap.parse_args()
    common = [x for s in a.set + [f"sceneProperties.liquid.viscosity={a.viscosity}",
                                  f"controlDict.endTime={a.end}"] for x in ("--set", s)]
    packings = {"dense": [], "loose": [x for s in (a.loose_set or LOOSE) for x in ("--set", s)]}
    res = {"viscosity_Pa_s": float(a.viscosity), "set": a.set, "loose_set": list(a.loose_set or LOOSE),
           "tier": "reference", "end_s": a.end, "critical_bulk_fraction": PHI_C,
           "reference": {"source": "Rondon, Pouliquen & Aussillous 2011 (Phys. Fluids 23, 073301)",
                         "runout_ratio_loose_over_dense": RUNOUT_RATIO,
                         "basal_excess_sign": {"dense": "negative", "loose": "positive"}},
           "command": "mixflow viscous-packing " + " ".join(sys.argv[1:]),
           "runs": {}}
    for name, sets in packings.items():
        work = os.path.join(os.path.abspath(a.work), f"viscous-{a.viscosity}-{name}")
        reuse = (["--settled-from", os.path.join(os.path.abspath(a.settled_from),
                                                 os.path.basename(work))] if a.settled_from else [])
        run(command("suite") + ["--tier", "reference", "--scenes", "W+P", "--work", work,
                                "--np", a.np] + common + sets + reuse)
        run_dir = os.path.join(work, "W+P")
        lam = os.path.join(work, "lambdas.json")
        run(command("mixture-lambdas") + ["--work",
             work, "--scenes", "W+P", "--out", lam])
        with open(lam) as f:
            basal = json.load(f)["scenes"]["W&P"]["basal_pore_pressure"]
        obs = observables(run_dir)
        sample = foamdict.read_dict(os.path.join(run_dir, "constant", "sceneProperties"))["sample"]
        at, moving = released(run_dir)
        obs.update({"settled_sample_fraction": settled_fraction(run_dir),
                    "settled_bulk_fraction": settled_fraction(run_dir, "bulkFraction"),
                    "runout_m": obs["granular_front_m"] - float(sample["length"]),
                    "pe_released_J_at": at,
                    "still_moving_at_end": moving,
                    "column_alpha_s": column_alpha(run_dir),
                    "basal_excess_Pa": {f"{r['t0']:.1f}-{r['t1']:.1f}": r["excess_Pa"]
                                        for r in basal},
                    "basal_hydrostatic_Pa": {f"{r['t0']:.1f}-{r['t1']:.1f}": r["hydrostatic_Pa"]
                                             for r in basal}})
        res["runs"][name] = obs
    dense, loose = res["runs"]["dense"], res["runs"]["loose"]
    first, last = (lambda s: next(iter(s.values()))), (lambda s: list(s.values())[-1])
    ratio = loose["runout_m"] / dense["runout_m"]
    early = lambda o: o["basal_excess_Pa"].get("0.0-0.1")  # noqa: E731
    res["checks"] = {
        "loose_below_critical": {"measured": loose["settled_bulk_fraction"], "critical": PHI_C,
                                 "passes": loose["settled_bulk_fraction"] < PHI_C},
        "dense_above_critical": {"measured": dense["settled_bulk_fraction"], "critical": PHI_C,
                                 "passes": dense["settled_bulk_fraction"] > PHI_C},
        "runout_ratio": {"measured": ratio, "reference": RUNOUT_RATIO, "minimum": RATIO_MIN,
                         "passes": ratio >= RATIO_MIN},
        # Energy released by 1 s, dense over loose: below 1 when the dense column is slower.
        # alpha_s of the column's lower interior over the run: a loose sample compacts (> 0)
        "loose_compacts": {"measured": last(loose["column_alpha_s"]) - first(loose["column_alpha_s"]),
                           "passes": last(loose["column_alpha_s"]) > first(loose["column_alpha_s"])},
        "dense_slower": {"measured": dense["pe_released_J_at"]["1"] / loose["pe_released_J_at"]["1"],
                         "passes": dense["pe_released_J_at"]["1"] < loose["pe_released_J_at"]["1"]},
        "dense_base_below_hydrostatic_0-0.1s": {"measured": early(dense),
                                                "passes": early(dense) is not None and early(dense) < 0},
        "loose_base_above_hydrostatic_0-0.1s": {"measured": early(loose),
                                                "passes": early(loose) is not None and early(loose) > 0},
    }
    out = os.path.abspath(a.out)
    os.makedirs(out, exist_ok=True)
    rows = []
    for name, o in res["runs"].items():
        row = {"packing": name, "settled_sample_fraction": o["settled_sample_fraction"],
               "settled_bulk_fraction": o["settled_bulk_fraction"],
               "runout_m": o["runout_m"], "granular_front_m": o["granular_front_m"],
               "simulated_to_s": o["simulated_to_s"], "still_moving_at_end": o["still_moving_at_end"],
               "grain_pe_released_J": o["grain_pe_released_J"],
               "grain_pe_initial_J": o["grain_pe_initial_J"]}
        for t, v in o["pe_released_J_at"].items():
            row[f"pe_released_{t}s_J"] = v
        for w, v in o["basal_excess_Pa"].items():
            row[f"basal_excess_{w}s_Pa"] = v
        rows.append(row)
    outputs.write_csv(os.path.join(out, "viscous_packing.csv"), rows)
    path = os.path.join(out, "summary.json")
    summary = json.load(open(path)) if os.path.exists(path) else {}
    summary["viscous_packing"] = res
    with open(path, "w") as f:  # as yield_stress_results.py writes it
        json.dump(summary, f, indent=1, sort_keys=True)
    if a.convergence_summary:  # the mixture-truth issue's entry, beside the ladders
        conv = json.load(open(a.convergence_summary))
        conv["loose_dense"] = {
            "runout_ratio": ratio, "end_s": a.end,
            "loose_excess_Pa": loose["basal_excess_Pa"], "dense_excess_Pa": dense["basal_excess_Pa"],
            "loose_bulk_fraction": loose["settled_bulk_fraction"],
            "dense_bulk_fraction": dense["settled_bulk_fraction"], "critical_bulk_fraction": PHI_C,
            "checks": res["checks"], "command": res["command"]}
        with open(a.convergence_summary, "w") as f:
            json.dump(conv, f, indent=1, sort_keys=True)
    print(json.dumps(res["checks"], indent=1))
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
