"""Serial against parallel mixture runs: the collapse's own sensitivity or a parallel defect?

usage: mixflow reproducibility [--scenes W+P,HB+P] [--ranks 2]
                                          [--work runs/reproducibility] [--out results/reproducibility]

Each scene is cases/W+P-quick (813 grains, 2-D fluid, 1.5 s) with that scene's liquid block
(W+P: water; HB+P: the paper's Herschel-Bulkley liquid, a creeping column). Runs, all from the
settled sample of the first:
  serial      ./Allrun 1 (settles; the reference)
  repeat      ./Allrun 1 again: must be identical (determinism)
  perturbed   ./Allrun 1 with the liquid density times (1 + 1e-12): a round-off-sized change
  ranks       ./Allrun RANKS with LIGGGHTS' equal slabs matched to the fluid's (demDict
              balanceInterval 0, processors "* * *")
  balanced    ./Allrun RANKS with the default decomposition: the DEM's x slabs re-balanced by
              particles every 0.05 s, apart from the fluid's slabs
Compared with the serial run at every common output time: the granular front (postProcessing/dem
front_x_m), the grains' translational kinetic energy, the liquid front (postProcessing/liquid
front_bed_m): the largest difference over the run, and at the end, absolute and relative to the
serial run's value there. If the ranks run differs from serial by about what the perturbed run
does, the difference is the collapse's amplification of round-off (the order of floating-point
sums changes with the decomposition), not a defect; that spread is the tolerance to expect.
Writes OUT/summary.json and OUT/differences.csv.
"""

import argparse
import csv
import os
import shutil
import subprocess
import sys

from mixflow import ROOT, foamcase, foamdict, outputs

PERTURBATION = 1e-12
QUANTITIES = {"granular_front_m": ("dem", "front_x_m"),
              "grain_ke_J": ("dem", "ke_translational_J"),
              "liquid_front_m": ("liquid", "front_bed_m")}


EQUAL_SLABS = {"balanceInterval": "0", "processors": '"* * *"'}


def make_case(work, scene, label, density_factor=1.0, dem=None):
    """cases/W+P-quick's inputs with SCENE's liquid block in WORK/SCENE/LABEL (DEM: demDict
    entries to set)."""
    d = os.path.join(work, scene, label)
    shutil.rmtree(d, ignore_errors=True)
    outputs.copy_inputs(os.path.join(ROOT, "cases", "W+P-quick"), d)
    sp = os.path.join(d, "constant", "sceneProperties")
    text = open(sp).read()
    liquid = open(os.path.join(ROOT, "cases", scene, "constant", "sceneProperties")).read()
    text = text[:text.index("liquid   //")] + liquid[liquid.index("liquid   //"):]
    if density_factor != 1.0:
        rho = float(foamdict.parse_dict(text)["liquid"]["density"])
        text, _ = foamdict.edit_dict(text, {"liquid": {"density": repr(rho * density_factor)}},
                                  note="round-off perturbation (mixflow reproducibility)")
    open(sp, "w").write(text)
    if dem:
        foamdict.edit_file(os.path.join(d, "system", "demDict"), dem,
                           note="mixflow reproducibility")
    return d


def allrun(case, ranks, settled=None):
    env = foamcase.run_env()
    cmd = ["./Allrun", str(ranks)] + ([settled] if settled else [])
    print(f"+ (cd {case} && {' '.join(cmd)})", flush=True)
    with open(os.path.join(case, "log.reproducibility"), "w") as log:
        r = subprocess.run(cmd, cwd=case, env=env, stdout=log, stderr=subprocess.STDOUT)
    if r.returncode != 0:
        sys.exit(f"reproducibility: {case}: Allrun failed (log.reproducibility)")


def series(case, which, column):
    path = os.path.join(case, outputs.SERIES[which])
    with open(path) as f:
        rows = list(csv.DictReader(ln for ln in f if ln.strip() and not ln.startswith("#")))
    return {round(float(r["time_s"]), 6): float(r[column]) for r in rows}


def compare(ref, other):
    """Largest |difference| over the common times, and at the last common time (abs, rel)."""
    out = {}
    for q, (which, column) in QUANTITIES.items():
        a, b = series(ref, which, column), series(other, which, column)
        times = sorted(set(a) & set(b))
        diffs = [abs(a[t] - b[t]) for t in times]
        end = times[-1]
        scale = abs(a[end]) or 1.0
        out[q] = {"max_abs": max(diffs), "end_abs": abs(a[end] - b[end]),
                  "end_rel": abs(a[end] - b[end]) / scale, "end_time_s": end,
                  "serial_end": a[end], "times": len(times)}
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scenes", default="W+P,HB+P")
    ap.add_argument("--ranks", type=int, default=2)
    ap.add_argument("--work", default=os.path.join(ROOT, "runs", "reproducibility"))
    ap.add_argument("--out", default=os.path.join(ROOT, "results", "reproducibility"))
    a = ap.parse_args()
    summary = {"command": "mixflow reproducibility " + " ".join(sys.argv[1:]),
               "perturbation": f"liquid density x (1 + {PERTURBATION:g})", "ranks": a.ranks,
               "scenes": {}}
    rows = []
    for scene in a.scenes.split(","):
        serial = make_case(a.work, scene, "serial")
        allrun(serial, 1)
        settled = os.path.join(serial, "dem")
        runs = {"repeat": (make_case(a.work, scene, "repeat"), 1),
                "perturbed": (make_case(a.work, scene, "perturbed", 1 + PERTURBATION), 1),
                f"ranks{a.ranks}": (make_case(a.work, scene, f"ranks{a.ranks}",
                                              dem=EQUAL_SLABS), a.ranks),
                f"balanced{a.ranks}": (make_case(a.work, scene, f"balanced{a.ranks}"), a.ranks)}
        summary["scenes"][scene] = {}
        for label, (case, ranks) in runs.items():
            allrun(case, ranks, settled)
            diff = compare(serial, case)
            summary["scenes"][scene][label] = diff
            for q, v in diff.items():
                rows.append({"scene": scene, "run": label, "quantity": q, **{
                    k: v[k] for k in ("max_abs", "end_abs", "end_rel", "serial_end")}})
                print(f"{scene} {label:10s} {q:17s} max |diff| {v['max_abs']:.3g}, at "
                      f"{v['end_time_s']:g} s {v['end_abs']:.3g} ({100 * v['end_rel']:.3g} % of "
                      f"{v['serial_end']:.4g})", flush=True)
    outputs.write_json(os.path.join(a.out, "summary.json"), summary)
    outputs.write_csv(os.path.join(a.out, "differences.csv"), rows)
    print(f"wrote {a.out}/summary.json, differences.csv")


if __name__ == "__main__":
    main()
