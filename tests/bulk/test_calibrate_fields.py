"""calibrate_drifts.py --fields on the synthetic extraction of drift_data.py: the drift fields
written on a target mesh hold, in every cell, the weighted time mean over the selected windows of
the ratios of the bin holding its centre (recomputed here from the extraction), the constant
estimate where the bin has no selected window or the cell lies outside the grid, clipped into the
bulk model's range with the count reported; bulkProperties gets `fields on;` and the source.
--per-window: one set per window inside --windows in constant/drifts/<centre>/, every cell of every
window equal to its bin's value recomputed from that window's samples alone (with --window-span 3
from the 3 windows centred on it) (the constant, the
clip and their counts as above, per window); bulkProperties gets `timeVarying on;`, which a later
fixed-field calibration sets off.

usage: test_calibrate_fields.py MIXFLOWEXTRACT BLOCKMESH WORKDIR"""
import json
import os
import subprocess
import sys

import numpy as np

from mixflow.cli import command  # noqa: E402
from mixflow.commands import calibrate_drifts as cd  # noqa: E402
import drift_data as dd  # noqa: E402
from mixflow import foamcase  # noqa: E402
from mixflow.foamdict import read_dict, unquote  # noqa: E402
from mixflow.synthcase import checker  # noqa: E402
from mixflow.commands.mixture_lambdas import load  # noqa: E402

# + [CASE, ...]: the command the test runs, with the lambda_p closure whose fields it recomputes
CALIBRATE = command("calibrate-drifts") + ["--pressure", "lambdaP"]

NX, NY, LX, LY = 40, 12, 1.0, 0.3  # 0.025 m cells over the 0.8 x 0.2 m grid and beyond it
FLOWING = 0.1  # 0.108 m/s: drops the slow bins (u_s 0.06-0.10), leaving some bins without a value
# (label, --windows, alpha_s of the target): the windows 0-0.06 s (3) leave one bin without a
# flowing window; alpha_s 0.005 makes the range lambda >= 0.005025 (alpha_s + lambda alpha_f >=
# 0.01), which the single window 0-0.02 s crosses in some bins (lambda_u down to -0.03).
# --field-mean wls: per bin sum_t w x y / sum_t w x^2 instead of the ratios' mean; flux: per bin
# sum_t w alpha_f y / sum_t w alpha_f x (the pressure drift without alpha_f).
RUNS = (("time mean, fallback", "0:0.06", 0.6, "ratio"), ("clipped", "0:0.02", 0.005, "ratio"),
        ("wls per bin", "0:0.06", 0.6, "wls"), ("flux per bin", "0:0.06", 0.6, "flux"))


def target_case(case, blockmesh, alpha):
    foamcase.write_foam_file(case, "system/controlDict", "dictionary", "controlDict",
                             "application mixflowBulkFoam;\nstartTime 0;\nendTime 1;\n"
                             "deltaT 1;\nwriteInterval 1;\n")
    foamcase.write_foam_file(case, "system/blockMeshDict", "dictionary", "blockMeshDict", f"""\
scale 1;
vertices ((0 0 0) ({LX} 0 0) ({LX} {LY} 0) (0 {LY} 0)
          (0 0 0.1) ({LX} 0 0.1) ({LX} {LY} 0.1) (0 {LY} 0.1));
blocks (hex (0 1 2 3 4 5 6 7) ({NX} {NY} 1) simpleGrading (1 1 1));
edges ();
boundary
(
    walls {{ type wall; faces ((0 4 7 3) (1 2 6 5) (0 1 5 4)); }}
    atmosphere {{ type patch; faces ((3 7 6 2)); }}
    frontAndBack {{ type empty; faces ((0 3 2 1) (4 5 6 7)); }}
);
""")
    foamcase.write_foam_file(case, "constant/bulkProperties", "dictionary", "bulkProperties",
                             f"solidFraction {alpha};\n")
    r = subprocess.run([blockmesh, "-case", case], capture_output=True, text=True,
                       env=foamcase.run_env())
    if r.returncode != 0:
        sys.exit(f"blockMesh failed:\n{r.stdout[-2000:]}{r.stderr[-2000:]}")


def expected(h5, constants, windows, how):
    """Per drift the cell values recomputed from the extraction: the wls selection (valid mask,
    alpha_s >= 0.1, for the velocity drifts solid speed >= FLOWING sqrt(g H) (the pressure drift
    takes every bin: --pressure-bins all), particle-equivalent weights), per bin
    sum_t w lambda / sum_t w, looked up at the cell centres of the uniform target mesh."""
    d = load(h5)
    f, valid, w = d["fields"], d["valid"], d["counts"]["particle_equivalents"]
    H = float(d["attrs"]["sample_height_m"])
    t0, t1 = (float(v) for v in windows.split(":"))
    win = (d["windows"]["t0"] >= t0 - 1e-9) & (d["windows"]["t1"] <= t1 + 1e-9)
    dense = win[:, None, None] & (f["alpha_s"] >= 0.1)
    flowing = dense & (np.hypot(f["u_s"], f["w_s"]) >= FLOWING * np.sqrt(9.81 * H))
    pairs = {"lambda_u": (f["u_s"], f["u_f"], valid["lambda_u"]),
             "lambda_w": (f["w_s"], f["w_f"], valid["lambda_w"]),
             "lambda_p": (f["p_s"] / dd.RHO_S, f["p_f"] / dd.RHO_F, valid["lambda_p_density"])}
    xc = (np.arange(NX) + 0.5) * LX / NX
    yc = (np.arange(NY) + 0.5) * LY / NY
    out, bins = {}, {}
    for q, (xs, ys, v) in pairs.items():
        r = ys / xs
        m = (dense if q == "lambda_p" else flowing) & v & np.isfinite(r) & (w > 0)
        if how == "wls":
            num = np.where(m, w * xs * ys, 0).sum(axis=0)
            den = np.where(m, w * xs * xs, 0).sum(axis=0)
        elif how == "flux":
            a = w * (f["alpha_f"] if q != "lambda_p" else 1.0)
            num = np.where(m, a * ys, 0).sum(axis=0)
            den = np.where(m, a * xs, 0).sum(axis=0)
            den = np.where(den != 0, den, np.nan)  # negative where the bin moves back
        else:
            num = np.where(m, w * np.nan_to_num(r), 0).sum(axis=0)
            den = np.where(m, w, 0).sum(axis=0)
        mean = num / np.where(den != 0, den, np.nan)
        cells = np.empty(NX * NY)
        for j in range(NY):
            for i in range(NX):
                bi, bj = int(xc[i] // 0.05), int(yc[j] // 0.05)
                inside = bi < mean.shape[1] and bj < mean.shape[0]
                val = mean[bj, bi] if inside else np.nan
                cells[j * NX + i] = val if np.isfinite(val) else constants[q]
        out[q], bins[q] = cells, int(np.isnan(mean).sum())
    return out, bins


def calibrate(check, case, target, label, args):
    """calibrate_drifts.py CASE --target TARGET --fields ARGS; exits on failure. Returns the
    command, its stdout and the JSON written."""
    cmd = CALIBRATE + [case,
           "--target", target, "--fields", "--flowing-factor", str(FLOWING), "--bootstrap",
           "50"] + args
    r = subprocess.run(cmd, capture_output=True, text=True)
    print(r.stdout + r.stderr)
    check(r.returncode == 0, f"{label}: calibrate_drifts.py --fields exits 0 (got {r.returncode})")
    if r.returncode != 0:
        sys.exit(1)
    with open(os.path.join(target, "constant", "bulkProperties.calibration.json")) as f:
        return cmd, r.stdout, json.load(f)


def check_cells(check, label, key, path, want, lo):
    """The cell values of the field PATH against WANT clipped to [LO, 1000]; returns the count
    of cells the clip moves."""
    got = np.array(foamcase.read_internal_field(path))
    check(got.size == NX * NY, f"{label}: {key}: {got.size} cell values ({NX * NY} cells)")
    clip = np.clip(want, lo, 1e3)
    err = float(np.max(np.abs(got - clip)))
    check(err <= 1e-12 * max(1.0, float(np.max(np.abs(clip)))),
          f"{label}: {key}: every cell equals its recomputed value clipped to [{lo:.4g}, 1000]: "
          f"max |diff| {err:.2e} (<= 1e-12 relative)")
    return int(((want < lo) | (want > 1e3)).sum())


def run_per_window(check, work, case, h5, blockmesh):
    """--fields --per-window over windows 0-0.06 s (3 of 0.02 s) at alpha_s 0.005 (the clip's
    range, crossed by single windows' bins): per window and drift every cell against its bin's
    value from that window alone; then a fixed-field calibration of the same target sets
    timeVarying off."""
    alpha, how, label = 0.005, "wls", "per window"
    lo = (0.01 - alpha) / (1 - alpha)
    target = os.path.join(work, "bulk_target_per_window")
    target_case(target, blockmesh, alpha)
    cmd, out, j = calibrate(check, case, target, label, ["--windows", "0:0.06", "--per-window"])
    consts = {q: j["drifts"][q]["value"] for q in j["drifts"]}  # the drifts calibrated
    series = os.path.join(target, "constant", "drifts")
    names = sorted(os.listdir(series), key=float)
    check(names == ["0.01", "0.03", "0.05"], f"{label}: window directories {names} (the centres "
          "of the 3 windows inside 0-0.06 s)")
    clipped = empty = 0
    for name in names:
        t = float(name)
        span = f"{t - 0.01:.10g}:{t + 0.01:.10g}"
        want, empty_bins = expected(h5, consts, span, how)
        for q, (key, *_) in ((q, cd.DRIFTS[q]) for q in consts):
            path = os.path.join(series, name, key)
            n_clip = check_cells(check, f"{label} {name} s", key, path, want[q], lo)
            fj = next(w for w in j["fields"][key]["windows"] if w["time"] == name)
            check(fj["clipped_cells"] == n_clip and
                  fj["fallback_cells"] == NX * NY - 32 * 8 + 4 * empty_bins[q],
                  f"{label} {name} s: {key}: {fj['clipped_cells']} cells reported clipped "
                  f"({n_clip} recomputed), {fj['fallback_cells']} the constant (outside the grid "
                  f"and 4 in each of the {empty_bins[q]} bins without a sample)")
            with open(path) as f:
                text = f.read()
            check(cd.sha256(h5) in text and f"window {t - 0.01:g}-{t + 0.01:g} s" in text and
                  f'location    "constant/drifts/{name}"' in text,
                  f"{label} {name} s: {key}: header records the sha256, the window and location")
            clipped += n_clip
            empty += empty_bins[q]
    check(clipped > 0 and empty > 0, f"{label}: the clip ({clipped} cells) and the fallback "
          f"({empty} empty bins) are exercised")
    for key in ("lambdaU", "lambdaW", "lambdaP"):
        r = j["fields"][key]
        check(f"{key}: 3 windows, {r['cells']} cells" in out and r["cells"] == 3 * NX * NY,
              f"{label}: {key}: counts summed over the windows printed ({r['cells']} cells)")
    d = read_dict(os.path.join(target, "constant", "bulkProperties"))["drifts"]
    check(d.get("fields") == "on" and d.get("timeVarying") == "on",
          f"{label}: bulkProperties drifts {{ fields on; timeVarying on; }}: {d.get('fields')}, "
          f"{d.get('timeVarying')}")
    calibrate(check, case, target, "fixed after per window", ["--windows", "0:0.06"])
    d = read_dict(os.path.join(target, "constant", "bulkProperties"))["drifts"]
    check(d.get("fields") == "on" and d.get("timeVarying") == "off",
          f"fixed fields after a per-window calibration: timeVarying {d.get('timeVarying')} "
          "(off: the earlier windows are no longer used)")
    r = subprocess.run(CALIBRATE + [case, "--target", target, "--per-window"],
                       capture_output=True, text=True)
    check(r.returncode == 2 and "--per-window: needs --fields" in r.stderr,
          f"--per-window without --fields: exit {r.returncode}; {r.stderr.strip()}")
    # --window-span 3: each window's cells from the samples of the 3 windows centred on it (2 at
    # the ends), i.e. the bin values recomputed over those windows together.
    label = "window span 3"
    _, _, j = calibrate(check, case, target, label,
                        ["--windows", "0:0.06", "--per-window", "--window-span", "3"])
    consts = {q: j["drifts"][q]["value"] for q in j["drifts"]}  # the drifts calibrated
    for name, pooled in (("0.01", "0:0.04"), ("0.03", "0:0.06"), ("0.05", "0.02:0.06")):
        want, _ = expected(h5, consts, pooled, how)
        for q, (key, *_) in ((q, cd.DRIFTS[q]) for q in consts):
            check_cells(check, f"{label} {name} s (windows {pooled} s)", key,
                        os.path.join(series, name, key), want[q], lo)
    for bad in ("2", "0"):
        r = subprocess.run(CALIBRATE + [case, "--target", target, "--fields", "--per-window",
                                      "--window-span", bad], capture_output=True, text=True)
        check(r.returncode == 2 and f"--window-span {bad}: allowed an odd integer >= 1" in r.stderr,
              f"--window-span {bad}: exit {r.returncode}; {r.stderr.strip()}")


def run(check, work, case, h5, blockmesh, label, windows, alpha, how):
    """calibrate_drifts.py --fields onto a fresh target; checks every cell. Returns the counts."""
    lo = (0.01 - alpha) / (1 - alpha)  # alpha_s + lambda alpha_f >= 0.01
    target = os.path.join(work, "bulk_target_" + label.replace(" ", "_").replace(",", ""))
    target_case(target, blockmesh, alpha)
    cmd, stdout, j = calibrate(check, case, target, label,
                               ["--windows", windows, "--field-mean", how])
    consts = {q: j["drifts"][q]["value"] for q in j["drifts"]}  # the drifts calibrated
    want, empty_bins = expected(h5, consts, windows, how)
    clipped = 0
    for q, (key, *_) in ((q, cd.DRIFTS[q]) for q in consts):
        path = os.path.join(target, "constant", key)
        n_clip = check_cells(check, f"{label} ({how} mean; the constant {consts[q]:.5g} outside "
                             f"the grid and in the {empty_bins[q]} bins without a selected "
                             "window)", key, path, want[q], lo)
        fj = j["fields"][key]
        clipped += fj["clipped_cells"]
        check(fj["clipped_cells"] == n_clip, f"{label}: {key}: {fj['clipped_cells']} cells "
              f"reported clipped, {n_clip} expected")
        check(f"{key}: {NX * NY} cells" in stdout and
              f"{fj['clipped_cells']} clipped" in stdout, f"{label}: {key}: counts printed")
        outside = (NX * NY) - 32 * 8  # cells beyond the 0.8 x 0.2 m grid
        check(fj["fallback_cells"] == outside + 4 * empty_bins[q],
              f"{label}: {key}: {fj['fallback_cells']} cells take the constant (the {outside} "
              f"outside the grid and 4 in each of the {empty_bins[q]} empty bins)")
        with open(path) as f:
            text = f.read()
        check(cd.sha256(h5) in text and "setConstraintTypes" in text,
              f"{label}: {key}: header records the extraction's sha256; constraint patches set")
    d = read_dict(os.path.join(target, "constant", "bulkProperties"))
    check(d["drifts"].get("fields") == "on" and cd.sha256(h5) in unquote(d["drifts"]["source"])
          and d["solidFraction"] == str(alpha),
          f"{label}: bulkProperties: drifts {{ fields on; source with the sha256 }}, "
          "solidFraction kept")
    return sum(empty_bins.values()), clipped, cmd


def main():
    exe, blockmesh, work = sys.argv[1:4]
    failures = []
    check = checker(failures)
    case = os.path.join(work, "dem_case")
    dd.make(case, exe)
    h5 = os.path.join(case, cd.H5_IN_CASE)
    counts = {}
    for label, windows, alpha, how in RUNS:
        empty, clipped, cmd = run(check, work, case, h5, blockmesh, label, windows, alpha, how)
        counts[label] = (empty, clipped)
    check(counts[RUNS[0][0]][0] > 0, f"bins without a selected window exist (the fallback is "
          f"exercised): {counts[RUNS[0][0]][0]}")
    check(counts[RUNS[1][0]][1] > 0, f"cells are clipped (the clip is exercised): "
          f"{counts[RUNS[1][0]][1]}")
    run_per_window(check, work, case, h5, blockmesh)

    # Refusals: --fields without --target, a target without a mesh; nothing written.
    r = subprocess.run(CALIBRATE + [case, "--target", os.path.join(work, "bulk_target_clipped"),
                                    "--fields", "--field-mean", "median"],
                       capture_output=True, text=True)
    check(r.returncode == 2 and "--field-mean median" in r.stderr, f"--field-mean median: exit "
          f"{r.returncode}; {r.stderr.strip()}")
    r = subprocess.run(CALIBRATE + [case, "--fields"], capture_output=True, text=True)
    check(r.returncode == 2 and "--target" in r.stderr, f"--fields without --target: exit "
          f"{r.returncode}; {r.stderr.strip()}")
    bare = os.path.join(work, "no_mesh")
    os.makedirs(os.path.join(bare, "constant"), exist_ok=True)
    r = subprocess.run(CALIBRATE + [case, "--target", bare, "--fields", "--bootstrap", "50"],
                       capture_output=True, text=True)
    check(r.returncode == 2 and "polyMesh" in r.stderr and "blockMesh" in r.stderr
          and not os.listdir(os.path.join(bare, "constant")),
          f"target without a mesh: exit {r.returncode}; {r.stderr.strip()}")
    print("PASS" if not failures else f"FAIL: {len(failures)} checks")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
