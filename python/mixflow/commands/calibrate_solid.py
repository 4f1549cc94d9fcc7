"""The bulk model's solid rheology calibrated on the dry collapse P (docs/calibration.md): a grid of
the yield coefficient tanPhi and the solid viscosity nu_s, each run as cases/P-bulk (the column of
P with air as its pore fluid), scored by the granular front and the final deposit against the DEM
run of P.

usage: mixflow calibrate-solid REFERENCE [--tan-phi 0.3,0.35,...]
           [--viscosity 0.003,...,0.1] [--cell-size 0.075] [--times 0.25:3:0.25]
           [--score front|front+deposit] [--work runs/solid-calibration] [--target CASE ...]
           [--out FILE.json]

REFERENCE: a finished DEM case of P (its postProcessing/dem/timeSeries.csv, column front_x_m; a
run that stopped at arrest keeps its last front; and its postProcessing/dem/depositProfile.csv,
column h_volume_m, for the deposit). Each grid point is the tier `bulk` case P-bulk at
--cell-size (`suite.py --tier bulk --scenes P-bulk --set cfdDict.cellSize=...`, once) with
`solid { tanPhi; viscosity; }` set in its constant/bulkProperties and run with ./Allrun. Two
errors per point: the front error, the root mean square of the relative front error at --times;
the deposit error, the relative L1 difference sum |h - h_dem| / sum h_dem of the bulk mixture's
height (postProcessing/liquid/profiles.csv depth_m at the write nearest the last of --times) and
the DEM deposit's volume depth averaged over each bulk cell column (deposit_columns). --score
picks the point: `front` (default) the front error alone, `front+deposit` the root of the sum of
both squared; the deposit error is reported with either when REFERENCE has a deposit, and
`front+deposit` refuses a REFERENCE without one. Writes OUT (JSON) and OUT with .csv (one row a
grid point); with --target, the best point's solid.tanPhi and solid.viscosity go into each
CASE/constant/bulkProperties (created if absent; nothing else changes). `--rheology muI` scores
instead one run with the mu(I) law at its defaults (`solid { rheology muI; }`, the Coulomb entries
removed; OUT default results/bulk_model/solid_mui_P.json), without --target. OUT's `best` is the
best point by --score, `best_by_score` the best by each score REFERENCE allows. Bad input exits 2
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
SCORES = {"front": "rms of front_bulk / front_dem - 1 over times_s",
          "front+deposit": "sqrt(rms_error^2 + deposit_error^2), deposit_error the relative L1 "
                           "difference of the final h(x)"}


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


def reference_deposit(case, required):
    """The DEM deposit's rows (outputs.deposit), None without the file unless REQUIRED."""
    path = os.path.join(case, outputs.DEPOSIT)
    if not os.path.isfile(path):
        if required:
            raise InputError(f"{path}: no such file (--score front+deposit needs the DEM run's "
                             f"final deposit; allowed without it: --score front)")
        return None
    rows = outputs.deposit(case)
    if len(rows) < 2 or outputs.DEPOSIT_VOLUME not in rows[0]:
        raise InputError(f"{path}: fewer than 2 rows with column {outputs.DEPOSIT_VOLUME}")
    return rows


def deposit_columns(x, h, centres):
    """H, given on bins of equal width centred at X, averaged over the cell columns of equal width
    centred at CENTRES by the length each bin shares with each column (zero outside the bins):
    a volume depth keeps its area sum(h dx)."""
    bx, cx = x[1] - x[0], centres[1] - centres[0]
    out = []
    for c in centres:
        lo, hi = c - cx / 2, c + cx / 2
        out.append(sum(hv * max(0.0, min(hi, xv + bx / 2) - max(lo, xv - bx / 2))
                       for xv, hv in zip(x, h)) / cx)
    return out


def deposit_error(case, ref_rows, t):
    """CASE's mixture height at the write nearest T against the DEM deposit REF_ROWS on CASE's
    cell columns: {time_s, error (sum |h - h_dem| / sum h_dem), back_wall_m and max_m of each}."""
    rows = outputs.profile_at(case, t)
    x = [r[outputs.PROFILE_X] for r in rows]
    h = [r[outputs.PROFILE_DEPTH] for r in rows]
    h_dem = deposit_columns([r[outputs.PROFILE_X] for r in ref_rows],
                            [r[outputs.DEPOSIT_VOLUME] for r in ref_rows], x)
    return {"time_s": rows[0][outputs.TIME],
            "error": sum(abs(a - b) for a, b in zip(h, h_dem)) / sum(h_dem),
            "back_wall_m": h[0], "max_m": max(h), "dem_back_wall_m": h_dem[0],
            "dem_max_m": max(h_dem), "x_m": x, "h_m": h, "dem_h_m": h_dem}


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


def combined(rec, how):
    """The score HOW (a key of SCORES) of a grid point's record."""
    if how == "front":
        return rec["rms_error"]
    return math.hypot(rec["rms_error"], rec["deposit_error"])


def score(case, ref, times, ref_deposit, how):
    """CASE's front errors at TIMES against REF, its deposit error against REF_DEPOSIT (None:
    not scored) and the score HOW ranks it by."""
    rows = outputs.series(case)
    end = rows[-1][outputs.TIME]
    fronts = {t: outputs.interpolated(rows, outputs.LIQUID_FRONT, min(t, end)) for t in times}
    errors = [fronts[t] / ref[t] - 1 for t in times]
    rms = math.sqrt(sum(e * e for e in errors) / len(errors))
    dep = deposit_error(case, ref_deposit, times[-1]) if ref_deposit else None
    rec = {"fronts_m": [fronts[t] for t in times], "errors": errors, "rms_error": rms,
           "final_error": errors[-1], "deposit_error": dep and dep["error"],
           "deposit_time_s": dep and dep["time_s"], "back_wall_m": dep and dep["back_wall_m"],
           "deposit_max_m": dep and dep["max_m"],
           "solver_cpu_s": foamcase.execution_time(os.path.join(case, "log.mixflowBulkFoam"))}
    rec["score"] = combined(rec, how)
    return rec, dep


def summary(rec, how):
    """REC's errors and its score HOW (a key of SCORES)."""
    return dict({k: rec[k] for k in ("tan_phi", "viscosity_m2_s", "rms_error", "final_error",
                                     "deposit_error", "back_wall_m")}, score=combined(rec, how))


def fmt(v):
    return "" if v is None else f"{v:.4f}"


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("reference")
    ap.add_argument("--tan-phi", default="0.3,0.35,0.4,0.45,0.5,0.55,0.6,0.7,0.8,0.9")
    ap.add_argument("--viscosity", default="0.003,0.01,0.02,0.03,0.05,0.1")
    ap.add_argument("--cell-size", default="0.075")
    ap.add_argument("--times", default="0.25:3:0.25")
    ap.add_argument("--score", choices=tuple(SCORES), default="front")
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
        ref_deposit = reference_deposit(a.reference, a.score == "front+deposit")
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
    grid, dep = [], None
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
        rec, dep = score(case, ref, times, ref_deposit, a.score)
        rec = {"tan_phi": tp, "viscosity_m2_s": nu, **rec}
        grid.append(rec)
        label = "muI (defaults)" if mui else f"tanPhi {tp:g} nu_s {nu:g}"
        deposit = "" if dep is None else f", deposit error {100 * dep['error']:.1f} %"
        print(f"{label}: rms front error {100 * rec['rms_error']:.1f} %, "
              f"at {times[-1]:g} s {100 * rec['final_error']:+.1f} %{deposit}", flush=True)
    best = min(grid, key=lambda r: r["score"])
    out = {"command": "mixflow calibrate-solid " + " ".join(sys.argv[1:]),
           "reference": os.path.relpath(os.path.abspath(a.reference), ROOT), "reference_end_s": ref_end,
           "cell_size_m": cell, "times_s": times, "reference_front_m": [ref[t] for t in times],
           "reference_deposit": dep and {k: dep[k] for k in ("x_m", "dem_h_m", "dem_back_wall_m",
                                                             "dem_max_m")},
           "rheology": a.rheology, "score": a.score, "score_definition": SCORES[a.score],
           "deposit_error_definition": "sum |h_bulk - h_dem| / sum h_dem over the bulk cell "
                                       "columns, h_dem the DEM h_volume_m averaged over each",
           "best": summary(best, a.score),
           "best_by_score": {how: summary(min(grid, key=lambda r: combined(r, how)), how)
                             for how in SCORES if how == "front" or ref_deposit},
           "grid": grid}
    outputs.write_json(a.out, out)
    with open(os.path.splitext(a.out)[0] + ".csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["tan_phi", "viscosity_m2_s", "rms_error", "deposit_error", "score",
                    "back_wall_m", "solver_cpu_s"] + [f"front_m_t{t:g}" for t in times])
        w.writerow(["dem", "", "", "", "", "" if dep is None else f"{dep['dem_back_wall_m']:.4f}",
                    ""] + [f"{ref[t]:.4f}" for t in times])
        for r in grid:
            w.writerow([r["tan_phi"], r["viscosity_m2_s"], f"{r['rms_error']:.4f}",
                        fmt(r["deposit_error"]), f"{r['score']:.4f}", fmt(r["back_wall_m"]),
                        r["solver_cpu_s"]] + [f"{v:.4f}" for v in r["fronts_m"]])
    for t in a.target:
        set_solid(t, best["tan_phi"], best["viscosity_m2_s"])
    if mui:
        print(f"wrote {a.out}")
        return 0
    deposit = "" if dep is None else f", deposit error {100 * best['deposit_error']:.1f} %"
    print(f"best by {a.score}: tanPhi {best['tan_phi']:g}, nu_s {best['viscosity_m2_s']:g} m2/s, "
          f"rms front error {100 * best['rms_error']:.1f} %{deposit}; wrote {a.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
