"""calibrate_drifts.py on a synthetic extraction with known drifts (drift_data.py): the wls
estimator recovers them within 4 standard errors, the ratio median of lambda_u is pulled low by
the slow bins, the flux estimator recovers lambda_u and finds its lambda_w ill-posed (vertical
solid flux of both signs), --vertical auto then writes the isotropic drift, the mass balance of
the data equals the extractor's, the bootstrap 16-84 % interval matches the least-squares standard error, the
flowing criterion drops the slow bins, and the command writes bulkProperties and its JSON.

usage: test_calibrate_recovery.py MIXFLOWEXTRACT WORKDIR"""
import json
import math
import os
import subprocess
import sys

import numpy as np

from mixflow.cli import command  # noqa: E402
from mixflow.commands import calibrate_drifts as cd  # noqa: E402
import drift_data as dd  # noqa: E402
from mixflow.foamdict import read_dict, unquote  # noqa: E402
from mixflow.synthcase import checker  # noqa: E402
from mixflow.commands.mixture_lambdas import load  # noqa: E402

LAMBDA_P = "lambdaP"  # the closure whose prescribed lambda_p the data carry


def main():
    exe, work = sys.argv[1], sys.argv[2]
    failures = []
    check = checker(failures)
    case = os.path.join(work, "dem_case")
    t = dd.make(case, exe)
    h5 = os.path.join(case, cd.H5_IN_CASE)

    # The case maker's bins are exact, so the truth below is what the extractor measured.
    f = load(h5)["fields"]
    k = {"us": "u_s", "ws": "w_s", "uf": "u_f", "wf": "w_f", "pf": "p_f"}
    err = max(float(np.max(np.abs(f[k[n]] - t[n]))) for n in k)
    check(err < 1e-6, f"extracted bins equal the prescribed values: max |diff| {err:.2e} < 1e-6")
    ps_err = float(np.max(np.abs(f["p_s"] / t["ps"] - 1)))
    check(ps_err < 1e-9, f"p_s = prescribed granular pressure: max rel. diff {ps_err:.2e} < 1e-9")

    res = cd.calibrate(case, pressure=LAMBDA_P)
    n = t["us"].size
    cases = (("lambda_u", dd.LU, dd.SIGMA_U, t["us"]), ("lambda_w", dd.LW, dd.SIGMA_W, t["ws"]),
             ("lambda_p", dd.LP, dd.SIGMA_P, t["ps"] / dd.RHO_S))
    for q, true, sigma, x in cases:
        r = res["drifts"][q]
        check(r["samples"] == n, f"{q}: all {n} (window, bin) samples flow and are valid "
                                 f"(got {r['samples']})")
        # Equal weights (36 particles in every bin): SE of the slope = sigma / sqrt(sum x^2).
        se = sigma / math.sqrt(float(np.sum(x * x)))
        v = r["wls"]["value"]
        check(abs(v - true) <= 4 * se, f"{q}: wls {v:.4f} recovers {true} within 4 SE = "
                                       f"{4 * se:.4f} (off by {abs(v - true):.4f})")
        half = 0.5 * (r["wls"]["p84"] - r["wls"]["p16"])
        check(0.6 * se <= half <= 1.6 * se,
              f"{q}: bootstrap 16-84 % half-width {half:.4f} within [0.6, 1.6] x the "
              f"least-squares SE {se:.4f} (ratio {half / se:.2f})")
        print(f"     {q}: wls {v:.4f} [{r['wls']['p16']:.4f}, {r['wls']['p84']:.4f}], median "
              f"{r['median']['value']:.4f} [{r['median']['p16']:.4f}, {r['median']['p84']:.4f}]")
    ru = res["drifts"]["lambda_u"]
    bias = dd.LU - ru["median"]["value"]
    # The slow bins' ratios carry -0.31 sigma / u_s (about -0.4): the median lands low.
    check(bias >= 0.03, f"lambda_u: the ratio median {ru['median']['value']:.4f} is biased low by "
                        f"{bias:.4f} >= 0.03, while wls is off by "
                        f"{abs(ru['wls']['value'] - dd.LU):.4f}")
    check(ru["median"]["p84"] < dd.LU, f"lambda_u: the median's 16-84 % interval "
                                       f"[{ru['median']['p16']:.4f}, {ru['median']['p84']:.4f}] "
                                       f"excludes the true {dd.LU}")
    # The flux-consistent estimator, sum alpha_f u_f / sum alpha_f u_s (alpha_f uniform here):
    # unbiased, SE = sigma sqrt(n) / sum u_s.
    se = dd.SIGMA_U * math.sqrt(n) / float(np.sum(t["us"]))
    v = ru["flux"]["value"]
    check(abs(v - dd.LU) <= 4 * se, f"lambda_u: flux {v:.4f} recovers {dd.LU} within 4 SE = "
                                    f"{4 * se:.4f} (off by {abs(v - dd.LU):.4f})")
    fu, fw = ru["fit"], res["drifts"]["lambda_w"]["fit"]
    check(fu["well_posed"] and fu["r2"] >= 0.9 and fw["well_posed"] and fw["r2"] >= 0.9,
          f"wls: lambda_u and lambda_w well-posed, R^2 {fu['r2']:.3f} and {fw['r2']:.3f} >= 0.9")
    check(fu["r2_additive_slip"] < fu["r2"], f"lambda_u: the multiplicative drift fits better "
          f"than an additive slip (R^2 {fu['r2']:.3f} against {fu['r2_additive_slip']:.3f})")
    # w_s of both signs: the net vertical solid flux nearly cancels, so flux's lambda_w is
    # ill-posed, and --vertical auto writes the isotropic drift, between LW and LU.
    resf = cd.calibrate(case, estimator="flux", vertical="auto", n_boot=200, pressure=LAMBDA_P)
    rw = resf["drifts"]["lambda_w"]
    share = rw["fit"]["solid_flux_net_share"]
    check(not rw["fit"]["well_posed"] and share < cd.FLUX_CANCEL_MIN,
          f"flux: lambda_w ill-posed, net vertical solid flux {share:.3f} of its magnitude "
          f"< {cd.FLUX_CANCEL_MIN:g} ({'; '.join(rw['fit']['ill_posed_because'])})")
    iso = rw["vertical"]["isotropic_value"]
    check(rw["vertical"]["used"] == "isotropic" and rw["value"] == iso and dd.LW < iso < dd.LU,
          f"--vertical auto: lambda_w written {rw['value']:.4f} = the isotropic drift, between "
          f"{dd.LW} and {dd.LU} (fit {rw['vertical']['fit_value']:.4f} not used)")
    resw = cd.calibrate(case, vertical="auto", n_boot=200, pressure=LAMBDA_P)
    check(resw["drifts"]["lambda_w"]["vertical"]["used"] == "fit",
          "wls with --vertical auto keeps the well-posed lambda_w fit")
    # The mass balance with the data's own fluxes, differenced here, equals the extractor's
    # mass_balance_residual / _scale (mixture_extract/DriftCoefficients.cpp) over the same bins.
    mres, mscale = f["mass_balance_residual"], f["mass_balance_scale"]
    ok = np.isfinite(mres) & np.isfinite(mscale)
    ext = float(np.sqrt(np.mean(mres[ok] ** 2)) / np.sqrt(np.mean(mscale[ok] ** 2)))
    mb = res["mass_balance"]
    check(mb["bins"] == int(ok.sum()) and abs(mb["data_residual_over_scale"] - ext) <= 1e-9 * ext,
          f"mass balance of the data: {mb['data_residual_over_scale']:.6f} over {mb['bins']} bins "
          f"= the extractor's {ext:.6f} over {int(ok.sum())}")
    sel = res["selection"]
    check(abs(sel["flowing_speed_m_s"] - 0.05 * math.sqrt(9.81 * 0.12)) < 1e-12,
          f"flowing threshold 0.05 sqrt(g H) = {sel['flowing_speed_m_s']:.5f} m/s (H 0.12 m)")

    # A flowing factor of 0.1 (0.1085 m/s) drops the slow bins (u_s <= 0.10 m/s) and only them.
    res2 = cd.calibrate(case, flowing_factor=0.1, n_boot=100, pressure=LAMBDA_P)
    speed = np.hypot(t["us"], t["ws"])
    fast = int(np.sum(speed >= 0.1 * math.sqrt(9.81 * 0.12)))
    check(res2["drifts"]["lambda_u"]["samples"] == fast,
          f"--flowing-factor 0.1 keeps the {fast} bins of solid speed >= 0.1085 m/s "
          f"(got {res2['drifts']['lambda_u']['samples']})")
    # Windows 0.04-0.12 s hold windows 2..5 (of 0.02 s): 4 x 64 samples.
    res3 = cd.calibrate(case, windows=(0.04, 0.12), n_boot=100, pressure=LAMBDA_P)
    check(res3["drifts"]["lambda_u"]["samples"] == 4 * 64 and
          res3["selection"]["windows_used"] == [0.04, 0.12],
          f"--windows 0.04:0.12: 4 windows, 256 samples (got "
          f"{res3['drifts']['lambda_u']['samples']}, {res3['selection']['windows_used']})")

    # The command end to end into a bulk case.
    target = os.path.join(work, "bulk_case")
    os.makedirs(os.path.join(target, "constant"), exist_ok=True)
    bp = os.path.join(target, "constant", "bulkProperties")
    if os.path.exists(bp):
        os.remove(bp)
    r = subprocess.run(command("calibrate-drifts") + [case, "--pressure", LAMBDA_P,
                        "--target", target], capture_output=True, text=True)
    print(r.stdout + r.stderr)
    check(r.returncode == 0, f"calibrate_drifts.py exits 0 (got {r.returncode})")
    d = read_dict(bp)["drifts"]
    for q, key in (("lambda_u", "lambdaU"), ("lambda_w", "lambdaW"), ("lambda_p", "lambdaP")):
        v = res["drifts"][q]["wls"]["value"]
        check(abs(float(d[key]) - v) <= 1e-5 * abs(v),
              f"bulkProperties drifts.{key} {d[key]} = the wls estimate {v:.6g} (6 digits)")
    src = unquote(d["source"])
    check(cd.sha256(h5) in src and "estimator wls" in src and "windows 0-0.12 s" in src,
          f"drifts.source records the h5, its sha256, estimator and windows: {src}")
    with open(bp + ".calibration.json") as fj:
        j = json.load(fj)
    check(abs(j["drifts"]["lambda_u"]["value"] - res["drifts"]["lambda_u"]["value"]) < 1e-12 and
          j["sha256"] == cd.sha256(h5),
          "the JSON next to bulkProperties holds the same estimates and fingerprint")
    print(f"{len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
