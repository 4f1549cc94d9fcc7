"""The drift coefficients a user takes to calibrate the quasi two-phase model: mixflowExtract on
finished mixture runs, and robust summaries of lambda_u, lambda_w and lambda_p (its density, raw
and kinematic conventions, mixture_extract/README.md) and of the pore pressure's split (the
pore-pressure ratio chi, the excess pore pressure, the effective stress p_s) over the flowing bins. Also written into the "lambdas"
entry of results/yield_stress/summary.json when that file exists.

usage: mixflow mixture-lambdas --work runs/reference [--scenes W+P,HB+P,B+P]
                                                   [--out results/yield_stress/lambdas.json]

For each scene WORK/<scene> (a finished suite run): system/extractDict is written (grid x 0 to 3 m
and y 0 to 0.72 m in the widest bins that are not narrower than the run's fluid cell, cfdDict
cellSize, as mixflowExtract requires: 0.075 m at the reference tier; windows of 0.1 s over the
run, fluid from OpenFOAM,
the liquid density from the scene), `mixflowExtract -case DIR -overwrite` runs, and from
postProcessing/mixture/mixture.h5:
  - the flowing bins: lambda valid (the extractor's masks) and alpha_s >= 0.1 and |u_s| >= 0.05 m/s
    (the grains move; where they rest the ratios are ill-conditioned);
  - median and 10 / 90 % quantiles of each lambda, of pore_pressure_ratio (chi, the bulk model's
    drifts.porePressureRatio), p_f_excess and p_s (sigma') over those bins and all windows, with
    the counts;
  - lambda_u and lambda_w also as the weighted least-squares slope of u_f on u_s over the same bins
    (weights alpha_s (1 - alpha_s) times the bin's particle samples): a ratio of sums, which small
    |u_s| cannot blow up;
  - the basal pore pressure under the initial column against hydrostatic (the extractor's
    p_f_excess and p_f_hydrostatic), per window up to 1 s (basal_pore_pressure).
load() (the file's arrays) and wls_slope() are shared with mixflow calibrate-drifts, bin_counts()
and run_extract() with mixflow calibrate.
Each scene's entry also names the run's --set entries (tier_set); drifts_error() compares two
runs' drifts (mixflow mixture-results, lambda_convergence/).
Needs numpy and h5py (Debian's python3-numpy, python3-h5py; hence /usr/bin/python3).
"""

import argparse
import json
import os
import subprocess
import sys

import h5py
import numpy as np

from mixflow import ROOT
from mixflow import observables as obs
from mixflow.foamdict import read_dict
LABEL = {"W+P": "W&P", "HB+P": "HB&P", "B+P": "B&P"}


X_RANGE, Y_RANGE = 3.0, 0.72  # m, from the channel's origin


def bin_counts(run_dir, x_range=X_RANGE, y_range=Y_RANGE):
    """Bins over X_RANGE and Y_RANGE no narrower than the run's fluid cell: the channel cut into
    round(length / cellSize) cells as mixflowPrepare cuts it (cfdDict cellSize, auto H / 20),
    the cell mixflowExtract checks the bins against."""
    cfd = read_dict(os.path.join(run_dir, "system", "cfdDict"))
    scene = read_dict(os.path.join(run_dir, "constant", "sceneProperties"))
    size = cfd.get("cellSize", "auto").split()[0]
    h = float(scene["sample"]["height"]) / 20 if size == "auto" else float(size)
    counts = []
    for span, extent in ((x_range, scene["channel"]["length"]), (y_range, scene["channel"]["height"])):
        extent = float(extent)
        cell = extent / max(1, int(extent / h + 0.5))  # lround, as mixflowPrepare
        counts.append(max(1, int(span / cell * (1 + 1e-9))))
    return tuple(counts)


def y_range(run_dir):
    """Y_RANGE, or up to 0.12 m above a tank's liquid (channel liquidDepth): the pore pressure
    against hydrostatic needs the liquid surface inside the grid."""
    scene = read_dict(os.path.join(run_dir, "constant", "sceneProperties"))
    depth = float(scene["channel"].get("liquidDepth", "0").split()[0])
    return max(Y_RANGE, depth + 0.12)


def extract(run_dir, build):
    top = y_range(run_dir)
    nx, ny = bin_counts(run_dir, y_range=top)
    with open(os.path.join(run_dir, "system", "extractDict"), "w") as f:
        f.write("FoamFile { version 2.0; format ascii; class dictionary; object extractDict; }\n"
                "// written by mixflow mixture-lambdas\n"
                f"grid {{ x (0 {X_RANGE!r} {nx}); y (0 {top!r} {ny}); }}\n"
                "windows { start 0; width 0.1; }\n"
                "fluid { source openfoam; }\n")
    run_extract(run_dir, build)


def run_extract(run_dir, build):
    """mixflowExtract -case RUN_DIR -overwrite with its system/extractDict; exits on failure."""
    r = subprocess.run([os.path.join(build, "bin", "mixflowExtract"), "-case", run_dir,
                        "-overwrite"], capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"mixflowExtract failed on {run_dir}:\n{r.stdout[-2000:]}{r.stderr[-2000:]}")


def quantiles(v):
    if v.size == 0:
        return {"median": None, "p10": None, "p90": None, "bins": 0}
    return {"median": float(np.median(v)), "p10": float(np.quantile(v, 0.1)),
            "p90": float(np.quantile(v, 0.9)), "bins": int(v.size)}


def load(h5):
    """The arrays of a mixflowExtract file (mixture_extract/README.md), each (window, y bin, x bin)
    but for the windows: {"fields": name -> float array (NaN where masked), "valid": name -> bool
    (the /masks/valid_<name> of the fields that have one), "counts": name -> array, "windows":
    name -> 1-d array, "grid": name -> 1-d array (x_edges, ...), "reasons": /masks/reasons (None
    without), "reason_bits": its bits by name, "attrs": root attributes}."""
    with h5py.File(h5, "r") as h:
        out = {"fields": {k: h["fields/" + k][()] for k in h["fields"].keys()},
               "valid": {k[len("valid_"):]: h["masks/" + k][()].astype(bool)
                         for k in h["masks"].keys() if k.startswith("valid_")},
               "counts": {k: h["counts/" + k][()] for k in h["counts"].keys()} if "counts" in h
               else {},
               "windows": {k: h["windows/" + k][()] for k in h["windows"].keys()},
               "grid": {k: h["grid/" + k][()] for k in h["grid"].keys()} if "grid" in h else {},
               # /masks/reasons and its bits by name (attribute bit_<value> = "<name>: meaning")
               "reasons": h["masks/reasons"][()] if "masks/reasons" in h else None,
               "reason_bits": {str(v.decode() if isinstance(v, bytes) else v).split(":")[0]:
                               int(k[len("bit_"):])
                               for k, v in (h["masks/reasons"].attrs.items()
                                            if "masks/reasons" in h else ())
                               if k.startswith("bit_")},
               "attrs": {k: (v.decode() if isinstance(v, bytes) else v) for k, v in h.attrs.items()},
               "path": h5}
    return out


def wls_slope(x, y, w):
    """Weighted least-squares slope of y on x through the origin: sum w x y / sum w x^2 (None
    when the denominator vanishes). A bin's ratio y/x enters with weight w x^2, so bins of small
    |x| cannot blow it up."""
    den = float(np.sum(w * x * x))
    return float(np.sum(w * x * y)) / den if den > 0 else None


def summarise(h5):
    d = load(h5)
    f, valid = d["fields"], d["valid"]
    samples = d["counts"].get("particle_samples")
    windows = int(d["windows"]["t0"].shape[0])
    a, us, ws = f["alpha_s"], f["u_s"], f["w_s"]
    speed = np.sqrt(np.nan_to_num(us) ** 2 + np.nan_to_num(ws) ** 2)
    flowing = (np.nan_to_num(a) >= 0.1) & (speed >= 0.05)
    out = {"windows": windows, "flowing_bins": int(flowing.sum())}
    for lam in ("lambda_u", "lambda_w", "lambda_p_density", "lambda_p_raw", "lambda_p_kinematic",
                "pore_pressure_ratio", "p_f_excess", "p_s"):
        if lam not in f:
            continue
        m = flowing & valid.get(lam, np.isfinite(f[lam])) & np.isfinite(f[lam])
        out[lam] = quantiles(f[lam][m])
        out[lam]["masked_in_flowing"] = int((flowing & ~m).sum())
    w = np.nan_to_num(a * (1 - a)) * (np.nan_to_num(samples) if samples is not None else 1.0)
    for lam, fs, ff in (("lambda_u", us, f["u_f"]), ("lambda_w", ws, f["w_f"])):
        m = flowing & np.isfinite(fs) & np.isfinite(ff)
        out[lam + "_wls_slope"] = wls_slope(fs[m], ff[m], w[m])
    out["basal_pore_pressure"] = basal_pore_pressure(d)
    return out


def basal_pore_pressure(d, t_max=1.0):
    """The liquid pressure in the bottom bin row under the initial column (x < sample length)
    against hydrostatic, per window up to T_MAX: the extractor's p_f_excess = p_f - rho_l g (h_l -
    y), h_l the liquid surface of the bin column (mixture_extract/README.md), and p_f_hydrostatic.
    Mean over the x bins where both are valid; Rondon et al. (2011): a dense column's base is
    below hydrostatic while it dilates, a loose one's above."""
    f, at = d["fields"], d["attrs"]
    with h5py.File(d["path"], "r") as h:
        x = h["grid/x"][()]
    cols = np.nonzero(x < float(at["sample_length_m"]))[0]
    rows = []
    for w, (t0, t1) in enumerate(zip(d["windows"]["t0"], d["windows"]["t1"])):
        if t1 > t_max + 1e-9:
            break
        excess, hydro = f["p_f_excess"][w, 0, cols], f["p_f_hydrostatic"][w, 0, cols]
        ok = np.isfinite(excess) & np.isfinite(hydro)
        if ok.any():
            rows.append({"t0": float(t0), "t1": float(t1), "excess_Pa": float(np.mean(excess[ok])),
                         "hydrostatic_Pa": float(np.mean(hydro[ok])), "columns": int(ok.sum())})
    return rows


def drifts_error(run, partner):
    """The convergence error of a run's drifts against its partner's (the same scene one exchange
    step finer), each as summarise() gives them: partner minus run for each median, quantile and
    slope (the basal pore pressure's windows are left out: a series, not a drift)."""
    def drifts(d):
        return {k: v for k, v in d.items() if k != "basal_pore_pressure"}
    return obs.convergence_error(drifts(run), drifts(partner))


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--work", required=True)
    ap.add_argument("--scenes", default="W+P,HB+P,B+P")
    ap.add_argument("--out", default=os.path.join(ROOT, "results", "yield_stress", "lambdas.json"))
    a = ap.parse_args()
    build = os.environ.get("MIXFLOW_BUILD", os.path.join(ROOT, "build"))
    res = {"command": " ".join(["mixflow mixture-lambdas"] + sys.argv[1:]),
           "flowing_rule": "lambda valid, alpha_s >= 0.1, |u_s| >= 0.05 m/s",
           "grid": "x 0-3 m, y 0-0.72 m in bins no narrower than a fluid cell, windows 0.1 s",
           "scenes": {}}
    for scene in a.scenes.split(","):
        r = obs.Scene(os.path.abspath(a.work), scene)
        if not r.done:
            sys.exit(f"mixture-lambdas: {r.dir} is not a finished run (no .done); run or resume "
                     "it with mixflow suite first")
        extract(r.dir, build)
        res["scenes"][LABEL.get(scene, scene)] = dict(
            summarise(os.path.join(r.dir, "postProcessing", "mixture", "mixture.h5")),
            tier_set=r.tier_set)
        print(scene, json.dumps(res["scenes"][LABEL.get(scene, scene)]), flush=True)
    os.makedirs(os.path.dirname(os.path.abspath(a.out)), exist_ok=True)
    with open(a.out, "w") as f:
        json.dump(res, f, indent=1, sort_keys=True)
    summary = os.path.join(os.path.dirname(os.path.abspath(a.out)), "summary.json")
    if os.path.exists(summary):
        with open(summary) as f:
            s = json.load(f)
        s["lambdas"] = res["scenes"]
        s["lambdas_command"] = res["command"]
        with open(summary, "w") as f:
            json.dump(s, f, indent=1, sort_keys=True)
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
