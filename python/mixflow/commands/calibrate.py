"""A finished CFD-DEM mixture case to a calibrated bulk run of the same scene, compared with it
(docs/calibration.md).

usage: mixflow calibrate CASE [--work DIR] [--end T] [--skip-existing] [--cell-size DX]
           [--pressure porePressureRatio|lambdaP] [--estimator wls|median|flux]
           [--vertical auto|fit|isotropic] [--flowing-factor F] [--pressure-bins all|flowing]

Steps, each into WORK (default CASE-calibration):
  1. extraction: mixflowExtract -case CASE -overwrite with CASE/system/extractDict; a case without
     one gets the shipped template docs/extractDict with its grid set to the case's channel (up to
     3 x 0.72 m) in bins no narrower than its fluid cell (mixture_lambdas.bin_counts);
  2. the bulk target WORK/bulk: CASE's inputs (outputs.copy_inputs) with cfdDict mixtureModel
     bulk, dimensions 2, cellSize DX (default CASE's) and controlDict endTime T (default CASE's
     last written time), the bulk tier's recipe (cases/tiers/bulk) applied to this one case;
  3. calibration: the constant drifts of the extraction written into WORK/bulk's bulkProperties
     (calibrate_drifts.calibrate and write_target; --pressure porePressureRatio, chi over the
     bulk model's rho_f p_m at WORK/bulk's solid fraction, and --vertical auto by default: an
     ill-posed lambda_w is replaced by the isotropic drift, and the table says so);
  4. the bulk run: WORK/bulk/Allrun 1;
  5. the comparison: fronts against time (CFD-DEM granular front_x_m, bulk front_bed_m), the
     surface h(x) at three times (CFD-DEM liquid, bulk mixture: postProcessing/liquid/
     profiles.csv) and u(y) at the CFD-DEM velocity profile's section and time (demDict
     velocityProfile; bulk_model_results.bulk_velocity) into WORK/fronts.png, profiles.png,
     velocity.png and WORK/summary.json (drifts, their 16-84 % bootstrap interval, the weighted R^2
     of the fluid against lambda times the solid quantity, the front errors, the rms differences).
--skip-existing keeps a step's output when it exists: the h5 file; the bulk case and its run
(reached its endTime) when its calibration JSON holds the drifts calibrated now. Bad input (no finished run, no fluid fields or particle
snapshots, a bad option) exits 2 naming the file or entry before anything runs.
"""

import argparse
import json
import math
import os
import shutil
import sys

import numpy as np

from mixflow import ROOT, bulkprops, foamcase, foamdict, outputs
from mixflow.commands import calibrate_drifts as cd
from mixflow.commands import mixture_lambdas as ml
from mixflow.commands.bulk_model_results import bulk_velocity, dem_front, profile

TEMPLATE = os.path.join(ROOT, "docs", "extractDict")
H5 = os.path.join("postProcessing", "mixture", "mixture.h5")
PROFILE_SHARES = (1 / 3, 2 / 3, 1.0)  # h(x) compared at these shares of the end time
FRONT_STEP_S = 0.05  # fronts compared every this many seconds


class Refusal(Exception):
    """Bad input found before a step runs: the message names the file or entry."""


def last_time(case):
    """The last written fluid time of CASE (its time directories other than 0), or None."""
    times = [t for t, _ in foamcase.time_dirs(case) if t > 0]
    return max(times) if times else None


def check_case(case, end):
    """Refuses CASE unless it is a finished CFD-DEM mixture run with what extraction reads."""
    def need(rel, what):
        if not os.path.exists(os.path.join(case, rel)):
            raise Refusal(f"{os.path.join(case, rel)}: missing ({what})")
    need(os.path.join("system", "cfdDict"), "a mixflow case has system/cfdDict")
    need(os.path.join("constant", "sceneProperties"), "the scene: its channel sizes the grid")
    cfd = foamdict.read_dict(os.path.join(case, "system", "cfdDict"))
    if cfd.get("mixtureModel", "cfddem") == "bulk":
        raise Refusal(f"{case}/system/cfdDict: mixtureModel bulk is a bulk-model case; CASE is "
                      "the CFD-DEM run to calibrate from (mixtureModel cfddem)")
    need(outputs.DEM_SERIES, "no finished CFD-DEM run: run the case's ./Allrun first")
    need(os.path.join("0", "C"), "the fluid cell centres Allrun writes (postProcess "
         "-funcs '(writeCellCentres writeCellVolumes)' -time 0)")
    need(outputs.SNAPSHOT_SERIES, "the particle snapshots extraction bins (demDict "
         "binarySnapshots on)")
    t_last = last_time(case)
    if t_last is None:
        raise Refusal(f"{case}: no fluid fields (no time directory after 0: controlDict "
                      "writeInterval, or the run did not start)")
    t_end = float(foamdict.read_dict(os.path.join(case, "system", "controlDict"))["endTime"])
    dem = outputs.read_rows(os.path.join(case, outputs.DEM_SERIES))
    if dem[-1][outputs.TIME] < t_end - outputs.END_TOLERANCE_S:
        raise Refusal(f"{os.path.join(case, outputs.DEM_SERIES)}: ends at "
                      f"{dem[-1][outputs.TIME]:g} s before controlDict endTime {t_end:g} s: the "
                      "run is not finished (resume it: its ./Allrun's hint)")
    if end is not None and not 0 < end <= t_last + outputs.END_TOLERANCE_S:
        raise Refusal(f"--end {end:g}: allowed (0, {t_last:g}] s, the case's last field write")
    return min(end or t_last, t_last)


def extract_dict_text(case):
    """The template docs/extractDict with its grid fitted to CASE's channel and fluid cell."""
    channel = foamdict.read_dict(os.path.join(case, "constant", "sceneProperties"))["channel"]
    xr = min(float(channel["length"].split()[0]), ml.X_RANGE)
    yr = min(float(channel["height"].split()[0]), ml.Y_RANGE)
    nx, ny = ml.bin_counts(case, xr, yr)
    with open(TEMPLATE) as f:
        text = f.read()
    return foamdict.edit_dict(text, {"grid": {"x": f"(0 {xr!r} {nx})", "y": f"(0 {yr!r} {ny})"}},
                              note="fitted by mixflow calibrate")[0]


def make_bulk_case(case, bulk, cell_size, end):
    """BULK: CASE's inputs as the bulk model (cases/tiers/bulk's mixture entries), to END."""
    shutil.rmtree(bulk, ignore_errors=True)
    outputs.copy_inputs(case, bulk)
    foamdict.edit_file(os.path.join(bulk, "system", "cfdDict"),
                       {"mixtureModel": "bulk", "dimensions": "2", "cellSize": repr(cell_size)},
                       note="mixflow calibrate: the bulk model of the CFD-DEM case")
    foamcase.set_entry(os.path.join(bulk, "system", "controlDict"), "endTime", repr(end))


def calibration_summary(res):
    """Per drift: value, bootstrap interval, R^2 (of the fluid quantity against the value times
    the solid one), samples and bins, the per-bin ratios' spread; the velocity drifts' fit
    quality, lambda_w's rule and the mass balance with the drifts (calibrate_drifts)."""
    out = {}
    for q, r in res["drifts"].items():
        e = r[res["estimator"]]
        interval = [e["p16"], e["p84"]]
        if r.get("vertical", {}).get("used") == "isotropic":
            interval = [r["vertical"]["isotropic_p16"], r["vertical"]["isotropic_p84"]]
        s = res["_samples"][q]
        out[q] = {"value": r["value"], "interval_16_84": interval,
                  "r2": cd.fit_quality(s["x"], s["y"], s["w"], r["value"])[0],
                  "samples": r["samples"], "spatial_bins": r["spatial_bins"],
                  "ratio_quantiles": r["ratio_quantiles"]}
        for k in ("fit", "vertical"):
            if k in r:
                out[q][k] = r[k]
    out["mass_balance"] = res["mass_balance"]
    return out


def rms(values):
    v = [x for x in values if math.isfinite(x)]
    return math.sqrt(sum(x * x for x in v) / len(v)) if v else None


def compare(case, bulk, end):
    """Fronts, h(x, t) and u(y) of the bulk run BULK against the CFD-DEM run CASE up to END."""
    dem = outputs.read_rows(os.path.join(case, outputs.DEM_SERIES))
    blk = outputs.read_rows(os.path.join(bulk, outputs.LIQUID_SERIES))
    times = [round(k * FRONT_STEP_S, 9) for k in range(1, int(end / FRONT_STEP_S + 1e-9) + 1)]
    fronts = [{"time_s": t, "cfd_dem_front_m": dem_front(dem, t),
               "bulk_front_m": outputs.interpolated(blk, outputs.LIQUID_FRONT, t)} for t in times]
    err = [f["bulk_front_m"] / f["cfd_dem_front_m"] - 1 for f in fronts]
    last = {"time_s": blk[-1][outputs.TIME], "bulk_front_m": blk[-1][outputs.LIQUID_FRONT],
            "cfd_dem_front_m": dem_front(dem, blk[-1][outputs.TIME])}
    last["front_error"] = last["bulk_front_m"] / last["cfd_dem_front_m"] - 1
    profiles = []
    for share in PROFILE_SHARES:
        xr, hr = profile(case, share * end)
        xb, hb = profile(bulk, share * end)
        diff = np.interp(xr, xb, hb) - np.asarray(hr)
        profiles.append({"time_s": share * end, "rms_difference_m": rms(list(diff)),
                         "cfd_dem": [xr, hr], "bulk": [xb, hb]})
    out = {"end_time_s": end, "front_at_end": last, "front_rms_error": rms(err),
           "fronts": fronts, "h_x_t": profiles}
    vp_path = os.path.join(case, outputs.VELOCITY_PROFILE)
    if os.path.exists(vp_path) and outputs.read_rows(vp_path):
        vp = outputs.read_rows(vp_path)
        x, t = vp[0]["x_section_m"], vp[0][outputs.TIME]
        y, us, uf, tb = bulk_velocity(bulk, x, t)
        yr = [r["y_m"] for r in vp]
        ur = [r["u_x_m_s"] for r in vp]
        diff = np.interp(yr, y, us) - np.asarray(ur) if y else []
        out["u_y"] = {"x_m": x, "time_s": t, "bulk_time_s": tb, "rms_difference_m_s":
                      rms(list(diff)), "cfd_dem": [yr, ur], "bulk": [y, us, uf]}
    else:
        out["u_y"] = {"missing": f"{vp_path}: none (demDict velocityProfile.time after the run's "
                                 "end)"}
    return out


def plots(cmp, work):
    """WORK/fronts.png, profiles.png and velocity.png: bulk over CFD-DEM."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    files = []
    fig, ax = plt.subplots(figsize=(5, 3.6))
    ts = [f["time_s"] for f in cmp["fronts"]]
    ax.plot(ts, [f["cfd_dem_front_m"] for f in cmp["fronts"]], "k-", label="CFD-DEM granular")
    ax.plot(ts, [f["bulk_front_m"] for f in cmp["fronts"]], "C0--", label="bulk, calibrated")
    ax.set(xlabel="t (s)", ylabel="front x (m)")
    files.append(_save(fig, ax, os.path.join(work, "fronts.png")))
    fig, ax = plt.subplots(figsize=(6, 3.6))
    for k, p in enumerate(cmp["h_x_t"]):
        ax.plot(*p["cfd_dem"], "-", color=f"C{k}", label=f"CFD-DEM liquid, {p['time_s']:.3g} s")
        ax.plot(*p["bulk"], "--", color=f"C{k}", label=f"bulk mixture, {p['time_s']:.3g} s")
    ax.set(xlabel="x (m)", ylabel="surface height (m)")
    files.append(_save(fig, ax, os.path.join(work, "profiles.png")))
    v = cmp["u_y"]
    if "cfd_dem" in v:
        fig, ax = plt.subplots(figsize=(4.5, 3.6))
        ax.plot(v["cfd_dem"][1], v["cfd_dem"][0], "k-o", ms=3,
                label=f"CFD-DEM grains, {v['time_s']:.3g} s")
        ax.plot(v["bulk"][1], v["bulk"][0], "C0--", label=f"bulk u_s, {v['bulk_time_s']:.3g} s")
        ax.plot(v["bulk"][2], v["bulk"][0], "C1:", label=f"bulk u_f, {v['bulk_time_s']:.3g} s")
        ax.set(xlabel="u (m/s)", ylabel="y (m)", title=f"x = {v['x_m']:g} m")
        files.append(_save(fig, ax, os.path.join(work, "velocity.png")))
    return files


def _save(fig, ax, path):
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    return path


def bulk_finished(bulk, end):
    path = os.path.join(bulk, outputs.LIQUID_SERIES)
    return os.path.exists(path) and \
        outputs.read_rows(path)[-1][outputs.TIME] >= end - outputs.END_TOLERANCE_S


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("case", help="a finished CFD-DEM mixture case (its ./Allrun done)")
    ap.add_argument("--work", help="where the bulk case and the results go (default "
                    "CASE-calibration)")
    ap.add_argument("--end", type=float, help="end of the bulk run and the comparison (s; default "
                    "the case's last field write)")
    ap.add_argument("--skip-existing", action="store_true",
                    help="keep a step's output when it exists")
    ap.add_argument("--cell-size", type=float, help="the bulk case's cfdDict cellSize (m; default "
                    "the CFD-DEM case's)")
    ap.add_argument("--pressure", default=cd.PRESSURE_DEFAULT,
                    help="calibrate-drifts --pressure (default porePressureRatio: no pole)")
    ap.add_argument("--estimator", default="wls", help="calibrate-drifts --estimator")
    ap.add_argument("--vertical", default="auto",
                    help="calibrate-drifts --vertical (default auto: lambda_w's fit if "
                    "well-posed, else the isotropic drift)")
    ap.add_argument("--flowing-factor", type=float, default=0.05,
                    help="calibrate-drifts --flowing-factor (lower it for a slow flow)")
    ap.add_argument("--pressure-bins", default=cd.PRESSURE_BINS_DEFAULT,
                    help="calibrate-drifts --pressure-bins (default all: the pressure closure "
                    "over every mixture bin, the column at rest too)")
    a = ap.parse_args(argv)
    case = os.path.abspath(a.case)
    work = os.path.abspath(a.work or case.rstrip(os.sep) + "-calibration")
    bulk = os.path.join(work, "bulk")
    try:
        if not os.path.isdir(case):
            raise Refusal(f"{a.case}: no such case directory")
        end = check_case(case, a.end)
        cell = a.cell_size or float(
            foamdict.read_dict(os.path.join(case, "system", "cfdDict"))["cellSize"].split()[0])
        if not cell > 0:
            raise Refusal(f"--cell-size {cell:g}: allowed > 0 m")
        cd.check_options(a.flowing_factor, 0.1, "particles", 1000, a.estimator)
        if a.pressure not in cd.PRESSURE:
            raise Refusal(f"--pressure {a.pressure}: allowed {', '.join(cd.PRESSURE)}")
        if a.vertical not in cd.VERTICAL:
            raise Refusal(f"--vertical {a.vertical}: allowed {', '.join(cd.VERTICAL)}")
        if a.pressure_bins not in cd.PRESSURE_BINS:
            raise Refusal(f"--pressure-bins {a.pressure_bins}: allowed "
                          f"{', '.join(cd.PRESSURE_BINS)}")
        if work == case or work.startswith(case + os.sep):
            raise Refusal(f"--work {work}: inside CASE, whose inputs it copies; choose another")
    except (Refusal, cd.InputError, foamdict.DictError, KeyError) as e:
        print(f"mixflow calibrate: error: {e}", file=sys.stderr)
        return 2
    os.makedirs(work, exist_ok=True)
    build = os.environ.get("MIXFLOW_BUILD", os.path.join(ROOT, "build"))
    h5 = os.path.join(case, H5)
    dict_path = os.path.join(case, "system", "extractDict")
    extract_dict = "the case's" if os.path.exists(dict_path) else "docs/extractDict, fitted"
    if not (a.skip_existing and os.path.exists(h5)):
        if not os.path.exists(dict_path):
            with open(dict_path, "w") as f:
                f.write(extract_dict_text(case))
        print(f"[1/5] mixflowExtract -case {case} ({dict_path}: {extract_dict})", flush=True)
        ml.run_extract(case, build)
    cal_json = bulkprops.path(bulk) + ".calibration.json"
    keep = a.skip_existing and os.path.exists(cal_json)
    if not keep:
        print(f"[2/5] bulk target {bulk}", flush=True)
        make_bulk_case(case, bulk, cell, end)
    print("[3/5] calibration of the drifts", flush=True)
    try:
        alpha, _ = cd.target_solid_fraction(bulk, cd.check_target(bulk))
        res = cd.calibrate(h5, a.estimator, a.flowing_factor, pressure=a.pressure,
                           vertical=a.vertical, solid_fraction=alpha,
                           pressure_bins=a.pressure_bins)
    except cd.InputError as e:
        print(f"mixflow calibrate: error: {e}; for a slow flow lower --flowing-factor, or the "
              f"extraction's thresholds.minVelocity / minPressure in {dict_path} (then run again "
              "without --skip-existing)", file=sys.stderr)
        return 2
    print(cd.table(res), flush=True)
    if keep:  # the kept bulk run stands only for these drifts
        with open(cal_json) as f:
            kept = json.load(f)
        keep = kept["pressure"] == res["pressure"] and all(
            kept["drifts"][q]["value"] == r["value"] for q, r in res["drifts"].items())
    if not keep:
        try:
            cd.write_target(bulk, res, case)
        except cd.InputError as e:  # a drift the bulk model cannot take: the table above says which
            print(f"mixflow calibrate: error: {e}", file=sys.stderr)
            return 2
    with open(cal_json) as f:
        written = json.load(f)
    if not (keep and bulk_finished(bulk, end)):
        print(f"[4/5] bulk run: {bulk}/Allrun 1", flush=True)
        foamcase.run_tool(["./Allrun", "1"], "mixflow calibrate", cwd=bulk)
    print("[5/5] comparison", flush=True)
    cmp = compare(case, bulk, end)
    out = {"command": "mixflow calibrate " + " ".join(argv if argv is not None else sys.argv[1:]),
           "case": case, "work": work, "bulk_case": bulk, "extract_dict": extract_dict,
           "h5": h5, "sha256": res["sha256"], "estimator": res["estimator"],
           "pressure": res["pressure"], "vertical": a.vertical, "selection": res["selection"],
           "bulk_cell_size_m": cell, "solid_fraction": written["solid_fraction"],
           "solid_fraction_from": written["solid_fraction_from"],
           "drift_range": written["drift_range"],
           "bulk_solver_cpu_s": foamcase.execution_time(
               os.path.join(bulk, "log.mixflowBulkFoam")),
           "calibration": calibration_summary(res), "comparison": cmp}
    out["plots"] = plots(cmp, work)
    outputs.write_json(os.path.join(work, "summary.json"), out)
    f = cmp["front_at_end"]
    print(f"front at {f['time_s']:g} s: bulk {f['bulk_front_m']:.3f} m, CFD-DEM "
          f"{f['cfd_dem_front_m']:.3f} m ({100 * f['front_error']:+.1f} %); rms over time "
          f"{100 * cmp['front_rms_error']:.1f} %; wrote {os.path.join(work, 'summary.json')}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
