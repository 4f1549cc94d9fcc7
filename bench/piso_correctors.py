#!/usr/bin/env python3
"""How many PISO correctors a viscous liquid needs: accuracy and cost against the viscous number.

PISO corrects the pressure with the momentum matrix's diagonal only; the neighbours' share of the
velocity correction is dropped and recovered by the next corrector. Its weight against the
diagonal is set by the viscous number D = mu dt / (rho dx^2) (the viscous term's off-diagonal
coefficients over the unsteady one). So the correctors a run needs depend on D, not on the
rheology's name.

This sweep measures that dependence on a 2-D Newtonian column (0.1 x 0.1 m in a closed 0.3 x
0.15 m channel, 5 mm cells, fixed step dt = maxDeltaT = 1e-3 s, 0.5 s) for mu over a range of D,
with nCorrectors = 2, 3, 4, 10, 20. Each run is judged against the same mu's run with the most
correctors that neither diverged nor burst (kinetic energy peaking at over 10x the calmest run's):
largest difference of the bed front (relative to the reference's front advance) and of the
time-integrated kinetic energy (relative), the CPU time, and whether it finished with a bounded
energy (a run whose kinetic energy passes the column's initial potential energy, that stops, or
that is still running after --timeout seconds with its step cut by the Courant limit, is
'diverged').

Usage: mixflow bench piso_correctors [--mu 1,5,25,100,250,1000] [--correctors 2,3,4,10,20]
                                        [--json OUT] [--csv OUT] [--work DIR] [--bin build/bin]
"""

import argparse
import csv
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time

sys.dont_write_bytecode = True
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
from mixflow import liquidcase  # noqa: E402  (write_case: the liquid tests' case writer)
from mixflow import outputs  # noqa: E402

RHO, DX, DT = 1000.0, 0.005, 1e-3


def write_case(case, mu, ncorr, end):
    """The column as a user writes it (sceneProperties, cfdDict, controlDict), with the liquid
    tests' case writer."""
    scene = ("content liquid;\nsample { length 0.1; height 0.1; width 0.1; }\n"
             "channel { length 0.3; height 0.15; }\n"
             f"liquid {{ rheology Newtonian; density {RHO}; viscosity {mu}; surfaceTension 0; }}\n")
    cfd = f"dimensions 2;\ncellSize {DX};\ndeltaT {DT};\nmaxDeltaT {DT};\nnCorrectors {ncorr};\n"
    liquidcase.write_case(case, scene, cfd, end, end)


def run(cmd, case, log, timeout=None):
    """Exit status, or None when the run passed `timeout` seconds (and was stopped)."""
    with open(os.path.join(case, log), "w") as f:
        try:
            return subprocess.run(cmd, cwd=case, stdout=f, stderr=subprocess.STDOUT,
                                  timeout=timeout).returncode
        except subprocess.TimeoutExpired:
            return None


def series(case):
    path = os.path.join(case, outputs.LIQUID_SERIES)
    if not os.path.exists(path):
        return []
    return outputs.read_series(path)


def one_run(a, work, mu, ncorr):
    case = os.path.join(work, f"mu{mu:g}_n{ncorr}")
    write_case(case, mu, ncorr, a.end)
    if run([os.path.join(a.bin, "mixflowPrepare"), "-case", case], case, "log.prepare") != 0:
        sys.exit(f"{case}: mixflowPrepare failed (see log.prepare)")
    if run([a.blockmesh], case, "log.blockMesh") != 0:
        sys.exit(f"{case}: blockMesh failed")
    t0 = os.times()
    # A diverging run cuts its adaptive step (Courant) and crawls: stop it after --timeout.
    rc = run([os.path.join(a.bin, "mixflowFoam")], case, "log.mixflowFoam", a.timeout)
    t1 = os.times()
    cpu = (t1.children_user + t1.children_system) - (t0.children_user + t0.children_system)
    s = series(case)
    pe0 = s[0]["potential_energy_J"] if s else 0.0
    ke_max = max((r["kinetic_energy_J"] for r in s), default=float("nan"))
    end_t = s[-1]["time_s"] if s else 0.0
    diverged = rc is None or rc != 0 or end_t < a.end - 0.5 * DT or not ke_max <= pe0
    return {"mu_Pa_s": mu, "n_correctors": ncorr, "viscous_number_D": mu * DT / (RHO * DX * DX),
            "cpu_s": round(cpu, 2), "end_time_s": end_t,
            "exit_status": "timed out" if rc is None else rc,
            "peak_kinetic_energy_J": ke_max, "initial_potential_energy_J": pe0,
            "diverged": diverged, "series": s}


def compare(r, ref):
    """Front and kinetic-energy errors against the reference run, at the same times: the largest
    front difference relative to the reference's front advance, and the difference of the
    time-integrated kinetic energy relative to the reference's (the step-to-step energy is noisy
    at small speeds, its integral is not)."""
    if r["diverged"] or ref["diverged"]:
        return None, None
    by_t = {round(x["time_s"], 9): x for x in ref["series"]}
    dfront, ike, ike_ref, prev = 0.0, 0.0, 0.0, None
    for x in r["series"]:
        y = by_t.get(round(x["time_s"], 9))
        if y is None:
            continue
        dfront = max(dfront, abs(x["front_bed_m"] - y["front_bed_m"]))
        if prev is not None:
            dt = x["time_s"] - prev[0]["time_s"]
            ike += 0.5 * dt * (x["kinetic_energy_J"] + prev[0]["kinetic_energy_J"])
            ike_ref += 0.5 * dt * (y["kinetic_energy_J"] + prev[1]["kinetic_energy_J"])
        prev = (x, y)
    advance = abs(ref["series"][-1]["front_bed_m"] - ref["series"][0]["front_bed_m"])
    return dfront / max(advance, 1e-9), abs(ike - ike_ref) / max(ike_ref, 1e-300)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--mu", default="1,5,25,100,250,1000", help="Newtonian viscosities (Pa s)")
    ap.add_argument("--correctors", default="2,3,4,10,20",
                    help="nCorrectors; the reference is the largest that neither diverged "
                         "nor burst")
    ap.add_argument("--end", type=float, default=0.5)
    ap.add_argument("--timeout", type=float, default=60,
                    help="CPU-bound wall seconds after which a run counts as diverged")
    ap.add_argument("--bin", default=os.path.join(ROOT, "build", "bin"))
    ap.add_argument("--blockmesh", default="blockMesh")
    ap.add_argument("--work", help="run directory (default: a temporary one, removed)")
    ap.add_argument("--json")
    ap.add_argument("--csv")
    a = ap.parse_args()
    os.environ.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")
    mus = [float(x) for x in a.mu.split(",")]
    ncs = sorted(int(x) for x in a.correctors.split(","))
    work = a.work or tempfile.mkdtemp(prefix="piso_correctors_")
    os.makedirs(work, exist_ok=True)
    rows = []
    t_start = time.time()
    print(f"{'mu (Pa s)':>10} {'D':>7} {'nCorr':>5} {'CPU s':>7} {'front err':>10} "
          f"{'int KE err':>11}  state", flush=True)
    for mu in mus:
        runs = {n: one_run(a, work, mu, n) for n in ncs}
        # A run whose kinetic energy peaks at more than 10x the calmest run's has burst (at
        # D = 400 even 20 correctors do, where 10 do not): it can be no reference.
        calm = min(r["peak_kinetic_energy_J"] for r in runs.values() if not r["diverged"])
        for r in runs.values():
            r["burst"] = not r["diverged"] and r["peak_kinetic_energy_J"] > 10 * calm
        ref_n = max(n for n in ncs if not runs[n]["diverged"] and not runs[n]["burst"])
        ref = runs[ref_n]
        for n in ncs:
            r = runs[n]
            df, dk = compare(r, ref)
            row = {k: v for k, v in r.items() if k != "series"}
            row.update({"front_error_of_advance": df, "integrated_ke_error": dk,
                        "cpu_ratio_to_reference": round(r["cpu_s"] / ref["cpu_s"], 3)
                        if ref["cpu_s"] > 0 else None})
            rows.append(row)
            state = ("diverged" if r["diverged"] else "burst" if r["burst"] else
                     "reference" if n == ref_n else "ok")
            row["state"] = state
            fmt = (lambda v, f: "-" if v is None else format(v, f))
            print(f"{mu:>10g} {row['viscous_number_D']:>7.3g} {n:>5d} {r['cpu_s']:>7.2f} "
                  f"{fmt(df, '10.2e')} {fmt(dk, '11.2e')}  {state}", flush=True)
        print(f"  ({time.time() - t_start:.0f} s wall so far)", flush=True)
    cmd = "mixflow bench piso_correctors " + " ".join(sys.argv[1:])
    out = {"command": cmd, "case": "2-D Newtonian column 0.1 x 0.1 m, channel 0.3 x 0.15 m, "
           f"cells {DX} m, dt {DT} s fixed, end {a.end} s", "runs": rows}
    if a.json:
        with open(a.json, "w") as f:
            json.dump(out, f, indent=1)
    if a.csv:
        with open(a.csv, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
            w.writeheader()
            w.writerows(rows)
    if not a.work:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
