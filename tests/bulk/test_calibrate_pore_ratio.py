"""calibrate_drifts.py --pressure porePressureRatio on a synthetic extraction with a known
pore-pressure ratio chi: drift_data.py's bins with a gas row on top (the liquid surface at the
grains' top edge, gas at P_GAS) and a pore pressure p_f = P_GAS + rho_f g (h - y) + e, e = chi/(1 -
chi) p_s, so that the extractor's p_f_excess / (p_s + p_f_excess) is chi in every bin. Checks: the
extractor's p_f_excess and pore_pressure_ratio against the prescribed ones (1e-9 relative: the
bins are exact), both estimators return chi (1e-9: no noise on the pressures), the target gets
`pressure porePressureRatio; porePressureRatio chi;`, a target holding lambdaP is refused, and a chi outside [-10, 1) is refused, nothing written.
The calibrations take the extractor's ratio (--pore-reference surface): the bins' p_s is not the
weight above them, so the bulk model's reference (mixture) would not give chi here
(test_round_trip.py checks that one).

usage: test_calibrate_pore_ratio.py MIXFLOWEXTRACT WORKDIR"""
import os
import shutil
import subprocess
import sys

import numpy as np

from mixflow import synthcase
from mixflow.commands import calibrate_drifts as cd  # noqa: E402
import drift_data as dd  # noqa: E402
from mixflow.commands.mixture_lambdas import load  # noqa: E402
from mixflow.foamdict import read_dict  # noqa: E402
from mixflow.synthcase import checker  # noqa: E402

CHI, P_GAS, G = 0.3, -5.0, 9.81  # ratio; gas pressure above the surface (a gauge offset), Pa
DY = 0.05  # synthcase.bin_field_case's bin height


def make(case, exe, chi):
    """The synthetic case with ratio CHI in every bin, extracted; returns (truth, excess)."""
    t = dd.truth()
    ny = t["ps"].shape[1]
    y = (np.arange(ny) + 0.5) * DY
    excess = chi / (1 - chi) * t["ps"]
    pf = P_GAS + dd.RHO_F * G * (ny * DY - y)[None, :, None] + excess
    synthcase.bin_field_case(case, t["us"], t["ws"], t["ps"], t["uf"], t["wf"], pf,
                             rho_s=dd.RHO_S, rho_f=dd.RHO_F, gas_pressure=P_GAS)
    r = subprocess.run([exe, "-case", case], capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"mixflowExtract failed on {case}:\n{r.stdout[-3000:]}{r.stderr[-3000:]}")
    return t, excess


def main():
    exe, work = sys.argv[1], sys.argv[2]
    failures = []
    check = checker(failures)
    shutil.rmtree(work, ignore_errors=True)
    case = os.path.join(work, "dem_case")
    t, excess = make(case, exe, CHI)
    f = load(os.path.join(case, cd.H5_IN_CASE))["fields"]
    ny = t["ps"].shape[1]
    e = f["p_f_excess"][:, :ny, :]
    err = float(np.max(np.abs(e - excess) / np.abs(excess)))
    check(err < 1e-9, f"p_f_excess = the prescribed excess: max rel. diff {err:.2e} < 1e-9")
    chi = f["pore_pressure_ratio"][:, :ny, :]
    err = float(np.max(np.abs(chi - CHI)))
    check(err < 1e-9, f"pore_pressure_ratio = {CHI} in every bin: max |diff| {err:.2e} < 1e-9")

    res = cd.calibrate(case, pressure="porePressureRatio", pore_reference="surface")
    r = res["drifts"]["pore_pressure_ratio"]
    for est in cd.ESTIMATORS:
        check(abs(r[est]["value"] - CHI) < 1e-9,
              f"{est} estimate {r[est]['value']:.12g} = {CHI} (1e-9)")
    check(set(res["drifts"]) == {"lambda_u", "lambda_w", "pore_pressure_ratio"},
          f"calibrated: {sorted(res['drifts'])}")

    target = os.path.join(work, "bulk")
    os.makedirs(os.path.join(target, "constant"))
    cd.write_target(target, res, case)
    d = read_dict(os.path.join(target, "constant", "bulkProperties"))["drifts"]
    check(d.get("pressure") == "porePressureRatio" and abs(float(d["porePressureRatio"]) - CHI)
          < 1e-5 and "lambdaP" not in d,
          f"bulkProperties drifts: pressure {d.get('pressure')}, porePressureRatio "
          f"{d.get('porePressureRatio')}, no lambdaP")

    # A target whose drifts hold the other closure's entry: refused, nothing written.
    other = os.path.join(work, "bulk_lambdaP")
    os.makedirs(os.path.join(other, "constant"))
    bp = os.path.join(other, "constant", "bulkProperties")
    with open(bp, "w") as fh:
        fh.write("drifts { lambdaP 1.2; }\n")
    try:
        cd.write_target(other, res, case)
        check(False, "a target with drifts.lambdaP refused")
    except cd.InputError as exc:
        check("drifts.lambdaP" in str(exc) and "nothing written" in str(exc),
              f"a target with drifts.lambdaP refused: {exc}")
    with open(bp) as fh:
        check(fh.read() == "drifts { lambdaP 1.2; }\n", "its bulkProperties unchanged")

    # chi = 1.5 (e = -3 p_s: the grains' load p_s + e negative): outside [-10, 1).
    case3 = os.path.join(work, "dem_case_out_of_range")
    make(case3, exe, 1.5)
    res3 = cd.calibrate(case3, pressure="porePressureRatio", pore_reference="surface")
    v = res3["drifts"]["pore_pressure_ratio"]["value"]
    bad = os.path.join(work, "bulk_out_of_range")
    os.makedirs(os.path.join(bad, "constant"))
    try:
        cd.write_target(bad, res3, case3)
        check(False, f"chi {v:.4g} refused")
    except cd.InputError as exc:
        check("porePressureRatio" in str(exc) and "[-10, 1)" in str(exc),
              f"chi {v:.4g} refused: {exc}")
    check(not os.path.exists(os.path.join(bad, "constant", "bulkProperties")), "nothing written")

    print(f"{len(failures)} failed")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
