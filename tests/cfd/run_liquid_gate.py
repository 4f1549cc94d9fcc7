#!/usr/bin/env python3
"""The gate of a liquid scene (sceneProperties `gate`): removed at once, or lifted as a plate
(mixflowFoam's fvOption liquidGate, cfd/fvOptions/liquidGate.H). Cases are written as a user
writes them (constant/sceneProperties, system/cfdDict, system/controlDict), run through
mixflowPrepare, blockMesh and mixflowFoam, and judged from postProcessing/liquid/timeSeries.csv
and the written fields.

Scene of every scenario: a 2-D water column L = H = 0.1 m (rho 1000 kg/m3, mu 1e-3 Pa s,
sigma 0.07 N/m) in a channel 0.5 x 0.15 m, 5 mm cells (H/20), so the plate (auto: two cells)
spans 0.1 <= x < 0.11 m.

  instant   `gate { removal instant; }` against the same scene without the block, to 0.3 s:
            timeSeries.csv and the fields written at 0.3 s byte-identical (the default is the
            paper's removal, and the block must change nothing), and no constant/fvOptions; a
            case prepared lifted and then instant has its generated fvOptions removed.
  held      A plate that never lifts (`speed 0`, and `lift ((0 0) (1 0))`) holds the column for
            0.2 s. Pass: the liquid volume beyond the plate (cell centres x >= 0.11 m) at 0.2 s
            below 1e-3 of the column's (measured 2e-22), and the liquid's kinetic energy below
            1e-4 of the column's initial potential energy E_p0 = rho g H^2 L W / 2 at every step,
            i.e. an rms speed below 1 % of sqrt(g H) (measured 4.5e-6; the free column has
            0.17 E_p0 at 0.2 s).
  delay     A lifted gate (h = v t, v = 1 and 0.5 m/s) against the instant one, to 0.35 s.
            Expectation: let t_i(x), t_l(x) be the first times the bed front (front_bed_m)
            reaches x. (1) Until the lower edge passes the first cell centre (h = dy/2, at
            t0 = dy / (2 v)) every plate cell is held, so nothing leaves the column; afterwards
            the plate only removes momentum, so the lifted flow cannot catch up:
            t_l(x) - t_i(x) >= t0. (2) At T_lift = H / v the edge clears the column and the plate
            no longer acts; by then liquid has already left under it with the momentum it
            gained, so the lifted flow is at least as far as an instant release started at
            T_lift: t_l(x) - t_i(x) <= T_lift. Pass: both bounds at every x from L + 2 cells to
            the last x both fronts reach (every 5 mm), and the slower gate's delay larger than the
            faster one's at each x (a gate that does nothing fails (1) and this).
  bad-input Broken gate entries stop `mixflowPrepare -check` (exit 2) naming the file, the entry
            and the allowed range or words.

Exit status 0 = pass, 1 = fail.
"""

import argparse
import filecmp
import os
import re
import subprocess
import sys

sys.dont_write_bytecode = True  # keep the source tree free of __pycache__
from mixflow import foamcase as fc  # noqa: E402
from mixflow.liquidcase import run_case, write_case  # noqa: E402
from mixflow.paper import G  # noqa: E402

L, H, W, CELL = 0.1, 0.1, 0.1, 0.005
PLATE_END = L + 2 * CELL  # the plate's default thickness: two cells
RHO = 1000.0


def scene(gate="", channel=0.5):
    return (f"content liquid;\nsample {{ length {L}; height {H}; width {W}; }}\n"
            f"channel {{ length {channel}; height 0.15; }}\n"
            "liquid { rheology Newtonian; density 1000; viscosity 0.001; surfaceTension 0.07; }\n"
            + (f"gate {{ {gate} }}\n" if gate else ""))


CFD = f"dimensions 2;\ncellSize {CELL};\n"


def check(cond, msg):
    print(("  ok   " if cond else "  FAIL ") + msg, flush=True)
    return cond


def run(a, work, name, gate, end, write, channel=0.5):
    case = os.path.join(work, name)
    write_case(case, scene(gate, channel), CFD, end, write)
    return case, run_case(a, case)


def instant(a, work):
    ok = True
    c0, s0 = run(a, work, "no_block", "", 0.3, 0.3)
    c1, s1 = run(a, work, "instant", "removal instant;", 0.3, 0.3)
    ok &= check(not os.path.exists(os.path.join(c1, "constant/fvOptions")),
                "removal instant: no constant/fvOptions written")
    same = filecmp.cmp(os.path.join(c0, "postProcessing/liquid/timeSeries.csv"),
                       os.path.join(c1, "postProcessing/liquid/timeSeries.csv"), shallow=False)
    ok &= check(same and len(s0) > 10,
                f"timeSeries.csv byte-identical with and without the block ({len(s0)} rows)")
    for f in ("alpha.liquid", "U", "p_rgh"):
        same = filecmp.cmp(os.path.join(c0, "0.3", f), os.path.join(c1, "0.3", f), shallow=False)
        ok &= check(same, f"0.3/{f} byte-identical")
    # A case prepared lifted, then instant: the generated fvOptions must not survive.
    case = os.path.join(work, "lifted_then_instant")
    write_case(case, scene("removal lifted; speed 1;"), CFD, 0.3, 0.3)
    fc.run([a.prepare, "-case", case], case, "log.mixflowPrepare.lifted")
    had = os.path.exists(os.path.join(case, "constant/fvOptions"))
    with open(os.path.join(case, "constant/sceneProperties"), "w") as f:
        f.write(fc.foam_header("dictionary", "sceneProperties") + scene("removal instant;"))
    fc.run([a.prepare, "-case", case], case, "log.mixflowPrepare")
    ok &= check(had and not os.path.exists(os.path.join(case, "constant/fvOptions")),
                "lifted then instant: the generated constant/fvOptions is removed")
    return ok


def liquid_beyond(case, time, x):
    """Liquid volume (m3, 2-D slab of width W) in the cells whose centres lie at >= x."""
    centres = fc.cell_centres(case)
    alpha = fc.read_internal_field(os.path.join(case, time, "alpha.liquid"), len(centres))
    return sum(al for al, c in zip(alpha, centres) if c[0] >= x) * CELL * CELL * W


def held(a, work):
    ok = True
    v0 = L * H * W
    ep0 = RHO * G * H * H * L * W / 2
    for name, gate in (("speed_0", "removal lifted; speed 0;"),
                       ("table_0", "removal lifted; lift ((0 0) (1 0));")):
        case, s = run(a, work, name, gate, 0.2, 0.2)
        beyond = liquid_beyond(case, "0.2", PLATE_END)
        ok &= check(beyond < 1e-3 * v0,
                    f"{name}: liquid beyond the plate at 0.2 s {beyond / v0:.2e} of the column "
                    "(allowed < 1e-3)")
        ek = max(r["kinetic_energy_J"] for r in s)
        ok &= check(ek < 1e-4 * ep0, f"{name}: max kinetic energy {ek / ep0:.2e} E_p0 "
                    "(allowed < 1e-4, rms speed < 1 % of sqrt(g H))")
        ok &= check(abs(s[-1]["time_s"] - 0.2) < 1e-9, f"{name}: ran to 0.2 s")
    return ok


def first_time(series, x):
    """First time (linear between rows) at which front_bed_m reaches x; None if never."""
    for r0, r1 in zip(series, series[1:]):
        if r1["front_bed_m"] >= x:
            if r0["front_bed_m"] >= x:
                return r0["time_s"]
            w = (x - r0["front_bed_m"]) / (r1["front_bed_m"] - r0["front_bed_m"])
            return r0["time_s"] + w * (r1["time_s"] - r0["time_s"])
    return None


def at(series, key, t):
    for r0, r1 in zip(series, series[1:]):
        if r0["time_s"] <= t <= r1["time_s"]:
            w = (t - r0["time_s"]) / (r1["time_s"] - r0["time_s"])
            return (1 - w) * r0[key] + w * r1[key]
    fc.fail(f"time {t} outside the series")


def momentum(series, t):
    """Horizontal liquid momentum rho V <u_x> (kg m/s) at t."""
    return RHO * at(series, "volume_domain_m3", t) * at(series, "mean_ux_m_s", t)


def delay(a, work):
    ok = True
    end = 0.45
    _, si = run(a, work, "instant", "", end, end, channel=0.8)
    lag_common = {}
    for v in (1.0, 0.5):
        _, sl = run(a, work, f"lifted_{v:g}", f"removal lifted; speed {v:g};", end, end,
                    channel=0.8)
        tlift = H / v
        # (1) Impulse: up to T_lift the plate pushes back on the liquid with at most the
        # hydrostatic force of the column at rest on its wetted part, rho g W (H - v t)^2 / 2
        # (draining lowers the pressure there), so the momentum deficit against the instant
        # release lies in (0, rho g W (H^3 - (H - v t)^3) / (6 v)].
        worst = 0.0
        positive = True
        for k in range(1, 11):
            t = k * tlift / 10
            deficit = momentum(si, t) - momentum(sl, t)
            bound = RHO * G * W * (H ** 3 - (H - v * t) ** 3) / (6 * v)
            positive &= deficit > 0
            worst = max(worst, deficit / bound)
        ok &= check(positive and worst <= 1.0,
                    f"v = {v:g} m/s: momentum deficit for t <= T_lift = {tlift:g} s positive and "
                    f"at most {worst:.2f} of the hydrostatic plate's impulse (allowed (0, 1])")
        # (2) Front: at the fixed time 2 T_lift (the edge cleared the column T_lift ago) the
        # lifted front is behind, by a time lag tau = t - t_i(x_l(t)) in (0, T_lift]: positive
        # because of the lost impulse, at most T_lift because by T_lift liquid has already left
        # under the plate with the momentum it gained, so the lifted flow is at least as far as
        # an instant release started at T_lift.
        t = 2 * tlift
        xi, xl = at(si, "front_bed_m", t), at(sl, "front_bed_m", t)
        tau = t - first_time(si, xl)
        ok &= check(xl < xi and 0 < tau <= tlift,
                    f"v = {v:g} m/s: at t = {t:g} s front {xl:.4f} m behind the instant "
                    f"{xi:.4f} m, time lag {tau:.4f} s = {tau / tlift:.3f} T_lift (allowed (0, 1])")
        lag_common[v] = end - 0.05 - first_time(si, at(sl, "front_bed_m", end - 0.05))
    # (3) The slower gate loses more impulse: its front lags more at a common time after both
    # gates cleared.
    ok &= check(lag_common[0.5] > lag_common[1.0] > 0,
                f"at t = {end - 0.05:g} s the lag of the 0.5 m/s gate {lag_common[0.5]:.4f} s "
                f"exceeds the 1 m/s gate's {lag_common[1.0]:.4f} s")
    return ok


def bad_input(a, work):
    ok = True
    bad = [
        ("lifted without a law", "removal lifted;", ["gate.speed", "missing", "[0, inf)"]),
        ("speed and lift", "removal lifted; speed 1; lift ((0 0) (1 1));",
         ["gate.lift", "not both"]),
        ("speed with instant", "removal instant; speed 1;",
         ["gate.speed", "not a parameter of removal instant"]),
        ("negative speed", "removal lifted; speed -1;", ["gate.speed", "[0, inf)"]),
        ("speed in mm/s", "removal lifted; speed 4530;", ["gate.speed", "plausible", "mm/s"]),
        ("odd table", "removal lifted; lift ((0 0) (0.1));", ["gate.lift", "(t h) pairs"]),
        ("times not increasing", "removal lifted; lift ((0.1 0) (0.1 1));",
         ["gate.lift", "must increase"]),
        ("negative height", "removal lifted; lift ((0 0) (0.1 -1));", ["gate.lift", "[0, inf)"]),
        ("one-cell plate", "removal lifted; speed 1; thickness 0.005;",
         ["gate.thickness", "two cells", "[0.01, 0.4)"]),
        ("plate past the outlet", "removal lifted; speed 1; thickness 0.5;",
         ["gate.thickness", "[0.01, 0.4)"]),
        ("unknown removal", "removal opened;", ["gate.removal", "instant, lifted"]),
        ("misspelt entry", "removal lifted; speed 1; thicknes 0.01;",
         ["gate.thicknes", "unknown entry", "removal, speed, lift, thickness"]),
    ]
    for name, gate, expected in bad:
        case = os.path.join(work, "bad_" + re.sub(r"\W+", "_", name))
        write_case(case, scene(gate), CFD, 0.3, 0.3)
        ok &= refused(a.prepare, case, name, ["constant/sceneProperties"] + expected)
    case = os.path.join(work, "valid_table")
    write_case(case, scene("removal lifted; lift ((0 0) (0.05 0.02) (0.1 0.2)); thickness 0.02;"),
               CFD, 0.3, 0.3)
    res = subprocess.run([a.prepare, "-case", case, "-check"], capture_output=True, text=True)
    ok &= check(res.returncode == 0 and "gate lifted" in res.stdout,
                "a valid table with a 4-cell plate is accepted")
    return ok


def refused(prepare, case, name, expected):
    """mixflowPrepare -check refuses CASE with exit 2 and a message holding every fragment."""
    res = subprocess.run([prepare, "-case", case, "-check"], capture_output=True, text=True)
    msg = res.stdout + res.stderr
    missing = [f for f in expected if f not in msg]
    last = msg.strip().splitlines()[-1] if msg.strip() else ""
    good = res.returncode == 2 and not missing
    ok = check(good, f"{name}: exit {res.returncode}; {last}")
    if not good:
        print(f"       expected exit 2 with fragments {missing}")
    return ok


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--scenario", required=True, choices=["instant", "held", "delay", "bad-input"])
    p.add_argument("--prepare", required=True)
    p.add_argument("--solver")
    p.add_argument("--blockmesh", default="blockMesh")
    p.add_argument("--workdir", required=True)
    a = p.parse_args()
    work = os.path.join(os.path.abspath(a.workdir), a.scenario)
    os.makedirs(work, exist_ok=True)
    if a.scenario != "bad-input":
        fc.require_foam_env()
    print(f"scenario {a.scenario}", flush=True)
    fn = {"instant": instant, "held": held, "delay": delay, "bad-input": bad_input}[a.scenario]
    ok = fn(a, work)
    print("PASS" if ok else "FAIL", flush=True)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
