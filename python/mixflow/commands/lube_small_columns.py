"""Lube et al.'s (2005) small-a claims measured on the paper's grains: small dry columns of
several aspect ratios in a wide (periodic) channel, run until they arrest.

usage: mixflow lube-small-columns [--lengths 0.15,0.3] [--aspects 0.5,0.75,1,1.5]
          [--work runs/lube_small_columns] [--out results/runout_scaling/lube_small_columns.json]

Each column is tests/collapse/column's (paper material, 1.2 cm beads, a periodic 5 d slab: no side
walls) with length L and height a L; the channel is (2 + 2 a) L long (Lube: the front advances
1.2 a L for a < 1.8) and 1.5 a L + 0.1 m high. With a = H0 / L from the settled height H0 and the
front's advance l_inf - L (cluster front): per column (l_inf - L) / L against Lube's 1.2 a, and the
summit (the deposit's highest point) against H0 (Lube: intact, H_inf = H0, for a < 1.8); per
length the least-squares fit (l_inf - L) / L = lambda a^alpha over the columns whose summit stayed
within 10 % of H0 (Lube's regime), against the experiments' wide-channel band alpha = 0.9 +- 0.1.
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys

from mixflow import ROOT, outputs
from mixflow.runout import fit_power_law
COLUMN = os.path.join(ROOT, "tests", "collapse", "column")
D = 0.012


def run(exe, work, L, a):
    d = os.path.join(work, f"L{L:g}-a{a:g}")
    shutil.rmtree(d, ignore_errors=True)
    shutil.copytree(COLUMN, d)
    sp = os.path.join(d, "constant", "sceneProperties")
    text = re.sub(r"sample\s*\{[^}]*\}", f"sample  {{ length {L}; height {a * L!r}; width 0.06; "
                  "solidFraction 0.6056; }", open(sp).read())
    # Room for the runout (Lube: 1.2 a L beyond the column) and above the column.
    text = re.sub(r"channel\s*\{[^}]*\}", f"channel {{ length {L * (2 + 2 * a)!r}; height "
                  f"{1.5 * a * L + 0.1!r}; sideWalls periodic; }}", text)
    open(sp, "w").write(text)
    cd = os.path.join(d, "system", "controlDict")
    open(cd, "w").write("FoamFile { version 2.0; format ascii; class dictionary; object "
                        "controlDict; }\nendTime 3;\nwriteInterval 1;\n")
    r = subprocess.run([exe, "-case", d], capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"mixflowDem failed on a = {a}:\n{r.stdout[-2000:]}{r.stderr[-2000:]}")
    s = json.load(open(os.path.join(d, "postProcessing", "dem", "summary.json")))
    with open(os.path.join(d, "postProcessing", "dem", "depositProfile.csv")) as f:
        rows = [ln.strip().split(",") for ln in f if ln.strip() and not ln.startswith("#")]
    k = rows[0].index("h_top_m")
    s["summit_m"] = max(float(r[k]) for r in rows[1:])
    return s


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--lengths", default="0.15,0.3")
    ap.add_argument("--aspects", default="0.5,0.75,1,1.5")
    ap.add_argument("--work", default=os.path.join(ROOT, "runs", "lube_small_columns"))
    ap.add_argument("--out", default=os.path.join(ROOT, "results", "runout_scaling",
                                                  "lube_small_columns.json"))
    ap.add_argument("--exe", default=os.path.join(
        os.environ.get("MIXFLOW_BUILD", os.path.join(ROOT, "build")), "bin", "mixflowDem"))
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    out = {"command": "mixflow lube-small-columns " + " ".join(sys.argv[1:]),
           "lube_2005": {"lambda": 1.2, "alpha": 1.0, "summit_intact_below_a": 1.8},
           "alpha_band": [0.8, 1.0], "lengths": {}}
    for L in (float(v) for v in a.lengths.split(",")):
        cols, pts = [], []
        for asp in (float(v) for v in a.aspects.split(",")):
            s = run(a.exe, a.work, L, asp)
            h0 = s["settled"]["height_m"]
            c = {"aspect_ratio": h0 / L, "settled_height_m": h0, "particles": s["settled"]["particles"],
                 "advance_over_L": s["runout_m"] / L, "lube_advance_over_L": 1.2 * h0 / L,
                 "summit_m": s["summit_m"], "summit_over_H0": s["summit_m"] / h0,
                 "stop_reason": s["stop_reason"]}
            c["summit_intact"] = abs(c["summit_over_H0"] - 1) <= 0.1
            cols.append(c)
            if c["summit_intact"]:
                pts.append((c["aspect_ratio"], c["advance_over_L"]))
            print(f"L {L:g} m, a = {c['aspect_ratio']:.3f}: (l - L)/L = {c['advance_over_L']:.3f} "
                  f"(Lube {c['lube_advance_over_L']:.3f}), summit / H0 = {c['summit_over_H0']:.3f}, "
                  f"{s['particles_remaining']} grains, {c['stop_reason']}", flush=True)
        rec = {"columns": cols}
        if len(pts) >= 2:
            rec["alpha"], rec["lambda"] = fit_power_law(*zip(*pts))
            rec["alpha_in_band"] = 0.8 <= rec["alpha"] <= 1.0
            print(f"L {L:g} m: alpha {rec['alpha']:.3f}, lambda {rec['lambda']:.3f} over the "
                  f"{len(pts)} columns with an intact summit", flush=True)
        out["lengths"][f"{L:g}"] = rec
    outputs.write_json(a.out, out)
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
