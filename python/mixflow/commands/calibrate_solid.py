"""The bulk model's solid rheology calibrated on the dry collapse P (docs/calibration.md): a grid of
the yield coefficient tanPhi and the solid viscosity nu_s, each run as cases/P-bulk (the column of
P with air as its pore fluid), scored by the granular front against the DEM run of P.

usage: mixflow calibrate-solid REFERENCE [--tan-phi 0.3,0.35,...]
           [--viscosity 0.003,...,0.1] [--cell-size 0.075] [--times 0.25:3:0.25]
           [--work runs/solid-calibration] [--target CASE ...] [--out FILE.json]

REFERENCE: a finished DEM case of P (its postProcessing/dem/timeSeries.csv, column front_x_m; a
run that stopped at arrest keeps its last front). Each grid point is the tier `bulk` case P-bulk
at --cell-size (`suite.py --tier bulk --scenes P-bulk --set cfdDict.cellSize=...`, once) with
`solid { tanPhi; viscosity; }` set in its constant/bulkProperties and run with ./Allrun. Score: the
root mean square of the relative front error at --times. Writes OUT (JSON) and OUT with .csv (one
row a grid point); with --target, the best point's solid.tanPhi and solid.viscosity go into each
CASE/constant/bulkProperties (created if absent; nothing else changes). `--rheology muI` scores
instead one run with the mu(I) law at its defaults (`solid { rheology muI; }`, the Coulomb entries
removed; OUT default results/bulk_model/solid_mui_P.json), without --target. Bad input exits 2
before anything runs.
"""

import argparse
import csv
import math
import os
import sys

from mixflow.cli import command
from mixflow import ROOT, bulkprops, foamcase, foamdict, outputs

SCENE = "P-bulk"


class InputError(Exception):
    """Bad input: the message names the file or option, the entry and the allowed range."""


def numbers(text, option, low, high):
    try:
        vals = [float(v) for v in text.split(",") if v.strip()]
    except ValueError:
        raise InputError(f"{option} {text}: not a comma-separated list of numbers") from None
    bad = [v for v in vals if not low <= v <= high]
    if not vals or bad:
        raise InputError(f"{option} {text}: each value must lie in [{low}, {high}]")
    return vals


def time_list(text):
    try:
        t0, t1, dt = (float(v) for v in text.split(":"))
    except ValueError:
        raise InputError(f"--times {text}: not T0:T1:DT") from None
    if not (0 < t0 <= t1 and dt > 0):
        raise InputError(f"--times {text}: needs 0 < T0 <= T1 and DT > 0")
    return [round(t0 + i * dt, 10) for i in range(int(math.floor((t1 - t0) / dt + 1e-9)) + 1)]


def reference_front(case, times):
    """The DEM front at TIMES (held at its last value after the run's end)."""
    path = os.path.join(case, outputs.DEM_SERIES)
    if not os.path.isfile(path):
        raise InputError(f"{path}: no such file (REFERENCE is a finished DEM case of P)")
    rows = outputs.read_series(path, comments=True)
    if not rows or outputs.GRANULAR_FRONT not in rows[0]:
        raise InputError(f"{path}: no rows with column {outputs.GRANULAR_FRONT}")
    end = rows[-1][outputs.TIME]
    return {t: outputs.interpolated(rows, outputs.GRANULAR_FRONT, min(t, end)) for t in times}, end


def run(cmd, cwd=None):
    foamcase.run_tool(cmd, "calibrate_solid", cwd)


def solid_entries(tan_phi, viscosity):
    return {"tanPhi": f"{tan_phi:g}", "viscosity": f"{viscosity:g}"}


def solid_text(case, tan_phi, viscosity):
    """CASE's constant/bulkProperties (path, text) with solid.tanPhi and solid.viscosity set."""
    try:
        p = bulkprops.path(case)
        return p, bulkprops.block_text(p, "solid", solid_entries(tan_phi, viscosity))
    except bulkprops.DictError as e:
        raise InputError(f"{bulkprops.path(case)}: {e}") from None


def set_solid(case, tan_phi, viscosity):
    bulkprops.write_text(*solid_text(case, tan_phi, viscosity))


def set_mui(case):
    """CASE's solid block the mu(I) law at its defaults: the Coulomb law's entries, which muI
    refuses, removed; every other entry kept (comments are not)."""
    tree = {k: v for k, v in bulkprops.read(case).items() if k != "FoamFile"}
    solid = {k: v for k, v in tree.get("solid", {}).items()
             if k not in ("tanPhi", "viscosity", "cohesion")}
    tree["solid"] = dict(solid, rheology="muI")
    bulkprops.write_text(bulkprops.path(case), bulkprops.HEADER + foamdict.format_dict(tree))


def score(case, ref, times):
    rows = outputs.series(case)
    end = rows[-1][outputs.TIME]
    fronts = {t: outputs.interpolated(rows, outputs.LIQUID_FRONT, min(t, end)) for t in times}
    errors = [fronts[t] / ref[t] - 1 for t in times]
    return {"fronts_m": [fronts[t] for t in times], "errors": errors,
            "rms_error": math.sqrt(sum(e * e for e in errors) / len(errors)),
            "final_error": errors[-1],
            "solver_cpu_s": foamcase.execution_time(os.path.join(case, "log.mixflowBulkFoam"))}


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("reference")
    ap.add_argument("--tan-phi", default="0.3,0.35,0.4,0.45,0.5,0.55,0.6,0.7,0.8,0.9")
    ap.add_argument("--viscosity", default="0.003,0.01,0.02,0.03,0.05,0.1")
    ap.add_argument("--cell-size", default="0.075")
    ap.add_argument("--times", default="0.25:3:0.25")
    ap.add_argument("--work", default=os.path.join(ROOT, "runs", "solid-calibration"))
    ap.add_argument("--target", action="append", default=[])
    ap.add_argument("--rheology", choices=("coulombViscoplastic", "muI"),
                    default="coulombViscoplastic")
    ap.add_argument("--out")
    a = ap.parse_args()
    mui = a.rheology == "muI"
    a.out = a.out or os.path.join(ROOT, "results", "bulk_model",
                                  "solid_mui_P.json" if mui else "solid_calibration.json")
    try:
        if mui and a.target:
            raise InputError("--target with --rheology muI: the mu(I) run is scored, not "
                             "calibrated (allowed: --target with coulombViscoplastic)")
        tan_phis = numbers(a.tan_phi, "--tan-phi", 0, 5)  # bulkProperties solid.tanPhi's range
        viscosities = numbers(a.viscosity, "--viscosity", 1e-9, 1e3)
        cell = numbers(a.cell_size, "--cell-size", 1e-3, 0.3)[0]
        times = time_list(a.times)
        ref, ref_end = reference_front(a.reference, times)
        for t in a.target:
            if not os.path.isdir(os.path.join(t, "constant")):
                raise InputError(f"--target {t}: no constant/ directory (a case directory)")
            solid_text(t, 0.5, 0.01)  # an unreadable bulkProperties stops here, before any run
    except InputError as e:
        print(f"calibrate_solid: {e}", file=sys.stderr)
        return 2

    base = os.path.join(a.work, "base", SCENE)
    if not os.path.isfile(os.path.join(base, outputs.DONE)):
        run(command("suite") + ["--tier", "bulk",
             "--scenes", SCENE, "--work", os.path.dirname(base), "--set",
             f"cfdDict.cellSize={cell:g}"])
    grid = []
    points = [(None, None)] if mui else [(tp, nu) for tp in tan_phis for nu in viscosities]
    for tp, nu in points:
        case = os.path.join(a.work, "muI" if mui else f"tanPhi{tp:g}_nu{nu:g}")
        if not os.path.isfile(os.path.join(case, outputs.DONE)):
            if os.path.isdir(case):
                sys.exit(f"calibrate_solid: {case} exists unfinished: remove it to rerun")
            outputs.copy_inputs(base, case)
            if mui:
                set_mui(case)
            else:
                set_solid(case, tp, nu)
            run(["./Allrun", "1"], cwd=case)
            open(os.path.join(case, outputs.DONE), "w").close()
        rec = {"tan_phi": tp, "viscosity_m2_s": nu, **score(case, ref, times)}
        grid.append(rec)
        label = "muI (defaults)" if mui else f"tanPhi {tp:g} nu_s {nu:g}"
        print(f"{label}: rms front error {100 * rec['rms_error']:.1f} %, "
              f"at {times[-1]:g} s {100 * rec['final_error']:+.1f} %", flush=True)
    best = min(grid, key=lambda r: r["rms_error"])
    out = {"command": "mixflow calibrate-solid " + " ".join(sys.argv[1:]),
           "reference": os.path.relpath(os.path.abspath(a.reference), ROOT), "reference_end_s": ref_end,
           "cell_size_m": cell, "times_s": times, "reference_front_m": [ref[t] for t in times],
           "rheology": a.rheology, "score": "rms of front_bulk / front_dem - 1 over times_s",
           "best": {k: best[k] for k in ("tan_phi", "viscosity_m2_s", "rms_error", "final_error")},
           "grid": grid}
    outputs.write_json(a.out, out)
    with open(os.path.splitext(a.out)[0] + ".csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["tan_phi", "viscosity_m2_s", "rms_error", "solver_cpu_s"]
                   + [f"front_m_t{t:g}" for t in times])
        w.writerow(["dem", "", "", ""] + [f"{ref[t]:.4f}" for t in times])
        for r in grid:
            w.writerow([r["tan_phi"], r["viscosity_m2_s"], f"{r['rms_error']:.4f}",
                        r["solver_cpu_s"]] + [f"{v:.4f}" for v in r["fronts_m"]])
    for t in a.target:
        set_solid(t, best["tan_phi"], best["viscosity_m2_s"])
    if mui:
        print(f"wrote {a.out}")
        return 0
    print(f"best: tanPhi {best['tan_phi']:g}, nu_s {best['viscosity_m2_s']:g} m2/s, rms front "
          f"error {100 * best['rms_error']:.1f} %; wrote {a.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
