"""Lobovsky et al. (2014) water dam break: the front with an instant and a lifted gate.

    mixflow lobovsky-gate [--heights 600,300] [--cell 0.01] [--work /tmp/lobovsky_gate]

The experiment (tests/reference/lobovsky2014_front_H600.csv, _H300.csv; their headers): a tank
1610 mm long, the water column 600 mm long and H = 600 or 300 mm high behind a gate lifted at a
median speed of 4.53 (H600) or 3.46 (H300) m/s, the downstream wall 1010 mm from the gate; the
wave tip's distance from the gate against time from the gate's first motion.

The scene: 2-D (dimensions 2), sample 0.6 x H, channel 1.61 x 1.0 m (the tank's height is not in
the reference files; the air above the column is 0.4 m or more), water (rho 998.2 kg/m3,
mu 1.0e-3 Pa s, sigma 0.0728 N/m), cells of --cell m, the outlet at the wall's position (the front
is compared only until it reaches the wall, so the missing wall does not enter). Two runs per
height: `gate { removal instant; }` and `gate { removal lifted; speed V; }` with the median speed
(the plate's default thickness, two cells, on the downstream side of x = 0.6 m). Nothing is tuned.

Compared: the front x(t) - L (front_bed_m, the bed cell row at alpha >= 0.5) at every datum with
0 < t and x below the wall (1.01 m); the relative error (x_sim - x_exp) / x_exp, summarised over
the data with x_exp >= 0.1 H (nearer the gate the relative error of a few millimetres diverges)
whose simulated fronts are both still two cells short of the outlet (where they stop).

Output (--out, default results/pure_liquids/gate/): lobovsky_H<H>.csv per height, one row per
datum: t_s, x_exp_m, x_instant_m, x_lifted_m, err_instant, err_lifted; summary.csv: per height
and gate the mean and largest |error|, the largest over the data with x_exp >= H (the front one
column height out), the error at the last datum before the wall, the CPU time.
Runs serially.
"""

import argparse
import csv
import os
import time

from mixflow import ROOT
from mixflow import liquidcase as rlc

WALL = 1.01  # m, the downstream wall's distance from the gate
SPEED = {600: 4.53, 300: 3.46}  # m/s, the median lift speeds of the reference files' headers


def scene(h, gate):
    return (f"content liquid;\nsample {{ length 0.6; height {h}; width 0.15; }}\n"
            "channel { length 1.61; height 1.0; }\n"
            "liquid { rheology Newtonian; density 998.2; viscosity 1.0e-3; "
            "surfaceTension 0.0728; }\n"
            f"gate {{ {gate} }}\n")


def read_reference(path):
    """[(t_s, x_m)] of a reference file (columns by name; # comments)."""
    with open(path) as f:
        rows = [ln for ln in f if not ln.startswith("#")]
    out = []
    for r in csv.DictReader(rows):
        out.append((float(r["t_s"]), float(r["x_m"])))
    return out


def run(a, name, h, gate, end):
    case = os.path.join(a.work, name)
    rlc.write_case(case, scene(h, gate), f"dimensions 2;\ncellSize {a.cell};\n", end, end)
    t0 = time.process_time()
    c0 = os.times()
    series = rlc.run_case(a, case)
    c1 = os.times()
    cpu = (c1.children_user + c1.children_system) - (c0.children_user + c0.children_system)
    return series, cpu + time.process_time() - t0


def front_at(series, t, L=0.6):
    return rlc.interp(series, "front_bed_m", t) - L


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--heights", default="600,300", help="column heights in mm: 600, 300")
    p.add_argument("--cell", type=float, default=0.01, help="cell size (m)")
    p.add_argument("--end", type=float, default=0.6, help="end time (s): past the wall arrival")
    p.add_argument("--work", default="/tmp/lobovsky_gate")
    rlc.add_program_arguments(p, ROOT)
    p.add_argument("--out", default=os.path.join(ROOT, "results/pure_liquids/gate"))
    a = p.parse_args()
    a.work = os.path.abspath(a.work)
    os.makedirs(a.work, exist_ok=True)
    os.makedirs(a.out, exist_ok=True)

    summary = []
    for hmm in (int(v) for v in a.heights.split(",")):
        h = hmm / 1000.0
        ref = read_reference(os.path.join(ROOT, "tests", "reference",
                                          f"lobovsky2014_front_H{hmm}.csv"))
        runs = {}
        for gate, entry in (("instant", "removal instant;"),
                            ("lifted", f"removal lifted; speed {SPEED[hmm]};")):
            runs[gate] = run(a, f"H{hmm}_{gate}_{a.cell:g}", h, entry, a.end)
            print(f"H{hmm} {gate}: {len(runs[gate][0])} rows, CPU {runs[gate][1]:.0f} s",
                  flush=True)
        rows = []
        for t, x in ref:
            if t <= 0 or x >= WALL - 1e-9 or t > a.end:
                continue
            xi, xl = (front_at(runs[g][0], t) for g in ("instant", "lifted"))
            rows.append([t, x, xi, xl, (xi - x) / x, (xl - x) / x])
        path = os.path.join(a.out, f"lobovsky_H{hmm}.csv")
        with open(path, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["t_s", "x_exp_m", "x_instant_m", "x_lifted_m", "err_instant",
                        "err_lifted"])
            w.writerows([[f"{v:.5g}" for v in r] for r in rows])
        # Up to the wall: the simulated fronts still two cells short of the outlet (there they
        # stop), and away from the gate.
        far = [r for r in rows if r[1] >= 0.1 * h and max(r[2], r[3]) < WALL - 2 * a.cell]
        late = [r for r in far if r[1] >= h]  # the front one column height or more out
        for k, gate in ((4, "instant"), (5, "lifted")):
            errs = [abs(r[k]) for r in far]
            late_errs = [abs(r[k]) for r in late]
            summary.append([hmm, gate, SPEED[hmm] if gate == "lifted" else "", a.cell, len(far),
                            sum(errs) / len(errs), max(errs), len(late), max(late_errs),
                            far[-1][k], far[-1][0], runs[gate][1]])
            print(f"H{hmm} {gate:8s}: {len(far)} data with x >= 0.1 H: mean |err| "
                  f"{summary[-1][5]:.3f}, max {summary[-1][6]:.3f}; {len(late)} with x >= H: "
                  f"max {max(late_errs):.3f}; last before the wall (t = {far[-1][0]:.3f} s) "
                  f"{far[-1][k]:+.3f}")
        print(f"wrote {path}", flush=True)
    path = os.path.join(a.out, "summary.csv")
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["H_mm", "gate", "speed_m_s", "cell_m", "n_data", "mean_abs_err",
                    "max_abs_err", "n_data_x_ge_H", "max_abs_err_x_ge_H", "err_last_before_wall",
                    "t_last_s", "cpu_s"])
        w.writerows([[f"{v:.4g}" if isinstance(v, float) else v for v in r] for r in summary])
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
