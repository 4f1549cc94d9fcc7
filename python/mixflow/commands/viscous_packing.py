"""Loose against dense collapse in a viscous Newtonian liquid (Rondon, Pouliquen & Aussillous
2011, Phys. Fluids 23, 073301): results/yield_stress/viscous_packing.csv and the
"viscous_packing" entry of summary.json.

usage: mixflow viscous-packing [--viscosity 4] [--loose 0.56:0.7]
                                          [--work runs/yield_stress] [--out results/yield_stress]

W+P at the reference tier with the liquid made Newtonian at --viscosity (Pa s; 4 is the paper's
Bingham liquid's plastic viscosity, Stokes number sqrt(rho_p (rho_p - rho_f) g d^3) / (18 sqrt(2)
mu) = 0.22: the viscous regime of Courrech du Pont et al. 2003, as Rondon's), settled dense (the
case's sample.solidFraction) and loose (--loose FRACTION:SETTLE_FRICTION: the packing control,
demDict settle.packingControl, settles the sample to FRACTION starting from SETTLE_FRICTION, and
stops naming settle.maxFriction if FRACTION lies beyond it). For each: the runout (granular front - L)
at the end, the grains' potential energy released by 0.5, 1, 2 and 3 s, and the basal pore
pressure under the initial column against hydrostatic per 0.1 s window (mixflow mixture-lambdas,
which needs /usr/bin/python3 with numpy and h5py).

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
from mixflow.commands.yield_stress_results import observables, settled_fraction

RUNOUT_RATIO = 2.0  # loose / dense runout, Rondon et al. 2011 (about)
RATIO_MIN = 1.5  # the check: the loose column runs at least 1.5 x the dense one's runout


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
    out = {f"{t:g}": pe0 - outputs.interpolated(dem, "pe_J", t) for t in times if t <= t_end + 1e-6}
    late = outputs.interpolated(dem, "pe_J", t_end - 0.5) - dem[-1]["pe_J"]
    return out, late > 0.05 * (pe0 - dem[-1]["pe_J"])


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--viscosity", default="4")
    ap.add_argument("--loose", default="0.56:0.7")
    ap.add_argument("--work", default=os.path.join(ROOT, "runs", "yield_stress"))
    ap.add_argument("--out", default=os.path.join(ROOT, "results", "yield_stress"))
    ap.add_argument("--np", default="1")
    a = ap.parse_args()
    frac, mu = a.loose.split(":")
    packings = {"dense": [], "loose": ["--set", f"sceneProperties.sample.solidFraction={frac}",
                                       "--set", f"demDict.settle.friction={mu}"]}
    res = {"viscosity_Pa_s": float(a.viscosity), "loose": a.loose, "tier": "reference",
           "reference": {"source": "Rondon, Pouliquen & Aussillous 2011 (Phys. Fluids 23, 073301)",
                         "runout_ratio_loose_over_dense": RUNOUT_RATIO,
                         "basal_excess_sign": {"dense": "negative", "loose": "positive"}},
           "command": "mixflow viscous-packing " + " ".join(sys.argv[1:]),
           "runs": {}}
    for name, sets in packings.items():
        work = os.path.join(os.path.abspath(a.work), f"viscous-{a.viscosity}-{name}")
        run(command("suite") + ["--tier", "reference",
             "--scenes", "W+P", "--work", work, "--np", a.np,
             "--set", "sceneProperties.liquid.viscosity=" + a.viscosity] + sets)
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
                    "runout_m": obs["granular_front_m"] - float(sample["length"]),
                    "pe_released_J_at": at,
                    "still_moving_at_end": moving,
                    "basal_excess_Pa": {f"{r['t0']:.1f}-{r['t1']:.1f}": r["excess_Pa"]
                                        for r in basal},
                    "basal_hydrostatic_Pa": {f"{r['t0']:.1f}-{r['t1']:.1f}": r["hydrostatic_Pa"]
                                             for r in basal}})
        res["runs"][name] = obs
    dense, loose = res["runs"]["dense"], res["runs"]["loose"]
    ratio = loose["runout_m"] / dense["runout_m"]
    early = lambda o: o["basal_excess_Pa"].get("0.0-0.1")  # noqa: E731
    res["checks"] = {
        "runout_ratio": {"measured": ratio, "reference": RUNOUT_RATIO, "minimum": RATIO_MIN,
                         "passes": ratio >= RATIO_MIN},
        # Energy released by 1 s, dense over loose: below 1 when the dense column is slower.
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
    print(json.dumps(res["checks"], indent=1))
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
