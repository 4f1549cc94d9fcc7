"""The coupled exchange interval T against the drag's relaxation number s = beta T / m.

A lone glass grain (d 0.5 mm, rho_p 2500) settles in a closed box of liquid (rho_f 1000, viscosity
--mu), the set-up of tests/coupling/run_settling.py (its case writer, mixflow/coupledcase.py:
cubic cells of 5 d, 8 x H x 8 cells, DiFeliceDrag + buoyancy + viscousForce, divided void fraction).
For every viscosity, drag integration and s, the exchange interval is T = s u_t / ((1 - rho_f /
rho_p) g) (beta at the terminal velocity: (m - m_f) g = beta u_t), exchangeEvery 20 DEM steps, and
the run lasts max(40 relaxation times m / beta, 60 T), cut so that the grain stays above the floor
of a box at most 200 cells tall (not run below 30 intervals). u_t is the Di Felice terminal velocity
(Cd = (0.63 + 4.8 / sqrt(Re))^2, solved here; the 'glass 0.5 mm in water' row of
tests/reference/terminal_velocity_single_sphere.csv at 1e-3 Pa s). Measured over the last 30 % of
the exchanges: the mean settling speed against u_t and its spread (max - min) / u_t; 'diverged'
when the run stopped, lost the grain or the speed passed 10 u_t.

Integrations: implicit, held (dragRelaxationLimit 0: the drag held over T unlimited) and
held_limited (the default dragRelaxationLimit 0.5). One CSV row per run.

  mixflow stability-drag --bin /work/main/build/bin --work /tmp/stab-drag \
      --csv results/stability/drag_interval.csv
"""
import argparse
import csv
import math
import os
import shutil
import sys

from mixflow import coupledcase as cc

D, RHO_P, RHO_F, G = 5e-4, 2500.0, 1000.0, 9.81
MAX_CELLS = 200  # box height in cells of 5 d


def terminal_velocity(mu):
    """Di Felice single-sphere terminal velocity (bisection on the force balance)."""
    w = (RHO_P - RHO_F) * G * math.pi * D**3 / 6

    def drag(u):
        re = RHO_F * u * D / mu
        cd = (0.63 + 4.8 / math.sqrt(re)) ** 2
        return 0.5 * cd * RHO_F * u * u * math.pi * D * D / 4

    lo, hi = 1e-30, 100.0
    for _ in range(200):
        mid = math.sqrt(lo * hi)
        lo, hi = (mid, hi) if drag(mid) < w else (lo, mid)
    return math.sqrt(lo * hi)


def one_run(a, mu, integration, s, work):
    u_t = terminal_velocity(mu)
    tau = u_t / ((1 - RHO_F / RHO_P) * G)  # m / beta at u_t
    T = s * tau
    every = 20
    h = 5 * D
    # The grain must not reach the floor: at most MAX_CELLS cells tall, the run cut to fit.
    # The limited held drag settles s / 0.5 times faster once clamped.
    speed = u_t * (max(1.0, s / 0.5) if integration == "held_limited" else 1.0)
    end = min(max(40 * tau, 60 * T), (MAX_CELLS - 3) * h / (1.3 * speed))
    row = dict(mu=mu, integration=integration, s=s, u_t=u_t, T=T, exchanges=int(end / T),
               mean_over_ut="", spread_over_ut="", status="")
    if end < 30 * T:
        row["status"] = "not run: the grain would reach the floor in 30 intervals"
        return row
    fall = speed * end
    hcells = max(24, int(math.ceil((1.3 * fall + 3 * h) / h)))
    box = cc.Box((8 * h, hcells * h, 8 * h), (8, hcells, 8))
    x0 = (0.5 * box.L[0] + 0.1 * h, box.L[1] - 1.5 * h, 0.5 * box.L[2] + 0.13 * h)
    dem = cc.liggghts_header(box, T / every, skin=0.5 * D) + f"""fix integr all nve/sphere
create_atoms 1 single {x0[0]!r} {x0[1]!r} {x0[2]!r} units box
set atom 1 diameter {D!r} density {RHO_P!r}
"""
    held = integration != "implicit"
    limit = 0.5 if integration == "held_limited" else 0.0
    coupling = f"""demScript "system/in.liggghts";
exchangeEvery {every};
forceModels (DiFeliceDrag buoyancy viscousForce);
voidFractionModel divided;
interpolation cell;
dragIntegration {"held" if held else "implicit"};
dragRelaxationLimit {limit!r};
maxVelocity {max(1.0, 100 * u_t)!r};
"""
    case = os.path.join(work, "case")
    try:
        cc.write_case(case, box, end, T, dem, coupling, rho_l=RHO_F, nu_l=mu / RHO_F)
        cc.run(case, a.bin + "/mixflowCoupled", a.blockmesh)
        rows = cc.read_exchange_log(case)
    except SystemExit:
        row["status"] = "diverged (run stopped)"
        return row
    n = len(rows)
    win = rows[int(0.7 * n):] or rows[-1:]
    vs = [-r["meanVy"] for r in win]
    mean = sum(vs) / len(vs)
    row["mean_over_ut"] = mean / u_t
    row["spread_over_ut"] = (max(vs) - min(vs)) / u_t
    lost = rows[-1]["particles"] != 1 or rows[-1]["particlesOutside"] != 0
    if lost or max(abs(v) for v in vs) > 10 * speed or not all(math.isfinite(v) for v in vs):
        row["status"] = "diverged"
    elif abs(mean / u_t - 1) <= a.tol and row["spread_over_ut"] <= a.tol:
        row["status"] = "ok"
    else:
        row["status"] = "off"
    if row["status"] == "ok":  # the others are kept to look at
        shutil.rmtree(case, ignore_errors=True)
    return row


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", required=True, help="mixflow's bin/ (mixflowCoupled)")
    ap.add_argument("--blockmesh", default=shutil.which("blockMesh") or "blockMesh")
    ap.add_argument("--work", required=True)
    ap.add_argument("--csv", required=True)
    ap.add_argument("--mu", default="1e-3,1,1e2,1e4")
    ap.add_argument("--s", default="0.1,0.5,1,1.5,1.9,2.5,5,20,100")
    ap.add_argument("--integrations", default="implicit,held,held_limited")
    ap.add_argument("--tol", type=float, default=0.03,
                    help="'ok' when the mean and the spread are within tol of u_t")
    a = ap.parse_args()
    os.environ.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")  # as foamcase.run_env
    done = {}
    if os.path.exists(a.csv):  # rows of an interrupted sweep are kept
        for r in csv.DictReader(open(a.csv)):
            done[(float(r["mu"]), r["integration"], float(r["s"]))] = r
    rows = []
    keys = ["mu", "integration", "s", "u_t", "T", "exchanges", "mean_over_ut", "spread_over_ut",
            "status"]
    os.makedirs(os.path.dirname(os.path.abspath(a.csv)), exist_ok=True)
    for mu in (float(m) for m in a.mu.split(",")):
        for integ in a.integrations.split(","):
            for s in (float(x) for x in a.s.split(",")):
                r = done.get((mu, integ, s)) or one_run(
                    a, mu, integ, s, os.path.join(a.work, f"mu{mu:g}_{integ}_s{s:g}"))
                rows.append(r)
                print("ROW", r, flush=True)
                grid = {(float(x["mu"]), x["integration"], float(x["s"])) for x in rows}
                kept = [x for k, x in done.items() if k not in grid]
                with open(a.csv, "w", newline="") as fh:
                    w = csv.DictWriter(fh, keys)
                    w.writeheader()
                    for x in kept + rows:
                        w.writerow({k: (f"{x[k]:.6g}" if isinstance(x[k], float) else x[k])
                                    for k in keys})
    return 0


if __name__ == "__main__":
    sys.exit(main())
