"""Post-processing of scripts/liquid_results.sh (pure-liquid scenes).

  liquid_results.py --calibrate CASE T
      prints the channel length whose outlet the water front of CASE (a W run in a long channel)
      reaches at time T: the bed front x_f(T), interpolated in the time series, to 0.01 m.
  liquid_results.py --side-walls WORK OUT --command CMD
      compares WORK/sidewalls-3d (case W as committed: 3-D, walls at z = 0 and W) with
      WORK/sidewalls-2d (the same in 2-D, no side walls): side_walls.csv/.png/.json in OUT.
  liquid_results.py --make WORK OUT --channel-length LC --command CMD
      writes into OUT: fronts.csv/.png (W, HB, B), slumps_normalised.csv/.png (HB-I, B-I: X_f/L vs
      t/T), froude.csv/.png (Fr at x = 1.38 m vs t - t0), energies.png, regularisation.csv,
      calibration.json and summary.json.

Definitions (also in summary.json): front = largest x where the bed cell row holds alpha >= 0.5
(postProcessing/liquid/timeSeries.csv, front_bed_m); t0 = first time the front reaches the
section x = 1.38 m; the flow "turns subcritical" at the first time t > t0 from which Fr < 1 holds
for at least HOLD_S seconds (or to the end of the run); Fr is undefined (nan) while the depth at
the section is below minDepth (half a cell).
"""

import argparse
import json
import math
import os
import sys

from mixflow.froude import HOLD_S, first_time, subcritical_after_arrival
from mixflow.outputs import interpolated as at
from mixflow.outputs import series  # (series(case): the liquid time series)
from mixflow.paper import L_SLUMP, PAPER_SUBCRITICAL, T_SLUMP


def calibrate(case, t):
    x = at(series(case), "front_bed_m", t)
    if math.isnan(x):
        sys.exit(f"no front at t = {t} s in {case}")
    print(f"{x:.2f}")


def make(work, out, lc, command):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    os.makedirs(out, exist_ok=True)
    runs = {c: series(os.path.join(work, c)) for c in ("W", "HB", "B", "HB-I", "B-I")}
    cal = series(os.path.join(work, "calibration"))

    # Fronts W, HB, B.
    tgrid = [0.01 * k for k in range(0, 401)]
    with open(os.path.join(out, "fronts.csv"), "w") as f:
        f.write("time_s,front_W_m,front_HB_m,front_B_m\n")
        for t in tgrid:
            f.write(f"{t:.2f}," + ",".join(f"{at(runs[c], 'front_bed_m', t):.4f}"
                                          for c in ("W", "HB", "B")) + "\n")
    fig, ax = plt.subplots(figsize=(6, 4))
    for c, st in (("W", "-"), ("HB", "--"), ("B", ":")):
        ax.plot([r["time_s"] for r in runs[c]], [r["front_bed_m"] for r in runs[c]], st, label=c)
    ax.axhline(lc, color="grey", lw=0.5)
    ax.text(0.05, lc, f" outlet x = {lc} m", va="bottom", fontsize=8)
    ax.set(xlabel="t (s)", ylabel="liquid front x_f (m), alpha >= 0.5 on the bed",
           title="Pure liquids W, HB, B (2-D, 0.02 m cells)")
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(out, "fronts.png"), dpi=120)
    plt.close(fig)

    # HB-I, B-I normalised fronts.
    with open(os.path.join(out, "slumps_normalised.csv"), "w") as f:
        f.write("case,time_s,t_over_T,Xf_over_L\n")
        for c in ("HB-I", "B-I"):
            step = max(1, len(runs[c]) // 400)
            for r in runs[c][::step] + [runs[c][-1]]:
                f.write(f"{c},{r['time_s']:.5g},{r['time_s'] / T_SLUMP[c]:.5g},"
                        f"{r['front_bed_m'] / L_SLUMP[c]:.5g}\n")
    fig, ax = plt.subplots(figsize=(6, 4))
    for c, st in (("HB-I", "-"), ("B-I", "--")):
        rows = [r for r in runs[c] if r["time_s"] > 0]
        ax.semilogx([r["time_s"] / T_SLUMP[c] for r in rows],
                    [r["front_bed_m"] / L_SLUMP[c] for r in rows], st,
                    label=f"{c} (T = {T_SLUMP[c]:g} s)")
    ax.set(xlabel="t / T", ylabel="X_f / L", title="Slumps HB-I, B-I (2-D)")
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(out, "slumps_normalised.png"), dpi=120)
    plt.close(fig)

    # Froude number at x = 1.38 m.
    sub, arrival = {}, {}
    fig, ax = plt.subplots(figsize=(6, 4))
    with open(os.path.join(out, "froude.csv"), "w") as f:
        f.write("case,time_s,t_minus_t0_s,depth_m,velocity_m_s,froude\n")
        for c, st in (("W", "-"), ("HB", "--"), ("B", ":")):
            t0, ts = subcritical_after_arrival(runs[c])
            arrival[c] = t0
            sub[c] = None if ts is None else round(ts - t0, 3)
            rows = [r for r in runs[c] if t0 is not None and r["time_s"] >= t0]
            step = max(1, len(rows) // 400)
            for r in rows[::step]:
                f.write(f"{c},{r['time_s']:.4f},{r['time_s'] - t0:.4f},{r['section_depth_m']:.5g},"
                        f"{r['section_velocity_m_s']:.5g},{r['section_froude']:.5g}\n")
            ax.plot([r["time_s"] - t0 for r in rows], [r["section_froude"] for r in rows], st,
                    label=f"{c}: subcritical after {sub[c]} s (paper {PAPER_SUBCRITICAL[c]} s)")
    ax.axhline(1, color="grey", lw=0.5)
    ax.set(xlabel="t - t0 (s)", ylabel="Fr = v / sqrt(g h) at x = 1.38 m", ylim=(0, 5),
           title="Froude number at x = 1.38 m (2-D)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "froude.png"), dpi=120)
    plt.close(fig)

    # Energies of the liquid.
    fig, ax = plt.subplots(figsize=(6, 4))
    for c, st in (("W", "-"), ("HB", "--"), ("B", ":")):
        e0 = runs[c][0]["potential_energy_J"]
        ax.plot([r["time_s"] for r in runs[c]], [r["potential_energy_J"] / e0 for r in runs[c]],
                st, label=f"{c} E_p / E_p0")
        ax.plot([r["time_s"] for r in runs[c]], [r["kinetic_energy_J"] / e0 for r in runs[c]],
                st, lw=0.8, label=f"{c} E_k / E_p0")
    ax.set(xlabel="t (s)", ylabel="energy / initial potential energy",
           title="Liquid energies (2-D slab of width W)")
    ax.legend(fontsize=8, ncol=2)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "energies.png"), dpi=120)
    plt.close(fig)

    # Regularisation: viscosity cap vs fronts.
    reg = []
    for cap in ("1e2", "1e3", "1e4", "1e5"):
        hb = runs["HB"] if cap == "1e4" else series(os.path.join(work, f"cap-HB-{cap}"))
        sl = series(os.path.join(work, f"cap-slump-{cap}"))
        reg.append({"viscosityCap_Pa_s": float(cap),
                    "HB_front_t0.5_m": round(at(hb, "front_bed_m", 0.5), 4),
                    "HB_front_t1.0_m": round(at(hb, "front_bed_m", 1.0), 4),
                    "HB_back_wall_depth_t4_m": round(hb[-1]["back_wall_depth_m"], 4),
                    "slump_front_t1_m": round(at(sl, "front_bed_m", 1.0), 4),
                    "slump_front_t4_m": round(sl[-1]["front_bed_m"], 4),
                    "slump_front_advance_t3_t4_mm":
                        round(1000 * (sl[-1]["front_bed_m"] - at(sl, "front_bed_m", 3.0)), 2)})
    with open(os.path.join(out, "regularisation.csv"), "w") as f:
        f.write(",".join(reg[0]) + "\n")
        for r in reg:
            f.write(",".join(str(v) for v in r.values()) + "\n")

    # Calibration.
    arrive = {x: first_time(cal, lambda r, x=x: r["front_bed_m"] >= x) for x in (4.0, 5.0, 6.0)}
    calib = {"rule": "channel length = x_f(t = 1.25 s) of case W (2-D, 0.02 m cells) in an 8 m "
                     "channel: the water front reaches the outlet at 1.25 s (Li & Zhao: water "
                     "leaves the domain from about t = 1.25 s)",
             "front_at_1.25_s_m": round(at(cal, "front_bed_m", 1.25), 3),
             "arrival_time_s_at_x_m": {str(k): v for k, v in arrive.items()},
             "channel_length_m": lc}
    with open(os.path.join(out, "calibration.json"), "w") as f:
        json.dump(calib, f, indent=2)
        f.write("\n")

    w_out = first_time(runs["W"], lambda r: r["volume_outlet_m3"] > 1e-3 * r["volume_domain_m3"])
    summary = {
        "subcritical_after_arrival_s": sub,
        "paper_subcritical_after_arrival_s": PAPER_SUBCRITICAL,
        "arrival_t0_at_1.38_m_s": arrival,
        "channel_length_m": lc,
        "channel_height_m": 1.2,
        "W_outflow_starts_s": w_out,
        "front_order_at_2s": sorted(("W", "HB", "B"),
                                    key=lambda c: -at(runs[c], "front_bed_m", 2.0)),
        "fidelity": "2-D (dimensions 2: one cell across the width W, no side walls), cells "
                    "0.02 m for W/HB/B (H/30), 0.0065 m for HB-I (H/20), 0.0022 m for B-I (H/10)",
        "definitions": {
            "front": "largest x where the bed cell row has alpha >= 0.5 (interpolated)",
            "t0": "first time the front reaches x = 1.38 m",
            "subcritical": f"first t > t0 from which Fr < 1 for {HOLD_S} s; Fr = q/h / sqrt(g h) "
                           "with h, q the width-averaged liquid depth and discharge at 1.38 m",
        },
        "regularisation": reg,
        "command": command,
    }
    with open(os.path.join(out, "summary.json"), "w") as f:
        json.dump(summary, f, indent=2)
        f.write("\n")
    print(json.dumps({"subcritical_after_arrival_s": sub, "channel_length_m": lc}))


def side_walls(work, out, command):
    """Case W with and without side walls: fronts, Froude at 1.38 m, subcritical time, outflow."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    runs = {d: series(os.path.join(work, f"sidewalls-{d}")) for d in ("2d", "3d")}
    res = {}
    for d, rows in runs.items():
        t0, ts = subcritical_after_arrival(rows)
        out_t = first_time(rows, lambda r: r["volume_outlet_m3"] > 1e-3 * r["volume_domain_m3"])
        res[d] = {"arrival_t0_s": t0,
                  "subcritical_after_arrival_s": None if ts is None else round(ts - t0, 3),
                  "front_m": {str(t): round(at(rows, "front_bed_m", t), 3)
                              for t in (0.5, 1.0, 1.25)},
                  "outflow_starts_s": out_t,
                  "simulated_to_s": rows[-1]["time_s"]}
    os.makedirs(out, exist_ok=True)
    tgrid = [0.01 * k for k in range(0, 221)]
    with open(os.path.join(out, "side_walls.csv"), "w") as f:
        f.write("time_s,front_2d_m,front_3d_m,froude_2d,froude_3d\n")
        for t in tgrid:
            f.write(f"{t:.2f}," + ",".join(f"{at(runs[d], k, t):.4f}" for k in
                                           ("front_bed_m", "section_froude")
                                           for d in ("2d", "3d")).replace("nan", "") + "\n")
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    for d, st in (("2d", "--"), ("3d", "-")):
        rows, r = runs[d], res[d]
        lab = "2-D (no side walls)" if d == "2d" else "3-D (walls at z = 0, W)"
        ax[0].plot([q["time_s"] for q in rows], [q["front_bed_m"] for q in rows], st, label=lab)
        ax[1].plot([q["time_s"] - r["arrival_t0_s"] for q in rows],
                   [q["section_froude"] for q in rows], st,
                   label=f"{lab}: subcritical after {r['subcritical_after_arrival_s']} s")
    ax[0].set(xlabel="t (s)", ylabel="liquid front x_f (m)", title="Case W, 0.03 m cells")
    ax[1].axhline(1, color="grey", lw=0.5)
    ax[1].set(xlabel="t - t0 (s)", ylabel="Fr at x = 1.38 m", ylim=(0, 5),
              title=f"paper: subcritical after {PAPER_SUBCRITICAL['W']} s")
    for a in ax:
        a.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "side_walls.png"), dpi=120)
    plt.close(fig)
    summary = {"command": command, "case": "W (cases/W: 0.03 m cells, channel 5.86 m), to 2.2 s",
               "runs": {"2d": "dimensions 2 (one cell across W, no side walls)",
                        "3d": "dimensions 3 (20 cells across W = 0.6 m, no-slip side walls)"},
               "paper_subcritical_after_arrival_s": PAPER_SUBCRITICAL["W"], **res}
    with open(os.path.join(out, "side_walls.json"), "w") as f:
        json.dump(summary, f, indent=2)
        f.write("\n")
    print(json.dumps(res))


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--calibrate", nargs=2, metavar=("CASE", "T"))
    p.add_argument("--make", nargs=2, metavar=("WORK", "OUT"))
    p.add_argument("--side-walls", nargs=2, metavar=("WORK", "OUT"))
    p.add_argument("--channel-length", type=float)
    p.add_argument("--command", default="scripts/liquid_results.sh")
    a = p.parse_args()
    if a.calibrate:
        calibrate(a.calibrate[0], float(a.calibrate[1]))
    elif a.make:
        make(a.make[0], a.make[1], a.channel_length, a.command)
    elif a.side_walls:
        side_walls(a.side_walls[0], a.side_walls[1], a.command)
    else:
        p.error("give --calibrate, --make or --side-walls")


if __name__ == "__main__":
    main()
