"""The calibration's round trip through the bulk model's own conventions: a coarse, short bulk run
of W+P (run A) with prescribed drift fields that vary in space (lambda_u(x), lambda_w(y), chi(x,
y), bulkProperties drifts { fields on; pressure porePressureRatio; }) is turned into synthetic
particles and fluid cells (synthcase.bin_field_case, one bin per bulk cell, one window per field
write), extracted by mixflowExtract, calibrated back onto the same mesh by `mixflow
calibrate-drifts --fields --pressure porePressureRatio`, and run again (run B, chi over the
bulk model's reference, --pore-reference mixture; run C, over the extractor's liquid surface,
--pore-reference surface).

What the synthetic data carry comes from the fields run A writes (apps/mixflowBulkFoam/
writeBulkFields.H), each as the CFD-DEM quantity the extractor reads:
  particles: velocity U.solid; contact stress per bulk volume sigma' = alpha_s (P_s - P_f) (the
             closure's P_s = P_f + sigma' / alpha_s), dumped as the LIGGGHTS per-particle virial;
  fluid:     velocity U.fluid, pressure P_f (p.fluid, Pa), liquid share alpha.liquid, air (p 0)
             above; a bin holds grains where alpha.liquid >= 0.5 (the solver's `inside`).
Asserted: in run B lambda_u, lambda_w and chi come back exactly (to 1e-9) in every cell whose
bin has a flowing sample (the data carry no noise, so no interval is needed); run B's front
within 1 % of run A's at every write, its surface h(x, t) within 1 % of the sample height. Run
C's chi misses by more than CHI_MISS per cell and its h(x, t) by more than 1 %: the extractor's
hydrostatic rho_f g (h_l - y) is not the bulk model's rho_f p_m in a flow (p_m / g (h_l - y) is
printed), and the test tells the two apart.

usage: test_round_trip.py BINDIR WORKDIR [--json FILE]  (FILE: the report, also printed; the
results/bulk_model/round_trip.json of results/bulk_model/README.md)"""
import json
import os
import shutil
import subprocess
import sys

import numpy as np

from mixflow import ROOT, bulkprops, foamcase, foamdict, outputs, synthcase
from mixflow.cli import command
from mixflow.commands import calibrate_drifts as cd
from mixflow.commands.calibrate import make_bulk_case
from mixflow.commands.mixture_lambdas import load, quantiles
from mixflow.synthcase import checker

SCENE = os.path.join(ROOT, "cases", "W+P")
CELL, END, WRITE = 0.06, 0.5, 0.05  # m, s, s: 98 x 20 cells; run A about 5 s
ROWS = 14  # grid rows (0.84 m): the mixture (0.6 m) and air above it
FLOWING = 0.005  # --flowing-factor: 0.012 m/s, so that nearly every moving bin is sampled
FRONT_TOL, H_TOL = 0.01, 0.01  # run B against run A: front relative, h(x, t) / sample height
H = 0.6  # m, W+P's sample height
CHI_MISS = 0.05  # run C's chi off by more than this per cell on average


def prescribed(x, y):
    """The drift fields of run A at cell centres (x, y) (m)."""
    return {"lambdaU": 1.15 + 0.25 * np.sin(np.pi * x / 1.8), "lambdaW": 0.9 + 0.3 * y / 0.6,
            "porePressureRatio": 0.35 - 0.2 * np.cos(np.pi * x / 1.8) - 0.1 * y / 0.6}


def field_text(name, values):
    return (foamcase.foam_header("volScalarField", name, "constant")
            + "// prescribed for the round trip (tests/bulk/test_round_trip.py)\n"
            "dimensions [0 0 0 0 0 0 0];\n\ninternalField " + foamcase.format_scalar_list(values)
            + "\n;\n\nboundaryField\n{\n    \".*\" { type zeroGradient; }\n"
            "    #includeEtc \"caseDicts/setConstraintTypes\"\n}\n")


def bulk_case(case):
    """W+P as the bulk model at CELL m to END s, written every WRITE s, its mesh made."""
    make_bulk_case(SCENE, case, CELL, END)
    foamcase.set_entry(os.path.join(case, "system", "controlDict"), "writeInterval", repr(WRITE))
    foamcase.run_tool(["mixflowPrepare", "-case", case], "test_round_trip")
    foamcase.run_tool(["blockMesh", "-case", case], "test_round_trip")
    return np.array(foamcase.cell_centres(case))


def run(case):
    foamcase.run_tool(["./Allrun", "1"], "test_round_trip", cwd=case)


def grid_shape(centres):
    """(nx, ny, dx, dy) of the uniform blockMesh: cell index j nx + i."""
    xs, ys = np.unique(np.round(centres[:, 0], 9)), np.unique(np.round(centres[:, 1], 9))
    nx, ny = xs.size, ys.size
    assert nx * ny == len(centres)
    ij = np.rint((centres[:, 0] - xs[0]) / (xs[1] - xs[0])) + nx * np.rint(
        (centres[:, 1] - ys[0]) / (ys[1] - ys[0]))
    assert np.array_equal(ij, np.arange(len(centres))), "cells not in j nx + i order"
    return nx, ny, float(xs[1] - xs[0]), float(ys[1] - ys[0])


def written(case, nx, ny):
    """Per field write after 0: alpha.liquid, U.solid, U.fluid, p.solid, p.fluid as (ROWS, nx)."""
    n = nx * ny
    out = []
    for t, name in sorted((t, name) for t, name in foamcase.time_dirs(case) if t > 0):
        d = os.path.join(case, name)

        def scalar(f):
            v = foamcase.read_internal_field(os.path.join(d, f), n)
            return np.array(v).reshape(ny, nx)[:ROWS]

        def vector(f):
            return np.array(foamcase.read_internal_field(os.path.join(d, f), n))[:, :2].reshape(
                ny, nx, 2)[:ROWS]
        out.append({"t": t, "alpha": scalar("alpha.liquid"), "us": vector("U.solid"),
                    "uf": vector("U.fluid"), "ps": scalar("p.solid"), "pf": scalar("p.fluid")})
    return out


def synthetic(case, fields, dx, dy, rho_s, rho_f, channel, stress):
    """The CFD-DEM stand-in of run A's FIELDS (synthcase.bin_field_case), extracted. STRESS(w):
    the contact stress per bulk volume the particles dump, from one write's fields."""
    def stack(f):
        return np.stack([f(w) for w in fields])
    synthcase.bin_field_case(
        case, stack(lambda w: w["us"][..., 0]), stack(lambda w: w["us"][..., 1]), stack(stress),
        stack(lambda w: w["uf"][..., 0]), stack(lambda w: w["uf"][..., 1]),
        stack(lambda w: w["pf"]), dx=dx, dy=dy, window=WRITE, start=fields[0]["t"] - WRITE / 2,
        H=H, rho_s=rho_s, rho_f=rho_f, liquid=stack(lambda w: w["alpha"]), channel=channel)
    exe = os.path.join(os.environ["MIXFLOW_BUILD"], "bin", "mixflowExtract")
    r = subprocess.run([exe, "-case", case], capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"mixflowExtract failed on {case}:\n{r.stdout[-3000:]}{r.stderr[-3000:]}")
    return os.path.join(case, cd.H5_IN_CASE)


def sampled_cells(h5, key, alpha_s, reference):
    """Bins (ROWS, nx) that have a sample of the drift KEY in the calibration's selection
    (calibrate_drifts.calibrate with the test's options)."""
    res = cd.calibrate(h5, flowing_factor=FLOWING, n_boot=10, pressure="porePressureRatio",
                       solid_fraction=alpha_s, pore_reference=reference)
    q = next(q for q, v in cd.DRIFTS.items() if v[0] == key)
    return res["_samples"][q]["mask"].any(axis=0)


def series(case):
    return outputs.read_rows(os.path.join(case, "postProcessing", "liquid", "timeSeries.csv"))


def profiles(case):
    """{time: (x, surface)} of postProcessing/liquid/profiles.csv."""
    rows = outputs.read_rows(os.path.join(case, "postProcessing", "liquid", "profiles.csv"))
    out = {}
    for r in rows:
        out.setdefault(round(r["time_s"], 9), []).append((r["x_m"], r["surface_m"]))
    return {t: np.array(v) for t, v in out.items()}


def main():
    bindir, work = sys.argv[1], os.path.abspath(sys.argv[2])
    json_out = (os.path.abspath(sys.argv[4]) if len(sys.argv) > 4 and sys.argv[3] == "--json"
                else None)
    os.environ["MIXFLOW_BUILD"] = os.path.dirname(os.path.abspath(bindir))
    failures = []
    check = checker(failures)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)

    # Run A: the prescribed drift fields.
    a = os.path.join(work, "A")
    centres = bulk_case(a)
    nx, ny, dx, dy = grid_shape(centres)
    truth = prescribed(centres[:, 0], centres[:, 1])
    for key, v in truth.items():
        bulkprops.write_text(os.path.join(a, "constant", key), field_text(key, v))
    bulkprops.write_text(bulkprops.path(a), bulkprops.block_text(
        bulkprops.path(a), "drifts", {"pressure": "porePressureRatio", "fields": "on"}))
    run(a)
    scene = foamdict.read_dict(os.path.join(a, "constant", "sceneProperties"))
    alpha_s = float(scene["sample"]["solidFraction"].split()[0])
    rho_s = float(scene["particles"]["density"].split()[0])
    rho_f = float(scene["liquid"]["density"].split()[0])
    fields = written(a, nx, ny)
    check(len(fields) == round(END / WRITE), f"run A: {len(fields)} field writes")
    top = max(float(np.max(np.where(w["alpha"] > 1e-3, 1, 0) * (np.arange(ROWS)[:, None] + 1)))
              for w in fields)
    check(top < ROWS, f"the mixture stays below the grid's top row ({top:g} of {ROWS} rows)")

    # The stand-in CFD-DEM case: the grains' contact stress sigma' = alpha_s (P_s - P_f).
    dem = os.path.join(work, "dem")
    channel = tuple(float(scene["channel"][k].split()[0]) for k in ("length", "height"))
    h5 = synthetic(dem, fields, dx, dy, rho_s, rho_f, channel,
                   lambda w: alpha_s * (w["ps"] - w["pf"]))

    # The extractor's hydrostatic (liquid surface) against the bulk model's rho_f p_m: p_m
    # = p_total / rho_m over g (h_l - y) in the mixture bins.
    d = load(h5)
    f = d["fields"]
    rho_m = alpha_s * rho_s + (1 - alpha_s) * rho_f
    mixed = (np.isfinite(f["p_f_hydrostatic"]) & np.isfinite(f["p_total"]) & (f["alpha_s"] > 0.1)
             & (f["p_f_hydrostatic"] > 0))
    share = (f["p_total"] / rho_m / (f["p_f_hydrostatic"] / rho_f))[mixed]
    report = {"p_m_over_g_h": quantiles(share), "runs": {}}
    print(f"p_m / g (h_l - y) over {share.size} mixture bins: {report['p_m_over_g_h']}")

    # Run B: calibrated onto the same mesh with chi over the bulk model's reference; run C over
    # the extractor's liquid surface.
    for label, reference in (("B", "mixture"), ("C", "surface")):
        case = os.path.join(work, label)
        report["runs"][label] = rec = calibrated_run(check, case, dem, h5, reference, truth,
                                                     centres, nx, ny, alpha_s, a)
        if rec is None:
            return 1
    b, c = report["runs"]["B"], report["runs"]["C"]
    for key in ("lambdaU", "lambdaW", "porePressureRatio"):
        e = b["drifts"][key]["max_abs_error"]
        check(e <= 1e-9, f"B: {key}: every cell of a sampled bin exact (max |diff| {e:.2e} "
              "<= 1e-9: the synthetic data carry no noise)")
    check(b["front_error"] <= FRONT_TOL, f"B: front against run A at every {WRITE:g} s: max "
          f"relative difference {b['front_error']:.2e} (<= {FRONT_TOL:g})")
    check(b["h_error_m"] <= H_TOL * H, f"B: h(x, t): max |h_B - h_A| {b['h_error_m']:.3g} m "
          f"(<= {H_TOL:g} x {H:g} m)")
    e = c["drifts"]["porePressureRatio"]["mean_abs_error"]
    check(e > CHI_MISS and c["h_error_m"] > H_TOL * H,
          f"C (the surface reference, not the bulk model's): chi misses by {e:.3g} per cell on "
          f"average (> {CHI_MISS:g}), h(x, t) by {c['h_error_m']:.3g} m (> {H_TOL:g} x {H:g} m): "
          "the round trip tells the conventions apart")
    report["passes"] = not failures
    print(json.dumps(report, indent=1))
    if json_out:
        outputs.write_json(json_out, report)
    print("PASS" if not failures else f"FAIL: {len(failures)} checks")
    return 1 if failures else 0


def calibrated_run(check, case, dem, h5, reference, truth, centres, nx, ny, alpha_s, a):
    """CASE: the bulk case calibrated from DEM with --pore-reference REFERENCE, run and compared
    with run A: per drift the cells of sampled bins against TRUTH, the front and h(x, t)."""
    bulk_case(case)
    cmd = command("calibrate-drifts") + [
        dem, "--target", case, "--fields", "--pressure", "porePressureRatio", "--field-mean",
        "wls", "--pore-reference", reference, "--flowing-factor", str(FLOWING), "--bootstrap",
        "200"]
    r = subprocess.run(cmd, capture_output=True, text=True)
    print(r.stdout + r.stderr)
    check(r.returncode == 0, f"calibrate-drifts --fields --pore-reference {reference} exits 0 "
          f"(got {r.returncode})")
    if r.returncode != 0:
        return None
    rec = {"pore_reference": reference, "drifts": {}}
    for key in truth:
        got = np.array(foamcase.read_internal_field(os.path.join(case, "constant", key)))
        sampled = np.zeros(nx * ny, bool)
        sampled[:ROWS * nx] = sampled_cells(h5, key, alpha_s, reference).ravel()
        err = np.abs(got - truth[key])[sampled]
        rec["drifts"][key] = {"cells_sampled": int(sampled.sum()),
                              "max_abs_error": float(err.max()),
                              "mean_abs_error": float(err.mean())}
    run(case)
    fa, fb = series(a), series(case)
    rec["front_error"] = max(
        abs(outputs.interpolated(fb, "front_bed_m", k * WRITE) /
            outputs.interpolated(fa, "front_bed_m", k * WRITE) - 1)
        for k in range(1, round(END / WRITE) + 1))
    pa, pb = profiles(a), profiles(case)
    rec["h_error_m"] = max(float(np.max(np.abs(pa[t][:, 1] - pb[t][:, 1]))) for t in pa)
    return rec


if __name__ == "__main__":
    sys.exit(main())
