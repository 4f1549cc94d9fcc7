#!/usr/bin/env python3
"""The DEM step's convergence at the paper's stiffness (70/700 GPa): bench/coupled_vs_dry.py's
W&P bench scene (813 grains, water, 2-D fluid at 0.06 m, 0.2 s of collapse) at each DEM step,
the exchange interval held at 5e-5 s in time (exchangeEvery = 5e-5 s / step), each run settling
its own sample softened at 1e-2 and stiffened (settle.stiffenFrom). Writes one JSON with, per
step, the CPU of the coupled and the dry collapse and the coupled run's observables, and their
change against the smallest step.

usage: dem_step_convergence.py [--steps 5e-7,1e-6,2e-6,auto] [--json OUT] [--collect DIR]
  --collect DIR: read DIR/step_<s>.json of earlier runs instead of running them (the JSON's
  command is then that of the runs it collects)."""
import argparse
import json
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
INTERVAL_S = 5e-5  # the paper's 100 steps of 5e-7 s
AUTO_STEP_S = 1.24e-6  # 0.1 T_R at 70 GPa (T_R 1.24e-5 s, 24 mm grains): the auto run's interval


def run(step, out):
    every = round(INTERVAL_S / (AUTO_STEP_S if step == "auto" else float(step)))
    cmd = [sys.executable, os.path.join(HERE, "coupled_vs_dry.py"), "--liquid", "W",
           "--young-modulus-factor", "1", "--stiffen-from", "1e-2", "--exchange-every", str(every),
           "--end", "0.2", "--json", out] + ([] if step == "auto" else ["--dem-step", step])
    subprocess.run(cmd, check=True)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--steps", default="5e-7,1e-6,2e-6,auto")
    ap.add_argument("--json", default="dem_step_convergence.json")
    ap.add_argument("--collect")
    a = ap.parse_args()
    work = a.collect or os.path.dirname(os.path.abspath(a.json))
    rows = []
    for step in a.steps.split(","):
        path = os.path.join(work, f"step_{step}.json")
        if not a.collect:
            run(step, path)
        d = json.load(open(path))
        r = d["runs"][0]
        rows.append({"dem_step": step, "dem_step_s": r["dem_step_s"],
                     "exchange_every": r["exchange_every"],
                     "exchange_interval_s": r["exchange_interval_s"],
                     "coupled_cpu_s": r["coupled_cpu_s"], "dry_collapse_cpu_s": d["dry_collapse_cpu_s"],
                     "settle_cpu_s": d["settle_cpu_s"], "observables": r["observables"]})
    finest = min(rows, key=lambda r: r["dem_step_s"])
    for r in rows:
        r["cost_over_finest"] = r["coupled_cpu_s"] / finest["coupled_cpu_s"]
        r["change_against_finest"] = {
            k: (v - finest["observables"][k]) / abs(finest["observables"][k])
            for k, v in r["observables"].items() if finest["observables"][k]}
    out = {"scene": "bench/coupled_vs_dry.py's W&P scene at 70/700 GPa, settled from 1e-2",
           "rows": rows, "command": f"mixflow bench dem_step_convergence --steps {a.steps} --json {a.json}"}
    json.dump(out, open(a.json, "w"), indent=1)
    for r in rows:
        ch = r["change_against_finest"]
        print(f"{r['dem_step']:>5} dt {r['dem_step_s']:.3g} s, every {r['exchange_every']}: coupled "
              f"{r['coupled_cpu_s']:.1f} CPU s ({r['cost_over_finest']:.2f}x), dry "
              f"{r['dry_collapse_cpu_s']:.1f} s; front 0.2 s {ch['granular_front_m_at_0.2s']:+.2%}, "
              f"liquid front {ch['liquid_front_m_at_0.2s']:+.2%}, PE released "
              f"{ch['particle_pe_released_J_at_0.2s']:+.2%}, KE {ch['particle_ke_J_at_0.2s']:+.2%}")


if __name__ == "__main__":
    main()
