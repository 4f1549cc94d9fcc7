"""The calibration command of the quasi two-phase bulk model (docs/calibration.md): constant drifts
lambda_u, lambda_w and the pore-pressure closure's value (the pore-pressure ratio chi, or lambda_p
with --pressure lambdaP) from a finished CFD-DEM mixture case, written into a bulk case's
constant/bulkProperties `drifts` block with the closure (`pressure porePressureRatio;` or
`pressure lambdaP;`).

usage: mixflow calibrate-drifts SOURCE [--target CASE] [--estimator wls|median|flux]
           [--pressure porePressureRatio|lambdaP] [--pore-reference mixture|surface]
           [--vertical fit|isotropic|auto]
           [--flowing-factor 0.05] [--pressure-bins all|flowing] [--min-solid-fraction 0.1]
           [--windows T0:T1]
           [--weights particles|samples|none] [--bootstrap 1000] [--seed 1] [--json FILE]
           [--fields [--per-window [--window-span K]]] [--field-mean wls|ratio]

SOURCE: a case directory (its postProcessing/mixture/mixture.h5, made by mixflowExtract) or an
.h5 file. The bins used (the same for both estimators) are, in the windows inside [T0, T1]: the
extractor's valid_lambda_<q> mask, alpha_s >= --min-solid-fraction, and, for the velocity drifts
(and the pressure closure with --pressure-bins flowing), flowing: solid speed
sqrt(u_s^2 + w_s^2) >= --flowing-factor * sqrt(g H), H the sample height (root attribute
sample_height_m); the pressure closure takes every such bin, flowing or at rest, by default
(--pressure-bins all): a column that stands carries its pore pressure too. Estimators: wls (default), the weighted least-squares slope through the origin
of u_f on u_s (w_f on w_s; p_f/rho_f on p_s/rho_s, the density convention, for lambda_p; the
excess pore pressure on the grains' load for chi, see --pore-reference); median, the median
of the per-bin ratios; flux, the flux-consistent ratio sum w alpha_f u_f / sum w alpha_f u_s
(the liquid volume flux the drift gives equals the measured one over the selection; for the
pressure drifts sum w y / sum w x). Uncertainty: the 16-84 % interval of the estimate over a
bootstrap of the spatial bins (each drawn with all its windows). Goodness of fit, per velocity
drift: R^2 of u_f against lambda u_s, the R^2 of an additive slip u_f = u_s + delta beside it,
and the mixture mass balance (P-Eq. 9) with the calibrated drifts, d/dx[(alpha_s + lambda_u
alpha_f) u_s] + d/dy[(alpha_s + lambda_w alpha_f) w_s], its RMS over the selected bins against
the RMS of its scale |d/dx| + |d/dy| (the data's own residual, alpha_s u_s + alpha_f u_f, beside
it). A drift is ill-posed when R^2 < 0.5, its 16-84 % interval is wider than its value, or (flux)
the selected solid flux cancels (|sum w alpha_f x| < 0.1 sum w alpha_f |x|): small vertical
speeds of both signs do that to lambda_w. --pore-reference: what chi's excess pore pressure is
over. mixture (default), the bulk model's own: P_f - rho_f p_m on the grains' buoyant load
alpha_s (rho_s - rho_f) p_m, with p_m = (p_s + p_f) / rho_m the mixture's kinematic pressure
(the extractor's total stress p_total over the bulk density rho_m = alpha_s rho_s + alpha_f
rho_f at the bulk model's alpha_s: the target's, else the source's sample_solid_fraction), in
every mixture bin; surface, the extractor's pore_pressure_ratio, p_f_excess (over rho_f g (h_l
- y) from the liquid surface) on p_s + p_f_excess. The two agree at rest; in a flow p_m departs
from g (h_l - y) and the surface ratio is not the bulk model's chi (docs/calibration.md, "Round
trip"). --vertical: fit (default) writes lambda_w's own
estimate; isotropic writes the one drift of both components (u_f = lambda u_s as vectors: the
components' samples pooled); auto writes the fit when it is well-posed, else the isotropic
drift, and says so. Prints a table; with --target writes
CASE/constant/bulkProperties (created if absent; only the drifts entries change) and the JSON
(default CASE/constant/bulkProperties.calibration.json). Bad input exits 2 before writing.
--fields (with --target, whose mesh must exist: mixflowPrepare and blockMesh first) also writes
the drift fields CASE/constant/lambdaU, lambdaW and lambdaP (or porePressureRatio) and `drifts {
fields on; }`: per cell,
from the bin holding the cell centre, the wls slope of that bin's selected windows (--field-mean
wls, default) or the time mean of its per-bin ratios (u_f / u_s, ...; --field-mean ratio), weighted
by the samples' weight w (--weights); the constant estimate where the bin has no selected window or
the cell lies outside the grid; clipped into the bulk model's range (the count is printed).
--per-window (with --fields) writes instead one set per extraction window inside --windows,
CASE/constant/drifts/<t>/lambdaU, lambdaW, lambdaP (t the window's centre, 6 digits), each cell
from its bin's samples of that window alone, or with --window-span K of the K windows centred on it
(the constant estimate where the bin has none then),
and `drifts { fields on; timeVarying on; }`: the bulk model takes them at its time, linear in time
between windows (bulkProperties drifts.interpolation). The counts printed are summed over the
windows.
"""

import argparse
import hashlib
import json
import math
import os
import shutil
import sys

import h5py
import numpy as np

from mixflow import bulkprops, foamcase
from mixflow.foamcase import FoamFileError, format_scalar_list
from mixflow.foamdict import DictError, parse_dict
from mixflow.paper import G
from mixflow.commands.mixture_lambdas import load, quantiles, wls_slope

H5_IN_CASE = os.path.join("postProcessing", "mixture", "mixture.h5")
# drift -> (bulkProperties key, the extractor's mask, solid and fluid quantity names): the
# velocity drifts and the two pore-pressure closures' quantities (PRESSURE picks one).
DRIFTS = {"lambda_u": ("lambdaU", "lambda_u", "u_s", "u_f"),
          "lambda_w": ("lambdaW", "lambda_w", "w_s", "w_f"),
          "lambda_p": ("lambdaP", "lambda_p_density", "p_s / rho_s", "p_f / rho_f"),
          "pore_pressure_ratio": ("porePressureRatio", "pore_pressure_ratio", "p_s + p_f_excess",
                                  "p_f_excess")}
# bulkProperties drifts.pressure -> the drift it calibrates; the default is chi, without the pole
# of Lambda_p (docs/bulk_model.md).
PRESSURE = {"lambdaP": "lambda_p", "porePressureRatio": "pore_pressure_ratio"}
PRESSURE_DEFAULT = "porePressureRatio"
# A result without its "pressure" entry was made when lambdaP was the only closure.
PRESSURE_OF_OLD_RESULTS = "lambdaP"
# What chi's excess pore pressure is over: the bulk model's rho_f p_m, or the extractor's
# hydrostatic from the liquid surface (--pore-reference).
PORE_REFERENCES = ("mixture", "surface")
# The ratio's range (common/DriftAlgebra.h kPoreRatioMin, kPoreRatioMax): [-10, 1).
RATIO_MIN, RATIO_MAX = -10.0, 1.0
# The pressure closure's bins (--pressure-bins): a pore pressure is defined in a bin at rest,
# where the velocity drifts' ratio is not, so a column that stands is calibrated too.
PRESSURE_BINS = ("all", "flowing")
PRESSURE_BINS_DEFAULT = "all"
ESTIMATORS = ("wls", "median", "flux")
# The extractor's "outside the mixture" reasons (mixture_extract/DriftCoefficients.h
# kOutsideMixture), by the names the file gives its bits.
OUTSIDE_MIXTURE = ("no_particles", "few_particle_samples", "no_liquid", "little_liquid",
                   "low_solid_fraction", "unsaturated")
VERTICAL = ("fit", "isotropic", "auto")
# Ill-posed drift: R^2 below, 16-84 % interval wider than the value times, solid flux cancelling.
R2_MIN, WIDTH_MAX, FLUX_CANCEL_MIN = 0.5, 1.0, 0.1
WEIGHTS = {"particles": "particle_equivalents", "samples": "particle_samples", "none": None}
# prepare/BulkModel.cpp readDrift: alpha_s + lambda alpha_f >= 0.01 (kDriftDenominatorMin in
# common/DriftAlgebra.h), |lambda| <= 1e3.
DRIFT_DENOMINATOR_MIN, DRIFT_MAX = 0.01, 1e3


class InputError(Exception):
    """Bad input: the message names the file or option, the entry and the allowed range."""


def find_h5(source):
    path = os.path.join(source, H5_IN_CASE) if os.path.isdir(source) else source
    if not os.path.isfile(path):
        raise InputError(f"{path}: no such file (SOURCE is a case directory holding {H5_IN_CASE}, "
                         "written by mixflowExtract, or an .h5 file)")
    return path


def sha256(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def parse_windows(text):
    """'T0:T1' (either side may be empty) -> (t0, t1) in s."""
    try:
        a, b = text.split(":")
        t0 = float(a) if a.strip() else 0.0
        t1 = float(b) if b.strip() else math.inf
    except ValueError:
        raise InputError(f"--windows '{text}': expected T0:T1 in s (e.g. 0.1:1.0)") from None
    if not (0 <= t0 < t1):
        raise InputError(f"--windows '{text}': allowed 0 <= T0 < T1")
    return t0, t1


def check_options(flowing_factor, min_solid_fraction, weights, n_boot, estimator):
    if not flowing_factor > 0:
        raise InputError(f"--flowing-factor {flowing_factor}: allowed > 0")
    if not 0 <= min_solid_fraction < 1:
        raise InputError(f"--min-solid-fraction {min_solid_fraction}: allowed [0, 1)")
    if weights not in WEIGHTS:
        raise InputError(f"--weights {weights}: allowed {', '.join(WEIGHTS)}")
    if not n_boot >= 10:
        raise InputError(f"--bootstrap {n_boot}: allowed whole >= 10")
    if estimator not in ESTIMATORS:
        raise InputError(f"--estimator {estimator}: allowed {', '.join(ESTIMATORS)}")


def samples(h5, d, flowing_factor, min_solid_fraction, windows, weights,
            pressure=PRESSURE_DEFAULT, pore_reference="mixture", solid_fraction=None,
            pressure_bins=PRESSURE_BINS_DEFAULT):
    """Per drift the selected (window, bin) samples: x (solid), y (fluid), w (weight) and block
    (the spatial bin, for the bootstrap); the selection's description; the windows inside
    WINDOWS as (index, t0, t1). SOLID_FRACTION: the bulk model's alpha_s, for chi over the
    mixture reference. PRESSURE_BINS: the pressure closure's bins, every mixture bin (all) or the
    flowing ones as the velocity drifts' (flowing)."""
    f, valid, attrs = d["fields"], d["valid"], d["attrs"]
    for name in ("alpha_s", "u_s", "w_s", "u_f", "w_f", "p_s", "p_f"):
        if name not in f:
            raise InputError(f"{h5}: no dataset /fields/{name} (a mixflowExtract file with fluid "
                             "data has it)")
    if "sample_height_m" not in attrs:
        raise InputError(f"{h5}: no root attribute sample_height_m (the flowing criterion's H)")
    H = float(attrs["sample_height_m"])
    speed_min = flowing_factor * math.sqrt(G * H)
    t0, t1 = d["windows"]["t0"], d["windows"]["t1"]
    tol = 1e-9 * max(1.0, float(np.max(np.abs(t1)))) if t1.size else 0.0
    win = (t0 >= windows[0] - tol) & (t1 <= windows[1] + tol)
    if not win.any():
        raise InputError(f"--windows {windows[0]:g}:{windows[1]:g}: holds none of the file's "
                         f"{t0.size} windows, which span [{float(np.min(t0)) if t0.size else 0:g}, "
                         f"{float(np.max(t1)) if t1.size else 0:g}] s ({h5} /windows)")
    rho_s = float(attrs.get("particle_density_kg_m3", float("nan")))
    rho_f = float(attrs.get("liquid_density_kg_m3", float("nan")))
    if not (rho_s > 0 and rho_f > 0):
        raise InputError(f"{h5}: root attributes particle_density_kg_m3 {rho_s:g} and "
                         f"liquid_density_kg_m3 {rho_f:g} must be > 0 (the density convention "
                         "of lambda_p needs both)")
    if WEIGHTS[weights] is None:
        wt = np.ones_like(f["alpha_s"])
    elif WEIGHTS[weights] in d["counts"]:
        wt = d["counts"][WEIGHTS[weights]].astype(float)
    else:
        raise InputError(f"{h5}: no dataset /counts/{WEIGHTS[weights]} for --weights {weights}")
    nw, ny, nx = f["alpha_s"].shape
    block = np.broadcast_to(np.arange(ny * nx).reshape(1, ny, nx), (nw, ny, nx))
    speed = np.sqrt(f["u_s"] ** 2 + f["w_s"] ** 2)
    with np.errstate(invalid="ignore"):
        dense = win[:, None, None] & (f["alpha_s"] >= min_solid_fraction)
        base = dense & (speed >= speed_min)
    xy = {"lambda_u": (f["u_s"], f["u_f"]), "lambda_w": (f["w_s"], f["w_f"]),
          "lambda_p": (f["p_s"] / rho_s, f["p_f"] / rho_f)}
    masks = dict(valid)
    if PRESSURE[pressure] == "pore_pressure_ratio" and pore_reference == "mixture":
        xy["pore_pressure_ratio"], masks["pore_pressure_ratio"] = mixture_load(
            h5, d, rho_s, rho_f, solid_fraction)
    elif PRESSURE[pressure] == "pore_pressure_ratio":
        if "p_f_excess" not in f:
            raise InputError(f"{h5}: no dataset /fields/p_f_excess (--pressure "
                             "porePressureRatio needs a mixflowExtract file that splits the pore "
                             "pressure: extract again with -overwrite)")
        xy["pore_pressure_ratio"] = (f["p_s"] + f["p_f_excess"], f["p_f_excess"])
    out = {}
    for q in ("lambda_u", "lambda_w", PRESSURE[pressure]):
        key, mask, _, _ = DRIFTS[q]
        if mask not in masks and q == "lambda_p":
            mask = "lambda_p_raw"  # same conditions (mixture, |p_s| >= minPressure)
        if mask not in masks:
            raise InputError(f"{h5}: no dataset /masks/valid_{mask}")
        x, y = xy[q]
        rows = dense if q == PRESSURE[pressure] and pressure_bins == "all" else base
        m = rows & masks[mask] & np.isfinite(x) & np.isfinite(y) & (wt > 0)
        if not m.any():
            n_valid = int((masks[mask] & win[:, None, None]).sum())
            raise InputError(
                f"{h5}: no bin to calibrate {q} from: in the {int(win.sum())} selected windows "
                f"{n_valid} (window, bin) pairs have /masks/valid_{mask}, none of them with "
                f"alpha_s >= {min_solid_fraction:g} (--min-solid-fraction, allowed [0, 1)) and "
                f"solid speed >= {speed_min:.4g} m/s = {flowing_factor:g} sqrt(g H), H "
                f"{H:g} m (--flowing-factor, allowed > 0)")
        af = f["alpha_f"] if q in ("lambda_u", "lambda_w") and "alpha_f" in f else np.ones_like(x)
        m &= np.isfinite(af)
        out[q] = {"x": x[m], "y": y[m], "w": wt[m], "af": af[m], "block": block[m],
                  "window": np.nonzero(m)[0], "mask": m, "x_all": x, "y_all": y, "w_all": wt,
                  "af_all": af}
    used = np.unique(np.concatenate([s["window"] for s in out.values()]))
    selected = [(int(i), float(t0[i]), float(t1[i])) for i in np.nonzero(win)[0]]
    info = {"flowing_speed_m_s": speed_min, "sample_height_m": H, "g_m_s2": G,
            "rho_s_kg_m3": rho_s, "rho_f_kg_m3": rho_f,
            "windows_used": [float(t0[used].min()), float(t1[used].max())],
            "windows_used_count": int(used.size), "windows_in_file": int(t0.size),
            "source_sample_solid_fraction": float(attrs.get("sample_solid_fraction", 0.0))}
    info["_base"] = base  # the flowing bins of the selected windows, for the mass balance
    return out, info, selected


def mixture_mask(d):
    """The bins inside the mixture: none of the extractor's OUTSIDE_MIXTURE reasons set (finite
    alpha_s in a file without /masks/reasons)."""
    if d["reasons"] is None:
        return np.isfinite(d["fields"]["alpha_s"])
    outside = sum(d["reason_bits"].get(name, 0) for name in OUTSIDE_MIXTURE)  # distinct bits
    return (d["reasons"] & outside) == 0


def mixture_load(h5, d, rho_s, rho_f, alpha):
    """chi's (load, excess) over the bulk model's reference: with p_m rho_m = p_s + p_f (the
    total stress) and rho_m = alpha rho_s + (1 - alpha) rho_f, the buoyant load alpha (rho_s -
    rho_f) p_m = (1 - rho_f / rho_m)(p_s + p_f) and the excess P_f - rho_f p_m; and the bins they
    hold in (inside the mixture, a nonzero load)."""
    if alpha is None or not 0 < alpha < 1:
        raise InputError(f"--pore-reference mixture: the bulk model's solid fraction {alpha} "
                         "(the target's bulkProperties solidFraction or sceneProperties "
                         f"sample.solidFraction, else {h5}'s sample_solid_fraction) must be in "
                         "(0, 1)")
    f = d["fields"]
    gamma = rho_f / (alpha * rho_s + (1 - alpha) * rho_f)
    total = f["p_s"] + f["p_f"]
    inside = mixture_mask(d)
    load = (1 - gamma) * total
    with np.errstate(invalid="ignore"):
        return (load, f["p_f"] - gamma * total), inside & np.isfinite(load) & (load != 0)


def flux_ratio(x, y, a):
    """sum a y / sum a x (None when the denominator vanishes)."""
    den = float(np.sum(a * x))
    return float(np.sum(a * y)) / den if den != 0 else None


def estimate(x, y, w, estimator, af=None):
    if estimator == "wls":
        return wls_slope(x, y, w)
    if estimator == "flux":
        return flux_ratio(x, y, w * (1.0 if af is None else af))
    return float(np.median(y / x))


def fit_quality(x, y, w, lam):
    """Weighted R^2 of y against lam x and of the additive slip y = x + delta (delta the weighted
    mean of y - x), each 1 - sum w r^2 / sum w (y - mean y)^2; None without spread in y."""
    sw = float(np.sum(w))
    ss = float(np.sum(w * (y - np.sum(w * y) / sw) ** 2)) if sw > 0 else 0.0
    if not ss > 0 or lam is None:
        return None, None, None
    delta = float(np.sum(w * (y - x)) / sw)
    return (1.0 - float(np.sum(w * (y - lam * x) ** 2)) / ss,
            1.0 - float(np.sum(w * (y - x - delta) ** 2)) / ss, delta)


def bootstrap(s, estimator, n_boot, seed):
    """Estimates over N_BOOT resamplings of the spatial bins (with replacement, each with all its
    windows: successive windows of one bin are correlated, so they are drawn together)."""
    rng = np.random.default_rng(seed)
    blocks, inv = np.unique(s["block"], return_inverse=True)
    nb = blocks.size
    draws = rng.integers(0, nb, size=(n_boot, nb))
    mult = np.stack([np.bincount(r, minlength=nb) for r in draws]).astype(float)  # (boot, block)
    x, y, w = s["x"], s["y"], s["w"]
    if estimator == "flux":
        a = w * s.get("af", 1.0)
        num = np.bincount(inv, weights=a * y, minlength=nb)
        den = mult @ np.bincount(inv, weights=a * x, minlength=nb)
        with np.errstate(invalid="ignore", divide="ignore"):
            return np.where(den != 0, (mult @ num) / np.where(den != 0, den, 1.0), np.nan)
    if estimator == "wls":
        sxy = np.bincount(inv, weights=w * x * y, minlength=nb)
        sxx = np.bincount(inv, weights=w * x * x, minlength=nb)
        den = mult @ sxx
        with np.errstate(invalid="ignore", divide="ignore"):
            return (mult @ sxy) / den
    r = y / x
    order = np.argsort(r)
    r, inv = r[order], inv[order]
    out = np.empty(n_boot)
    for k0 in range(0, n_boot, 100):  # (100, samples) at a time bounds the memory
        cw = np.cumsum(mult[k0:k0 + 100][:, inv], axis=1)
        out[k0:k0 + 100] = r[np.argmax(cw >= 0.5 * cw[:, -1:], axis=1)]  # lower weighted median
    return out


def calibrate(source, estimator="wls", flowing_factor=0.05, min_solid_fraction=0.1,
              windows=(0.0, math.inf), weights="particles", n_boot=1000, seed=1,
              pressure=PRESSURE_DEFAULT, vertical="fit", pore_reference="mixture",
              solid_fraction=None, pressure_bins=PRESSURE_BINS_DEFAULT):
    """The drifts of SOURCE (case directory or .h5): a dict with per drift the chosen estimate
    ("value"), every estimator, their bootstrap 16/84 % bounds, the per-bin ratio quantiles and
    counts, the velocity drifts' fit quality and well-posedness, lambda_w's rule ("vertical"),
    the mass balance with the drifts ("mass_balance"), and the selection ("selection") and file
    ("h5", "sha256")."""
    check_options(flowing_factor, min_solid_fraction, weights, n_boot, estimator)
    if vertical not in VERTICAL:
        raise InputError(f"--vertical {vertical}: allowed {', '.join(VERTICAL)}")
    if pressure not in PRESSURE:
        raise InputError(f"--pressure {pressure}: allowed {', '.join(PRESSURE)}")
    if pore_reference not in PORE_REFERENCES:
        raise InputError(f"--pore-reference {pore_reference}: allowed "
                         f"{', '.join(PORE_REFERENCES)}")
    if pressure_bins not in PRESSURE_BINS:
        raise InputError(f"--pressure-bins {pressure_bins}: allowed {', '.join(PRESSURE_BINS)}")
    h5 = find_h5(source)
    try:
        d = load(h5)
    except (OSError, KeyError) as e:
        raise InputError(f"{h5}: not a mixflowExtract HDF5 file ({e})") from None
    ratio = PRESSURE[pressure] == "pore_pressure_ratio"
    if ratio and pore_reference == "mixture" and solid_fraction is None:
        solid_fraction = float(d["attrs"].get("sample_solid_fraction", 0.0))
    sel, info, selected = samples(h5, d, flowing_factor, min_solid_fraction, windows, weights,
                                  pressure, pore_reference, solid_fraction, pressure_bins)
    base = info.pop("_base")
    res = {"h5": h5, "sha256": sha256(h5), "estimator": estimator, "pressure": pressure,
           "selection": dict(info, flowing_factor=flowing_factor,
                             min_solid_fraction=min_solid_fraction, weights=weights,
                             pressure_bins=pressure_bins,
                             windows_option=[windows[0], None if math.isinf(windows[1])
                                             else windows[1]],
                             bootstrap=n_boot, seed=seed),
           "drifts": {}}
    if ratio:
        res["pore_reference"] = pore_reference
        if pore_reference == "mixture":
            res["pore_solid_fraction"] = solid_fraction
    for q, s in sel.items():
        r = {"samples": int(s["x"].size), "spatial_bins": int(np.unique(s["block"]).size),
             "ratio_quantiles": quantiles(s["y"] / s["x"])}
        for est in ESTIMATORS:
            v = estimate(s["x"], s["y"], s["w"], est, s["af"])
            b = bootstrap(s, est, n_boot, seed)
            b = b[np.isfinite(b)]
            r[est] = {"value": v, "p16": float(np.quantile(b, 0.16)) if b.size else None,
                      "p84": float(np.quantile(b, 0.84)) if b.size else None}
        if r[estimator]["value"] is None:
            raise InputError(f"{h5}: {q}: the selected bins' {DRIFTS[q][2]} are all 0; no slope")
        r["value"] = r[estimator]["value"]
        if q in ("lambda_u", "lambda_w"):
            r["fit"] = posedness(s, r, estimator)
        res["drifts"][q] = r
    vertical_rule(res, sel, estimator, vertical, n_boot, seed)
    res["mass_balance"] = mass_balance(h5, d, base, res["drifts"]["lambda_u"]["value"],
                                       res["drifts"]["lambda_w"]["value"])
    res["_samples"] = sel  # the full (window, y, x) selection, for --fields
    res["_windows"] = selected  # the windows inside --windows, for --per-window
    return res


def posedness(s, r, estimator):
    """A velocity drift's fit quality (fit_quality), the relative width of its 16-84 % interval,
    the solid flux's cancellation (flux: |sum a x| / sum a |x|) and whether it is well-posed."""
    x, y, w, a = s["x"], s["y"], s["w"], s["w"] * s["af"]
    lam, e = r["value"], r[estimator]
    r2, r2_add, delta = fit_quality(x, y, w, lam)
    width = ((e["p84"] - e["p16"]) / abs(lam) if e["p16"] is not None and e["p84"] is not None
             and lam else None)
    cancel = float(abs(np.sum(a * x)) / np.sum(a * np.abs(x))) if np.sum(a * np.abs(x)) > 0 else 0.0
    why = []
    if r2 is None or r2 < R2_MIN:
        why.append(f"R^2 {r2 if r2 is None else round(r2, 3)} < {R2_MIN:g}")
    if width is None or width > WIDTH_MAX:
        why.append(f"16-84 % interval {width if width is None else round(width, 3)} x the value "
                   f"> {WIDTH_MAX:g}")
    if estimator == "flux" and cancel < FLUX_CANCEL_MIN:
        why.append(f"the solid flux cancels ({cancel:.3f} < {FLUX_CANCEL_MIN:g})")
    return {"r2": r2, "r2_additive_slip": r2_add, "additive_slip_m_s": delta,
            "interval_width_rel": width, "solid_flux_net_share": cancel, "well_posed": not why,
            "ill_posed_because": why}


def vertical_rule(res, sel, estimator, vertical, n_boot, seed):
    """lambda_w as --vertical says: its fit, or the isotropic drift of both components pooled
    (auto: the fit if well-posed). Records res["drifts"]["lambda_w"]["vertical"]."""
    su, sw = sel["lambda_u"], sel["lambda_w"]
    pooled = {k: np.concatenate([su[k], sw[k]]) for k in ("x", "y", "w", "af")}
    pooled["block"] = np.concatenate([su["block"], sw["block"]])
    if estimator == "flux":  # along each component's motion: the vertical flux cannot cancel
        sign = np.sign(pooled["x"])
        pooled["x"], pooled["y"] = pooled["x"] * sign, pooled["y"] * sign
    iso = estimate(pooled["x"], pooled["y"], pooled["w"], estimator, pooled["af"])
    b = bootstrap(pooled, estimator, n_boot, seed)
    b = b[np.isfinite(b)]
    rw = res["drifts"]["lambda_w"]
    use_iso = vertical == "isotropic" or (vertical == "auto" and not rw["fit"]["well_posed"])
    rw["vertical"] = {"rule": vertical, "used": "isotropic" if use_iso else "fit",
                      "fit_value": rw["value"], "isotropic_value": iso,
                      "isotropic_p16": float(np.quantile(b, 0.16)) if b.size else None,
                      "isotropic_p84": float(np.quantile(b, 0.84)) if b.size else None}
    if use_iso:
        if iso is None:
            raise InputError(f"{res['h5']}: --vertical {vertical}: the pooled solid velocities "
                             "are all 0; no isotropic drift")
        rw["value"] = iso


def mass_balance(h5, d, base, lam_u, lam_w):
    """P-Eq. 9 with constant drifts, d/dx[(alpha_s + lam_u alpha_f) u_s] + d/dy[(alpha_s + lam_w
    alpha_f) w_s], as the extractor differences it (central between mixture bins, one-sided at
    the mixture's edge): RMS over the BASE bins that have both derivatives, against the RMS of
    the scale |d/dx| + |d/dy|; and the same for the data's own alpha_s u_s + alpha_f u_f."""
    f = d["fields"]
    dx = float(np.diff(d["grid"]["x_edges"]).mean())
    dy = float(np.diff(d["grid"]["y_edges"]).mean())
    mix = mixture_mask(d)

    def deriv(g, axis, h):
        gp, gm = np.roll(g, -1, axis), np.roll(g, 1, axis)
        inp, inm = np.roll(mix, -1, axis), np.roll(mix, 1, axis)
        n = g.shape[axis]
        idx = np.arange(n).reshape([-1 if k == axis else 1 for k in range(g.ndim)])
        inp = inp & (idx < n - 1)
        inm = inm & (idx > 0)
        with np.errstate(invalid="ignore"):
            out = np.where(inp & inm, (gp - gm) / (2 * h),
                           np.where(inp, (gp - g) / h, np.where(inm, (g - gm) / h, np.nan)))
        return np.where(mix, out, np.nan)

    def rms(mx, my):
        ddx, ddy = deriv(mx, 2, dx), deriv(my, 1, dy)
        ok = base & np.isfinite(ddx) & np.isfinite(ddy)
        if not ok.any():
            return None, 0
        res_, scale = (ddx + ddy)[ok], (np.abs(ddx) + np.abs(ddy))[ok]
        s = float(np.sqrt(np.mean(scale ** 2)))
        return (float(np.sqrt(np.mean(res_ ** 2))) / s if s > 0 else None), int(ok.sum())

    a_s, a_f = f["alpha_s"], f["alpha_f"]
    cal, n = rms((a_s + lam_u * a_f) * f["u_s"], (a_s + lam_w * a_f) * f["w_s"])
    own, _ = rms(a_s * f["u_s"] + a_f * f["u_f"], a_s * f["w_s"] + a_f * f["w_f"])
    return {"residual_over_scale": cal, "data_residual_over_scale": own, "bins": n,
            "lambda_u": lam_u, "lambda_w": lam_w}


def table(res):
    def g(v):
        return f"{v:8.4g}" if v is not None else f"{'-':>8}"

    lines = [f"{'drift':19} {'value':>8} {'16%':>8} {'84%':>8}   {'wls':>8} {'median':>8} "
             f"{'flux':>8}   {'ratio p10':>9} {'p50':>8} {'p90':>8} {'samples':>8} {'bins':>5}"]
    for q, r in res["drifts"].items():
        e, rq = r[res["estimator"]], r["ratio_quantiles"]
        if r.get("vertical", {}).get("used") == "isotropic":
            e = {"p16": r["vertical"]["isotropic_p16"], "p84": r["vertical"]["isotropic_p84"]}
        lines.append(f"{q:19} {r['value']:8.4g} {g(e['p16'])} {g(e['p84'])}   "
                     f"{g(r['wls']['value'])} {g(r['median']['value'])} {g(r['flux']['value'])}   "
                     f"{rq['p10']:9.4g} {rq['median']:8.4g} {rq['p90']:8.4g} {r['samples']:8d} "
                     f"{r['spatial_bins']:5d}")
    for q in ("lambda_u", "lambda_w"):
        f = res["drifts"][q]["fit"]
        lines.append(f"{q}: R^2 {g(f['r2']).strip()} (additive slip u_f = u_s + "
                     f"{g(f['additive_slip_m_s']).strip()} m/s: R^2 "
                     f"{g(f['r2_additive_slip']).strip()}), "
                     + ("well-posed" if f["well_posed"] else
                        "ill-posed: " + "; ".join(f["ill_posed_because"])))
    v = res["drifts"]["lambda_w"]["vertical"]
    lines.append(f"lambda_w written: {v['used']} (--vertical {v['rule']}; fit {g(v['fit_value']).strip()}, "
                 f"isotropic {g(v['isotropic_value']).strip()})")
    mb = res["mass_balance"]
    lines.append(f"mass balance (P-Eq. 9) with these drifts: RMS residual / RMS scale "
                 f"{g(mb['residual_over_scale']).strip()} over {mb['bins']} bins (the data's own "
                 f"alpha_s u_s + alpha_f u_f: {g(mb['data_residual_over_scale']).strip()})")
    if res.get("pore_reference") == "mixture":
        lines.append(f"pore_pressure_ratio over the bulk model's rho_f p_m, p_m = (p_s + p_f) / "
                     f"rho_m at alpha_s {res['pore_solid_fraction']:g} (--pore-reference mixture)")
    elif res.get("pore_reference") == "surface":
        lines.append("pore_pressure_ratio over the hydrostatic from the liquid surface "
                     "(--pore-reference surface: the extractor's pore_pressure_ratio)")
    s = res["selection"]
    lines.append(f"estimator {res['estimator']} (16-84 % bootstrap over spatial bins, "
                 f"{s['bootstrap']} draws); flowing: solid speed >= {s['flowing_speed_m_s']:.4g} "
                 f"m/s ({s['flowing_factor']:g} sqrt(g H), H {s['sample_height_m']:g} m; "
                 f"the pressure closure's bins: {s.get('pressure_bins', 'flowing')}), "
                 f"alpha_s >= {s['min_solid_fraction']:g}; windows {s['windows_used'][0]:g}-"
                 f"{s['windows_used'][1]:g} s ({s['windows_used_count']} of "
                 f"{s['windows_in_file']}); weights {s['weights']}")
    return "\n".join(lines)


def _num(v):
    return f"{v:.6g}"


def target_solid_fraction(target, tree):
    """alpha_s the bulk model of TARGET uses (prepare/BulkModel.cpp): bulkProperties
    solidFraction, else its sceneProperties sample.solidFraction; (None, None) without either."""
    if "solidFraction" in tree:
        return float(tree["solidFraction"]), "constant/bulkProperties solidFraction"
    scene = os.path.join(target, "constant", "sceneProperties")
    if os.path.isfile(scene):
        try:
            with open(scene) as f:
                sf = parse_dict(f.read()).get("sample", {}).get("solidFraction")
            if sf is not None:
                return float(sf.split()[0]), f"{scene} sample.solidFraction"
        except (DictError, ValueError):
            pass
    return None, None


def _solid_fraction(target, tree, res):
    """target_solid_fraction, else the source's sample_solid_fraction."""
    alpha, where = target_solid_fraction(target, tree)
    if alpha is not None:
        return alpha, where
    return res["selection"]["source_sample_solid_fraction"], "the source's sample_solid_fraction"


def bulk_properties_text(path, drifts, source, block, fields=False, per_window=False,
                         pressure=PRESSURE_DEFAULT):
    """The text of PATH (absent: a new file) with drifts { lambdaU; lambdaW; pressure; lambdaP or
    porePressureRatio; source; } (and `fields on;` with FIELDS, `timeVarying on;` with
    PER_WINDOW) set through foamdict.edit_dict: every other byte of an existing file stays as it
    is. BLOCK is the file's drifts block: a `fields` or `timeVarying` it has that this
    calibration does not write is set off, so that no drifts of an earlier calibration stay in
    use."""
    entries = {DRIFTS[q][0]: _num(v) for q, v in drifts.items()}
    entries["pressure"] = pressure
    for key, on in (("fields", fields), ("timeVarying", per_window)):
        if on or key in block:
            entries[key] = "on" if on else "off"
    entries["source"] = '"' + source.replace('"', "'") + '"'
    return bulkprops.block_text(path, "drifts", entries)



def bin_means(s, how):
    """Per spatial bin (y, x) over the selected windows, NaN where the bin has none: the weighted
    time mean of the ratio y/x, sum_t w (y/x) / sum_t w (ratio), the wls slope of the bin's
    windows, sum_t w x y / sum_t w x^2 (wls: a window where the grains barely move weighs less),
    or the bin's flux ratio sum_t w alpha_f y / sum_t w alpha_f x (flux)."""
    m = s["mask"]
    with np.errstate(invalid="ignore", divide="ignore"):
        x = np.where(m, s["x_all"], 0.0)
        y = np.where(m, s["y_all"], 0.0)
        w = np.where(m, s["w_all"], 0.0)
        if how == "wls":
            num, den = (w * x * y).sum(axis=0), (w * x * x).sum(axis=0)
        elif how == "flux":
            a = w * np.where(m, s["af_all"], 0.0)
            num, den = (a * y).sum(axis=0), (a * x).sum(axis=0)
            return np.where(den != 0, num / np.where(den != 0, den, 1.0), np.nan)
        else:
            num = (w * np.where(m, y / np.where(m, x, 1.0), 0.0)).sum(axis=0)
            den = w.sum(axis=0)
        return np.where(den > 0, num / np.where(den > 0, den, 1.0), np.nan)


def cell_centres(target):
    """The cell centres (x, y) of TARGET's mesh as an (n, 2) array."""
    try:
        return np.array(foamcase.cell_centres(target))
    except FoamFileError as e:
        raise InputError(f"{e} (--fields writes the drifts on the target's mesh: run "
                         "mixflowPrepare and blockMesh on it first)") from None


def drift_fields(res, centres, lo, hi, how, window=None):
    """Per drift the cell values on CENTRES (see bin_means) and their bookkeeping; with WINDOW
    (indices of the file's windows) from those windows' samples alone."""
    with h5py.File(res["h5"], "r") as h:
        xe, ye = h["grid/x_edges"][()], h["grid/y_edges"][()]
    ix = np.searchsorted(xe, centres[:, 0], side="right") - 1
    iy = np.searchsorted(ye, centres[:, 1], side="right") - 1
    inside = (ix >= 0) & (ix < xe.size - 1) & (iy >= 0) & (iy < ye.size - 1)
    out = {}
    for q, s in res["_samples"].items():
        if window is not None:
            mask = np.zeros_like(s["mask"])
            mask[list(window)] = s["mask"][list(window)]
            s = dict(s, mask=mask)
        means = bin_means(s, how)
        v = np.full(len(centres), np.nan)
        v[inside] = means[iy[inside], ix[inside]]
        fallback = ~np.isfinite(v)
        v[fallback] = res["drifts"][q]["value"]
        # chi's range is [-10, 1): its cells are held below 1 by the largest double under it.
        qlo, qhi = ((RATIO_MIN, np.nextafter(RATIO_MAX, -np.inf)) if q == "pore_pressure_ratio"
                    else (lo, hi))
        clipped = (v < qlo) | (v > qhi)
        v = np.clip(v, qlo, qhi)
        out[q] = {"values": v, "cells": int(v.size), "from_bins": int((~fallback).sum()),
                  "fallback_cells": int(fallback.sum()), "clipped_cells": int(clipped.sum()),
                  "bins_with_value": int(np.isfinite(means).sum()), "bins": int(means.size),
                  "min": float(v.min()), "max": float(v.max())}
    return out


FIELD_MEAN_TEXT = {"wls": "the wls slope of the windows", "ratio": "the weighted time mean of the ratios",
                   "flux": "the flux ratio of the windows"}


def field_text(name, values, source, field_mean, location="constant"):
    return ("FoamFile\n{\n    version     2.0;\n    format      ascii;\n    class       "
            f"volScalarField;\n    location    \"{location}\";\n    object      {name};\n}}\n"
            f"// {source}\n// per cell: {FIELD_MEAN_TEXT[field_mean]} of the bin holding its centre "
            "(the constant estimate where none), clipped to the bulk model's range\n\n"
            f"dimensions      [0 0 0 0 0 0 0];\n\ninternalField   {format_scalar_list(values)}\n;\n\n"
            "boundaryField\n{\n"
            "    \".*\" { type zeroGradient; }\n    #includeEtc \"caseDicts/setConstraintTypes\"\n}\n")


def public(res):
    """RES without its private entries (keys starting with _: the samples kept for --fields)."""
    return {k: v for k, v in res.items() if not k.startswith("_")}


def check_target(target):
    """TARGET has constant/ and a readable bulkProperties (or none); returns the latter's tree."""
    const = os.path.join(target, "constant")
    if not os.path.isdir(const):
        raise InputError(f"{target}: no constant/ directory (--target is a case directory; "
                         "bulkProperties goes into its constant/)")
    path = bulkprops.path(target)
    try:
        tree = bulkprops.read(target)
    except DictError as e:
        raise InputError(f"{path}: {e}") from None
    if "drifts" in tree and not isinstance(tree["drifts"], dict):
        raise InputError(f"{path}: 'drifts' is an entry, not a block")
    return tree


def window_name(t0, t1):
    """The directory name of a window in constant/drifts/: its centre, as OpenFOAM names a time
    (6 significant digits)."""
    return f"{(t0 + t1) / 2:.6g}"


def series_fields(res, centres, lo, hi, field_mean, source, target, span=1):
    """--per-window: per window inside --windows the drift fields of the samples of the SPAN
    windows centred on it (fewer at the ends), as (path, text) under
    TARGET/constant/drifts/<centre>/, and per drift their bookkeeping (counts summed over the
    windows, each window's own under "windows")."""
    names = [window_name(t0, t1) for _, t0, t1 in res["_windows"]]
    if len(set(names)) != len(names):
        raise InputError(f"{res['h5']} /windows: two windows share the centre "
                         f"{next(n for n in names if names.count(n) > 1)} s at 6 digits "
                         "(--per-window names each window's fields by its centre); nothing "
                         "written")
    files, summary = [], {}
    wins, half = res["_windows"], span // 2
    for k, (name, (i, t0, t1)) in enumerate(zip(names, wins)):
        pool = [w[0] for w in wins[max(0, k - half):k + half + 1]]
        pooled = (f", pooled over windows {wins[max(0, k - half)][1]:g}-"
                  f"{wins[min(len(wins) - 1, k + half)][2]:g} s" if span > 1 else "")
        for q, f in drift_fields(res, centres, lo, hi, field_mean, window=pool).items():
            key = DRIFTS[q][0]
            rel = os.path.join("constant", "drifts", name)
            files.append((os.path.join(target, rel, key),
                          field_text(key, f["values"], f"{source}, field mean {field_mean}, "
                                     f"window {t0:g}-{t1:g} s{pooled}", field_mean, rel)))
            r = summary.setdefault(key, {"windows": [], "min": f["min"], "max": f["max"],
                                         "file": os.path.join(target, "constant", "drifts")})
            r["windows"].append(dict({k: v for k, v in f.items() if k != "values"}, time=name,
                                     t0=t0, t1=t1))
            r["min"], r["max"] = min(r["min"], f["min"]), max(r["max"], f["max"])
    for r in summary.values():
        for k in ("cells", "from_bins", "fallback_cells", "clipped_cells", "bins_with_value",
                  "bins"):
            r[k] = sum(w[k] for w in r["windows"])
    return files, summary


def write_series(target, files):
    """The window directories of FILES into TARGET/constant/drifts/, replacing the earlier
    series as a whole (through a directory renamed over it): no window of an earlier calibration
    stays."""
    final = os.path.join(target, "constant", "drifts")
    staging = final + ".new"
    shutil.rmtree(staging, ignore_errors=True)
    for p, body in files:
        p = os.path.join(staging, os.path.relpath(p, final))
        os.makedirs(os.path.dirname(p), exist_ok=True)
        bulkprops.write_text(p, body)
    shutil.rmtree(final, ignore_errors=True)
    os.replace(staging, final)


def write_target(target, res, source_arg, json_path=None, fields=False, field_mean="wls",
                 per_window=False, window_span=1):
    """Checks TARGET and the drifts against the bulk model's range, then writes
    TARGET/constant/bulkProperties and the JSON (with FIELDS also constant/lambdaU, lambdaW,
    lambdaP; with PER_WINDOW instead one set per window, constant/drifts/<centre>/); returns
    their paths. Nothing is written when a check fails (InputError)."""
    tree = check_target(target)
    centres = cell_centres(target) if fields else None
    path = bulkprops.path(target)
    try:
        alpha, alpha_from = _solid_fraction(target, tree, res)
    except ValueError as e:
        raise InputError(f"{path}: solidFraction: {e}") from None
    lo = (DRIFT_DENOMINATOR_MIN - alpha) / (1 - alpha) if alpha < 1 else -DRIFT_MAX
    drifts = {q: r["value"] for q, r in res["drifts"].items()}
    if res.get("pore_reference") == "mixture" and abs(res["pore_solid_fraction"] - alpha) > 1e-9:
        raise InputError(f"{path}: chi was calibrated over the mixture reference at alpha_s "
                         f"{res['pore_solid_fraction']:g}, the target's is {alpha:g} (from "
                         f"{alpha_from}): calibrate with the target's solid fraction; nothing "
                         "written")
    pressure = res.get("pressure", PRESSURE_OF_OLD_RESULTS)
    other = next(k for k in PRESSURE if k != pressure)
    if other in tree.get("drifts", {}):
        raise InputError(f"{path}: drifts.{other} belongs to the other pore-pressure closure "
                         f"(drifts.pressure {other}); remove it to calibrate --pressure "
                         f"{pressure}; nothing written")
    for q, v in drifts.items():
        if q == "pore_pressure_ratio":
            if not RATIO_MIN <= v < RATIO_MAX:
                raise InputError(f"{path}: drifts.porePressureRatio would be {v:.6g}, outside "
                                 f"the bulk model's allowed range [{RATIO_MIN:g}, {RATIO_MAX:g}); "
                                 "nothing written")
        elif not lo <= v <= DRIFT_MAX:
            raise InputError(f"{path}: drifts.{DRIFTS[q][0]} would be {v:.6g}, outside the bulk "
                             f"model's allowed range [{lo:.4g}, {DRIFT_MAX:g}] (alpha_s + lambda "
                             f"alpha_f >= {DRIFT_DENOMINATOR_MIN:g}, alpha_s {alpha:g} from "
                             f"{alpha_from}); nothing written")
    s = res["selection"]
    rel = os.path.relpath(res["h5"], source_arg) if os.path.isdir(source_arg) else res["h5"]
    where = (os.path.normpath(source_arg) + " " + rel) if os.path.isdir(source_arg) else rel
    vert = res["drifts"]["lambda_w"].get("vertical", {}).get("used", "fit")
    source = (f"calibrate_drifts.py: {where} sha256 {res['sha256']}, estimator "
              f"{res['estimator']}, windows {s['windows_used'][0]:g}-{s['windows_used'][1]:g} s"
              + (f", lambda_w {vert}" if vert != "fit" else ""))
    try:
        text = bulk_properties_text(path, drifts, source, tree.get("drifts", {}), fields,
                                    per_window, pressure)
    except DictError as e:
        raise InputError(f"{path}: {e}") from None
    json_path = json_path or path + ".calibration.json"
    files, series = [], []
    private = res
    res = dict(public(res), bulk_properties=path, source=source, solid_fraction=alpha,
               solid_fraction_from=alpha_from, drift_range=[lo, DRIFT_MAX])
    if per_window:
        series, res["fields"] = series_fields(private, centres, lo, DRIFT_MAX, field_mean, source,
                                              target, window_span)
        res["field_mean"], res["window_span"] = field_mean, window_span
    elif fields:
        fs = drift_fields(private, centres, lo, DRIFT_MAX, field_mean)
        res["fields"] = {}
        res["field_mean"] = field_mean
        for q, f in fs.items():
            name = DRIFTS[q][0]
            fp = os.path.join(target, "constant", name)
            files.append((fp, field_text(name, f["values"], f"{source}, field mean {field_mean}",
                                         field_mean)))
            res["fields"][name] = dict({k: v for k, v in f.items() if k != "values"}, file=fp)
    files += [(path, text), (json_path, json.dumps(res, indent=1, sort_keys=True) + "\n")]
    if series:
        write_series(target, series)
    for p, body in files:
        bulkprops.write_text(p, body)
    return ([os.path.join(target, "constant", "drifts")] if series else []) + [p for p, _ in files]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("source", help="CFD-DEM case directory or its mixture.h5")
    ap.add_argument("--target", help="bulk case: writes its constant/bulkProperties drifts")
    ap.add_argument("--estimator", default="wls",
                    help="wls (default), median or flux (sum alpha_f u_f / sum alpha_f u_s)")
    ap.add_argument("--vertical", default="fit",
                    help="lambda_w written: fit (default, its own estimate), isotropic (one "
                    "drift of both components) or auto (the fit if well-posed, else isotropic)")
    ap.add_argument("--pressure", default=PRESSURE_DEFAULT,
                    help="the pore-pressure closure calibrated and written (bulkProperties "
                    "drifts.pressure): porePressureRatio (default: chi, without the pole of "
                    "Lambda_p; docs/bulk_model.md) or lambdaP (the pressure drift of Pokhrel et "
                    "al.)")
    ap.add_argument("--pore-reference", default="mixture",
                    help="--pressure porePressureRatio: chi's excess over the bulk model's rho_f "
                    "p_m (mixture, default) or over the extractor's hydrostatic from the liquid "
                    "surface (surface: its pore_pressure_ratio)")
    ap.add_argument("--flowing-factor", type=float, default=0.05,
                    help="flowing bins: solid speed >= FACTOR sqrt(g H) (default 0.05)")
    ap.add_argument("--pressure-bins", default=PRESSURE_BINS_DEFAULT,
                    help="the pressure closure's bins: all (default: every mixture bin, the "
                    "column at rest too, whose pore pressure is defined where u_f / u_s is not) "
                    "or flowing (the velocity drifts' bins)")
    ap.add_argument("--min-solid-fraction", type=float, default=0.1)
    ap.add_argument("--windows", default=":", help="T0:T1 (s): windows inside it (default all)")
    ap.add_argument("--weights", default="particles")
    ap.add_argument("--bootstrap", type=int, default=1000)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--json", help="JSON of the result (default next to bulkProperties)")
    ap.add_argument("--fields", action="store_true",
                    help="with --target: also the drift fields constant/lambdaU, lambdaW, lambdaP "
                    "on the target's mesh, and drifts { fields on; }")
    ap.add_argument("--per-window", action="store_true",
                    help="with --fields: one set of fields per extraction window inside "
                    "--windows, constant/drifts/<centre>/lambdaU, lambdaW, lambdaP, from that "
                    "window's samples alone, and drifts { timeVarying on; } (the bulk model "
                    "takes them at its time, docs/bulk_model.md)")
    ap.add_argument("--window-span", type=int, default=1,
                    help="--per-window: each window's fields from the samples of the SPAN "
                    "windows centred on it (odd, >= 1; default 1: its own alone)")
    ap.add_argument("--field-mean", default="wls",
                    help="--fields: per bin the wls slope of its windows (wls, default: the "
                    "ratios' mean lets W&P's lambda_w reach the range limit and the run diverge), "
                    "the weighted time mean of the ratios (ratio) or the flux ratio sum alpha_f "
                    "u_f / sum alpha_f u_s of its windows (flux)")
    a = ap.parse_args(argv)
    try:
        if a.fields and not a.target:
            raise InputError("--fields: needs --target CASE (the fields go on its mesh)")
        if a.per_window and not a.fields:
            raise InputError("--per-window: needs --fields (the windows' fields are drift fields)")
        if a.window_span < 1 or a.window_span % 2 == 0:
            raise InputError(f"--window-span {a.window_span}: allowed an odd integer >= 1")
        if a.window_span > 1 and not a.per_window:
            raise InputError("--window-span: applies to --per-window only")
        if a.field_mean not in FIELD_MEAN_TEXT:
            raise InputError(f"--field-mean {a.field_mean}: allowed {', '.join(sorted(FIELD_MEAN_TEXT))}")
        alpha = None
        if a.target:  # before the extraction is read: a bad target fails at once
            alpha, _ = target_solid_fraction(a.target, check_target(a.target))
        res = calibrate(a.source, a.estimator, a.flowing_factor, a.min_solid_fraction,
                        parse_windows(a.windows), a.weights, a.bootstrap, a.seed, a.pressure,
                        a.vertical, a.pore_reference, alpha, a.pressure_bins)
        print(table(res))
        if a.target:
            for p in write_target(a.target, res, a.source, a.json, a.fields, a.field_mean,
                                  a.per_window, a.window_span):
                print(f"wrote {p}")
            if a.fields:
                with open(a.json or bulkprops.path(a.target) + ".calibration.json") as f:
                    for name, r in json.load(f)["fields"].items():
                        each = f"{len(r['windows'])} windows, " if "windows" in r else ""
                        print(f"{name}: {each}{r['cells']} cells, {r['from_bins']} from their bin "
                              f"({r['bins_with_value']} of {r['bins']} bins have a value), "
                              f"{r['fallback_cells']} the constant, {r['clipped_cells']} clipped "
                              f"into the allowed range; values [{r['min']:.4g}, {r['max']:.4g}]")
        elif a.json:
            with open(a.json, "w") as f:
                json.dump(public(res), f, indent=1, sort_keys=True)
            print(f"wrote {a.json}")
    except InputError as e:
        print(f"calibrate_drifts.py: error: {e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
