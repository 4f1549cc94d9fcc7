"""Martin & Moyce (1952) water column (n^2 = 1): what a lifted gate changes in the front.

    mixflow martin-moyce-gate [--speeds 1,2,4.53] [--cells 40] [--work /tmp/mm_gate]

The CTest's column (tests/cfd/run_liquid_cases.py::martin_moyce: a = 0.05715 m, 2-D, a/40 cells,
water/air, to t = 0.26 s) with the instant removal and with the plate lifted at each speed (m/s;
4.53 is Lobovsky et al.'s median for their 600 mm column; the plate two cells thick). Nothing is
tuned: the question is how far a lift at the speeds experiments report moves the front, against
the instant gate's lead over the data.

Output (--out, default results/pure_liquids/gate/): martin_moyce.csv, one row per front datum
(T = t sqrt(g/a), Z = x/a): T, Z_exp and Z of each run; martin_moyce_summary.csv, per run: the
mean and largest Z - Z_exp over the data with 1 <= T <= 3.3, the slope dZ/dT fitted there, and
the front's delay against the instant gate (ms) where it reaches Z = 2, 3 and 4. Runs serially.
"""

import argparse
import csv
import math
import os

import numpy as np

from mixflow import ROOT
from mixflow import liquidcase as rlc
from mixflow.paper import G

A = rlc.MM_SIDE
T_RANGE = (1.0, 3.3)  # the data's range of the slope and the errors
Z_MARKS = (2.0, 3.0, 4.0)


def z_of_t(series):
    """(T, Z) of a run: the bed-row front from the gate side's back wall, over a."""
    t = np.array([r["time_s"] for r in series])
    x = np.array([r["front_bed_m"] for r in series])
    return t * math.sqrt(G / A), x / A


def time_at(T, Z, z):
    """The first T at which Z reaches z (linear between rows), None if it never does."""
    for i in range(1, len(Z)):
        if Z[i - 1] < z <= Z[i]:
            return T[i - 1] + (T[i] - T[i - 1]) * (z - Z[i - 1]) / (Z[i] - Z[i - 1])
    return None


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--speeds", default="1,2,4.53", help="lift speeds (m/s), comma-separated")
    p.add_argument("--cells", type=int, default=40, help="cells over a")
    p.add_argument("--work", default="/tmp/mm_gate")
    rlc.add_program_arguments(p, ROOT)
    p.add_argument("--out", default=os.path.join(ROOT, "results/pure_liquids/gate"))
    a = p.parse_args()
    a.work = os.path.abspath(a.work)
    os.makedirs(a.out, exist_ok=True)
    ref = rlc.read_martin_moyce(os.path.join(ROOT, "tests", "reference",
                                             "martin_moyce_1952_n2eq1_front_height.csv"))["front_Z"]
    gates = [("instant", "")] + [(f"lifted_{v:g}", f"removal lifted; speed {v:g};")
                                  for v in (float(s) for s in a.speeds.split(","))]
    runs = {}
    for name, gate in gates:
        case = os.path.join(a.work, name)
        rlc.write_martin_moyce_case(case, a.cells, gate)
        runs[name] = z_of_t(rlc.run_case(a, case))
        print(f"{name}: {len(runs[name][0])} rows", flush=True)
    with open(os.path.join(a.out, "martin_moyce.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["T", "Z_exp"] + [f"Z_{n}" for n, _ in gates])
        for T, Z in ref:
            w.writerow([T, Z] + [f"{np.interp(T, *runs[n]):.4f}" for n, _ in gates])
    rows = []
    T0, Z0 = runs["instant"]
    scale_ms = 1000 * math.sqrt(A / G)
    for name, _ in gates:
        T, Z = runs[name]
        data = [(t, z) for t, z in ref if T_RANGE[0] <= t <= T_RANGE[1]]
        err = [np.interp(t, T, Z) - z for t, z in data]
        tt = np.array([t for t, _ in data])
        slope = np.polyfit(tt, np.interp(tt, T, Z), 1)[0]
        delays = []
        for z in Z_MARKS:
            t_run, t_inst = time_at(T, Z, z), time_at(T0, Z0, z)
            delays.append("" if t_run is None or t_inst is None
                          else f"{(t_run - t_inst) * scale_ms:.1f}")
        rows.append([name, f"{np.mean(err):.3f}", f"{max(err, key=abs):.3f}", f"{slope:.3f}"]
                    + delays)
        print(f"{name}: mean Z - Z_exp {rows[-1][1]}, largest {rows[-1][2]}, dZ/dT {rows[-1][3]}, "
              f"delay at Z = 2/3/4: {'/'.join(delays)} ms", flush=True)
    exp_slope = np.polyfit(*zip(*[(t, z) for t, z in ref if T_RANGE[0] <= t <= T_RANGE[1]]), 1)[0]
    rows.append(["experiment", "", "", f"{exp_slope:.3f}", "", "", ""])
    with open(os.path.join(a.out, "martin_moyce_summary.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["run", "mean_dZ", "largest_dZ", "slope_dZdT"]
                   + [f"delay_ms_at_Z{z:g}" for z in Z_MARKS])
        w.writerows(rows)


if __name__ == "__main__":
    main()
