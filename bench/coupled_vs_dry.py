#!/usr/bin/env python3
"""Benchmark: the coupled HB&P scene against the dry P scene with the same particles and
DEM settings: CPU-time ratio of the collapse, and the coupled run's split between DEM (inside
LIGGGHTS runs), coupling (exchanges: locate, void fraction, forces, source) and fluid (the rest).
Target: coupled <= 1.3 x dry.

The scene is cases/W+P-quick with the Herschel-Bulkley liquid of case HB (813 grains, 2-D fluid at
0.06 m, 1.5 s) -- a quick-size HB&P; the dry twin is the same scene with content particles. Both
settle the same sample (same seed); the settling is timed separately and left out of both.
The ratio compares the CPU of the collapse phases as the programs measure them (mixflowDem after
its settling, mixflowCoupled's time loop): start-up, mesh and restart reading are left out.

usage: coupled_vs_dry.py [--end 1.0] [--exchange-every 25,100] [--drag-integration implicit|held]
                         [--drag-fluid-response none|share] [--liquid HB|W|B]
                         [--json OUT] [--bin build/bin]
With several exchange intervals each coupled run is compared with the same dry twin, and the
fronts and particle kinetic energy at half time and at the end are reported with their change
from the first interval's run: the speed/accuracy trade of the exchange interval.
CPU seconds (user + sys of the programs) are compared: wall time also counts waiting for a core.

Second baseline, per coupled run: the same run's LIGGGHTS command stream without the coupling,
replayed by plain `liggghts` (dry_replay): a dry collapse of the very sample the coupled run
started from, in the same run chunks. The dry twin settles its own sample, whose collapse costs
60-97 CPU s at the paper's stiffness from one run to the next (bench/README.md); the replay takes
that variance out of the ratio (`ratio_coupled_over_dry_replay`)."""
import argparse
import csv
import json
import os
import re
import shutil
import sys
import tempfile

sys.dont_write_bytecode = True
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
from mixflow.timing import timed as _timed  # noqa: E402
from mixflow import foamdict, outputs  # noqa: E402


def timed(cmd, cwd):
    """(wall s, CPU s of the command and its children, stdout)."""
    return _timed(cmd, cwd, with_output=True)


def set_entry(path, key, value):
    """Sets (or inserts) a top-level entry with the dictionary editor (mixflow.foamdict)."""
    foamdict.edit_file(path, {key: value}, note="bench")


def last_row_at(path, t):
    """The last row of a mixflow time series (CSV, '#' comments) with time_s <= t."""
    with open(path) as f:
        rows = list(csv.DictReader(ln for ln in f if not ln.startswith("#")))
    return [r for r in rows if float(r["time_s"]) <= t + 1e-9][-1]


def observables(case, end):
    """At half the run and at its end: the fronts (single-particle or single-cell quantities, noisy
    in a small scene), and integral ones: the particles' and the liquid's potential energy released
    since t = 0, the particles' kinetic energy and their mean x."""
    out = {}
    dem = os.path.join(case, outputs.DEM_SERIES)
    liq = os.path.join(case, outputs.LIQUID_SERIES)
    g0, l0 = last_row_at(dem, 0.0), last_row_at(liq, 0.0)
    with open(os.path.join(case, outputs.EXCHANGE)) as f:
        ex = list(csv.DictReader(ln for ln in f if not ln.startswith("#")))
    for t in (0.5 * end, end):
        g, lq = last_row_at(dem, t), last_row_at(liq, t)
        e = [r for r in ex if float(r["time"]) <= t + 1e-9][-1]
        out[f"granular_front_m_at_{t:g}s"] = float(g["front_x_m"])
        out[f"liquid_front_m_at_{t:g}s"] = float(lq["front_bed_m"])
        out[f"particle_pe_released_J_at_{t:g}s"] = float(g0["pe_J"]) - float(g["pe_J"])
        out[f"liquid_pe_released_J_at_{t:g}s"] = (float(l0["potential_energy_J"]) -
                                                  float(lq["potential_energy_J"]))
        out[f"particle_ke_J_at_{t:g}s"] = float(g["ke_translational_J"])
        out[f"particle_mean_x_m_at_{t:g}s"] = float(e["meanX"])
    return out


def dry_replay(case):
    """The coupled run's own DEM work without the fluid: the command stream mixflowCoupled gave
    LIGGGHTS (<case>/dem/in.liggghts: the settled sample restarted without the gate, then one
    `run N` per exchange) minus the coupling's fixes (fluid forces, drag state) and snapshots,
    replayed with the plain `liggghts` binary. The same grains from the same packing, the same
    run chunks: a dry collapse that differs from the coupled run only by the coupling. Returns
    its CPU seconds (the restart's reading included, ~0.1 s), or None without `liggghts`."""
    if not shutil.which("liggghts"):
        return None
    drop = re.compile(r"mixflowDragState|mixflowFluidForce|^dump |^run 0$")
    with open(os.path.join(case, "dem", "in.liggghts")) as f:
        lines = [ln for ln in f if not drop.search(ln.rstrip("\n"))]
    script = os.path.join(case, "dem", "in.dry_replay")
    with open(script, "w") as f:
        f.writelines(lines)
    _, cpu = _timed(["liggghts", "-in", script, "-log", os.path.join(case, "dem", "log.dry_replay"),
                     "-screen", "none"], case)
    return cpu


def edit(path, overrides):
    """Set (or insert, creating blocks) the entries of OVERRIDES in the dictionary file PATH,
    with the dictionary editor (mixflow.foamdict, the one behind suite.py's --set)."""
    foamdict.edit_file(path, overrides, note="bench", create_blocks=True)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--end", type=float, default=1.0)
    ap.add_argument("--json")
    ap.add_argument("--keep", action="store_true", help="keep the run directories (printed)")
    ap.add_argument("--bin", default=os.path.join(ROOT, "build", "bin"))
    ap.add_argument("--exchange-every", default="",
                    help="DEM steps per exchange, one coupled run each, e.g. 25,100 (default: "
                    "the case's couplingProperties)")
    ap.add_argument("--drag-integration", choices=("implicit", "held"),
                    help="couplingProperties dragIntegration (default: the case's)")
    ap.add_argument("--case", help="a mixture case to bench instead of the quick-size scene, e.g. "
                    "a suite run's WORK/HB+P at tier paper-window (its inputs are copied; "
                    "--liquid is then ignored)")
    ap.add_argument("--liquid", default="HB", choices=("HB", "W", "B"),
                    help="the liquid of this case in cases/ (default HB: the issue's HB&P)")
    ap.add_argument("--drag-fluid-response", choices=("none", "share", "continuity"),
                    help="couplingProperties dragFluidResponse (default: the case's)")
    ap.add_argument("--rayleigh-fraction", type=float,
                    help="demDict rayleighFraction, the DEM step in Rayleigh times, for the "
                    "settling, the dry twin and the coupled runs (default: the case's, 0.1)")
    ap.add_argument("--young-modulus-factor", type=float,
                    help="demDict youngModulusFactor (default: the case's, 1e-3); 1 is the paper's "
                    "70/700 GPa")
    ap.add_argument("--settled", help="a dem/ directory with settled.{restart,state,inputs} of "
                    "an earlier run of this bench with the same DEM settings (kept with --keep): "
                    "the coupled runs start from it instead of settling again; mixflowDem -reuse "
                    "refuses it if settled from other inputs (or if it has no fingerprint)")
    ap.add_argument("--void-smoothing", type=float,
                    help="couplingProperties dividedCoeffs smoothing (face band / particle radius; "
                         "default: the case's, 0 = off)")
    ap.add_argument("--n-correctors", type=int,
                    help="cfdDict nCorrectors, the PISO pressure correctors per fluid step "
                         "(default: the case's, auto: 3 or 10 by the viscous number)")
    ap.add_argument("--drag-viscosity-max", default="",
                    help="couplingProperties DiFeliceDragCoeffs viscosityMax in Pa s, the drag's "
                         "viscosity bound; a comma list runs each (with every --exchange-every) "
                         "against the same dry twin, 'none' = the case's (no bound), e.g. none,1 "
                         "(1 lets HB&P's column flow)")
    ap.add_argument("--dem-step", type=float,
                    help="demDict timeStep in s (default: the case's, auto); the paper's is 5e-7")
    ap.add_argument("--stiffen-from", type=float,
                    help="demDict settle.stiffenFrom: settle at this youngModulusFactor, then "
                    "stiffen (default: the case's, 0 = settle at youngModulusFactor)")
    a = ap.parse_args()
    work = tempfile.mkdtemp(prefix="mixflow-bench-cpl-")
    env_path = a.bin + os.pathsep + os.environ["PATH"]
    os.environ["PATH"] = env_path
    os.environ.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")
    os.environ["MIXFLOW_ROOT"] = ROOT

    # The coupled scene: W+P-quick with case HB's liquid (or --liquid's), or --case as it is.
    label = os.path.basename(os.path.normpath(a.case)) if a.case else f"{a.liquid}+P-quick"
    cpl = os.path.join(work, label)
    outputs.copy_inputs(a.case or os.path.join(ROOT, "cases", "W+P-quick"), cpl)
    sp = os.path.join(cpl, "constant", "sceneProperties")
    text = open(sp).read()
    if not a.case:
        hb = open(os.path.join(ROOT, "cases", a.liquid, "constant", "sceneProperties")).read()
        text = text[:text.index("liquid   //")] + hb[hb.index("liquid   //"):]
        open(sp, "w").write(text)
    set_entry(os.path.join(cpl, "system", "controlDict"), "endTime", repr(a.end))
    cp = os.path.join(cpl, "constant", "couplingProperties")
    if a.drag_integration:
        set_entry(cp, "dragIntegration", a.drag_integration)
    if a.drag_fluid_response:
        set_entry(cp, "dragFluidResponse", a.drag_fluid_response)
    if a.void_smoothing is not None:
        edit(cp, {"dividedCoeffs": {"smoothing": repr(a.void_smoothing)}})
    if a.n_correctors:
        edit(os.path.join(cpl, "system", "cfdDict"), {"nCorrectors": str(a.n_correctors)})
    dem_dict = os.path.join(cpl, "system", "demDict")
    for entry, value in (("rayleighFraction", a.rayleigh_fraction),
                         ("youngModulusFactor", a.young_modulus_factor), ("timeStep", a.dem_step)):
        if value:
            set_entry(dem_dict, entry, repr(value))
    if a.stiffen_from:
        edit(dem_dict, {"settle": {"stiffenFrom": repr(a.stiffen_from)}})
    props = foamdict.read_dict(cp)
    everies = [int(n) for n in a.exchange_every.split(",")] if a.exchange_every else \
        [int(props["exchangeEvery"])]
    # The dry twin: same particles, walls, DEM settings; no liquid.
    dry = os.path.join(work, "P-twin")
    os.makedirs(os.path.join(dry, "constant"))
    os.makedirs(os.path.join(dry, "system"))
    dtext = text[:text.index("liquid   //")].replace("content mixture;", "content particles;")
    open(os.path.join(dry, "constant", "sceneProperties"), "w").write(dtext)
    for f in ("demDict", "controlDict"):
        shutil.copy(os.path.join(cpl, "system", f), os.path.join(dry, "system", f))

    mf = lambda p: os.path.join(a.bin, p)  # noqa: E731
    if a.settled:
        # A sample settled earlier with the same settings (settling at the paper's stiffness
        # takes ~10 min for this scene), taken only if its fingerprint shows the same settling
        # inputs (mixflowDem -reuse); the dry twin still settles its own (not timed).
        timed([mf("mixflowDem"), "-case", cpl, "-settleOnly", "-reuse", os.path.abspath(a.settled)],
              cpl)
        c_settle = None
    else:
        _, c_settle, _ = timed([mf("mixflowDem"), "-case", cpl, "-settleOnly"], cpl)
    w_dry_all, c_dry_all, dry_out = timed([mf("mixflowDem"), "-case", dry], dry)
    # The dry collapse's CPU as mixflowDem measures it after its own settling (the same
    # commands as the coupled case's); the difference of two whole runs is kept as a check (it
    # carries both settlings' noise, which at the paper's stiffness is larger than the collapse).
    m = re.search(r"collapse phase: wall [0-9.eE+-]+ s, CPU ([0-9.eE+-]+) s", dry_out)
    if not m:
        sys.exit("coupled_vs_dry: mixflowDem printed no collapse-phase CPU (an old build?)")
    c_dry = float(m.group(1))
    c_dry_diff = None if c_settle is None else c_dry_all - c_settle
    runs = []
    vmaxes = [None if v == "none" else float(v) for v in a.drag_viscosity_max.split(",")] \
        if a.drag_viscosity_max else [None]
    for vmax, n in ((v, n) for v in vmaxes for n in everies):
        case = os.path.join(work, f"{label}-every{n}" +
                            ("" if vmax is None else f"-dragvmax{vmax:g}"))
        shutil.copytree(cpl, case)  # the settled sample included
        set_entry(os.path.join(case, "constant", "couplingProperties"), "exchangeEvery", str(n))
        if vmax is not None:
            edit(os.path.join(case, "constant", "couplingProperties"),
                 {"DiFeliceDragCoeffs": {"viscosityMax": repr(vmax)}})
        timed([mf("mixflowPrepare"), "-case", case], case)
        timed(["blockMesh", "-case", case], case)
        try:
            w_cpl, c_proc, out = timed([mf("mixflowCoupled"), "-case", case], case)
        except SystemExit as e:  # a diverged run is a result of the trade too: record it, go on
            why = re.search(r"FOAM FATAL ERROR:\s*\n(.*)", str(e))
            runs.append({"exchange_every": n, "drag_viscosity_max": vmax,
                         "failed": why.group(1) if why else str(e)[-500:]})
            print(f"exchange every {n}: failed: {runs[-1]['failed']}", file=sys.stderr)
            continue
        # The time loop alone (start-up, mesh and restart reading left out, as the dry side's
        # settling is); the whole process's CPU is kept too.
        m = re.search(r"time loop CPU ([0-9.eE+-]+) s", out)
        if not m:
            sys.exit("coupled_vs_dry: mixflowCoupled printed no time-loop CPU (an old build?)")
        c_cpl = float(m.group(1))
        m = re.search(r"inside LIGGGHTS runs ([0-9.eE+-]+) s", out)
        dem_s = float(m.group(1)) if m else float("nan")
        with open(os.path.join(case, outputs.EXCHANGE)) as f:
            rows = list(csv.DictReader(ln for ln in f if not ln.startswith("#")))
        coupling_s = sum(float(r["seconds"]) for r in rows)
        summ = json.load(open(os.path.join(case, outputs.DEM_SUMMARY)))
        c_replay = dry_replay(case)
        with open(os.path.join(case, "system", "in.liggghts")) as f:
            dem_step = float(re.search(r"^timestep\s+(\S+)", f.read(), re.M).group(1))
        runs.append({
            "exchange_every": n, "drag_viscosity_max": vmax, "dem_step_s": dem_step, "exchange_interval_s": n * dem_step,
            "coupled_cpu_s": c_cpl, "coupled_process_cpu_s": c_proc,
            "ratio_coupled_over_dry": c_cpl / c_dry,
            # The coupling's own cost over the dry collapse, as if the coupled DEM cost what the
            # dry one did: the DEM's run-to-run cost varies by up to 60 % on this machine, and a
            # held column does other DEM work than a collapsing one (bench/README.md).
            "overhead_ratio": 1 + (w_cpl - dem_s) / c_dry,
            # Against the same sample's dry collapse (dry_replay): the coupling's cost alone.
            "dry_replay_cpu_s": c_replay,
            "ratio_coupled_over_dry_replay": c_cpl / c_replay if c_replay else None,
            "coupled_wall_s": w_cpl, "coupled_split_wall_s": {
                "dem_inside_liggghts": dem_s, "coupling_exchanges": coupling_s,
                "fluid_and_rest": w_cpl - dem_s - coupling_s},
            # What the ratio is made of (bench/README.md): ratio ~ DEM_coupled / DEM_dry +
            # (fluid + exchange per exchange) / (N x DEM step cost).
            "per_exchange_fluid_and_coupling_s": (w_cpl - dem_s) / max(len(rows), 1),
            "per_dem_step_s": dem_s / max(float(rows[-1]["demStep"]), 1.0) if rows else None,
            "observables": observables(case, a.end), "particles": summ["settled"]["particles"]})
    done = [r for r in runs if "observables" in r]
    for vmax in vmaxes:  # how far each observable moves from the shortest interval's value
        group = [r for r in done if r["drag_viscosity_max"] == vmax]
        for r in group[1:]:
            r["change_vs_every%d" % group[0]["exchange_every"]] = {
                k: v - group[0]["observables"][k] for k, v in r["observables"].items()}
    res = {
        "scene": a.case if a.case else
        f"W+P-quick geometry with case {a.liquid}'s liquid (2-D fluid 0.06 m)",
        "drag_integration": props.get("dragIntegration", "implicit"),
        "drag_fluid_response": props.get("dragFluidResponse", "none"),
        "void_smoothing": a.void_smoothing if a.void_smoothing is not None else 0.0,
        "n_correctors": a.n_correctors, "drag_viscosity_max": vmaxes,
        "dem_dict": {k: v for k, v in foamdict.read_dict(dem_dict).items()
                     if k in ("youngModulusFactor", "timeStep", "rayleighFraction")},
        "simulated_s": a.end, "particles": done[0]["particles"] if done else None,
        "settle_cpu_s": c_settle, "dry_collapse_cpu_s": c_dry,
        "dry_collapse_cpu_s_by_difference": c_dry_diff, "target_ratio": 1.3,
        "runs": runs,
        "command": " ".join(["mixflow bench coupled_vs_dry"] + sys.argv[1:]),
    }
    print(json.dumps(res, indent=2))
    if a.json:
        with open(a.json, "w") as f:
            json.dump(res, f, indent=2)
            f.write("\n")
    if a.keep:
        print(f"runs kept in {work}")
    else:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
