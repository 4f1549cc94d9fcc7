"""Mixture scene end to end: a copy of cases/W+P-quick, shortened,
run through its Allrun (mixflowDem -settleOnly, mixflowPrepare, blockMesh, mixflowCoupled), then
checked against conservation laws, and then mixflowExtract on it, checked with h5py.

Asserts (tolerances and why):
  - `nCorrectors auto` on the coupled step: the viscous number mixflowPrepare printed matches
    mu_max dt / (rho dx^2) recomputed from the scene, the CFD step and the mesh (to its 3 printed
    digits), and fvSolution holds the rule's count (3 up to 20, else 10);
  - every exchange: action = reaction to 1e-10 of sum |F_i| (the source is assembled from the same
    forces; round-off only), fluid-seen particle volume = particle volume - outside - clipped to
    1e-9 (exact volume split);
  - liquid volume balance (V0 - V_domain - V_outlet - V_top) / V0 within 1e-6 every step;
  - particles: remaining + deleted at outlet + deleted at top + lost = settled count, exactly;
  - the settled sample is saturated: initial liquid volume = pore volume of the box
    [0, L] x [0, settled height] x [0, W] within the particle volume of the cell row the top cuts;
    its liquid surface at the back wall (sum alpha V / area, the paper's flow height) is the
    settled height within that row's height, and the liquid volume depth lies below it by more
    than 0.3 of the height (the grains' share, about 0.6);
  - mixflowExtract: mixture.h5 opens with h5py; /fields/alpha_s etc. have shape
    (windows, y bins, x bins) and units; the particle volume in the bins (alpha_s x bin volume,
    summed) equals the particles' volume N Vp at the window's snapshots to 1e-9 (exact split, the
    snapshot mean of a count that does not change while nothing leaves; the grid starts one radius
    behind the back wall and below the floor, because the grains there overlap the walls by their
    contact deflection: 6e-7 and 1.4e-7 of the volume).
With --dem contactSnapshots=on the coupled run writes its contact snapshots (dem/ContactDumps.h)
and the extraction takes the stress along the contact lines (HDF5 attribute stress_source).
With --liquid-case (another case's liquid, e.g. HB+P's Herschel-Bulkley) and --couple ENTRY=VALUE
(couplingProperties entries; BLOCK.ENTRY=VALUE inside a block, e.g. dividedCoeffs.smoothing=0),
--scene ENTRY=VALUE (sceneProperties entries, e.g. liquid.yieldStress=0)
and --drag-viscosity CLOSURE (DiFeliceDragCoeffs dragViscosity), the same checks run on that
variant; --grain-energy-max E also
asserts the grains' energy budget: their kinetic energy never exceeds the potential energy they
have released by more than E joules (a closed collapse only dissipates; E covers the elastic
energy of the settled contacts that the restart releases).
"""

import argparse
import csv
import math
import os
import re
import shutil
import subprocess
import sys

sys.dont_write_bytecode = True
from mixflow import foamcase as fc  # noqa: E402
from mixflow import foamdict  # noqa: E402
from mixflow import outputs  # noqa: E402


def rows(path):
    with open(path) as f:
        lines = [ln for ln in f if not ln.startswith("#")]
    return list(csv.DictReader(lines))


def check_correctors(case):
    """`nCorrectors auto` on the coupled step: the D that mixflowPrepare printed equals mu_max
    dt / (rho dx_min^2) recomputed here from the scene (cap or viscosity), the CFD step and the
    mesh it printed (to the 3 digits printed), and the count written to fvSolution follows the
    rule (3 up to D = 20, else 10; docs/parameters.md)."""
    log = open(os.path.join(case, "log.mixflowPrepare")).read()
    liquid = foamdict.read_dict(os.path.join(case, "constant", "sceneProperties"))["liquid"]
    mu = float(liquid["viscosityCap"] if liquid["rheology"] != "Newtonian" else
               liquid["viscosity"])
    dt = float(re.search(r"CFD step (\S+) s", log).group(1))
    m = re.search(r"(\d)-D, mesh .* cells of (\S+) x (\S+) x (\S+) m", log)
    sides = [float(m.group(2)), float(m.group(3))]
    if m.group(1) == "3":
        sides.append(float(m.group(4)))
    d_expected = mu * dt / (float(liquid["density"]) * min(sides) ** 2)
    pm = re.search(r"PISO nCorrectors (\d+) \(auto\): viscous number mu dt/\(rho dx\^2\) = (\S+)",
                   log)
    written = int(re.search(r"nCorrectors\s+(\d+);",
                            open(os.path.join(case, "system", "fvSolution")).read()).group(1))
    rule = 3 if d_expected <= 20 else 10
    # D is printed with 3 significant digits: within half a unit of the third.
    good = (pm is not None and abs(float(pm.group(2)) - d_expected) <= 5e-3 * d_expected and
            written == rule == int(pm.group(1)))
    print(f"PISO correctors: D printed {pm.group(2) if pm else None}, recomputed {d_expected:.4g}; "
          f"written {written}, rule {rule}")
    return good


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--root", required=True, help="repository (cases/, scripts/)")
    ap.add_argument("--bindir", required=True, help="directory of the mixflow programs")
    ap.add_argument("--workdir", required=True)
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("--end", type=float, default=0.3)
    ap.add_argument("--liquid-case", help="take the liquid block of cases/NAME's sceneProperties")
    ap.add_argument("--couple", action="append", default=[], metavar="ENTRY=VALUE",
                    help="a couplingProperties entry of the run (repeatable)")
    ap.add_argument("--scene", action="append", default=[], metavar="ENTRY=VALUE",
                    help="sceneProperties entries (BLOCK.ENTRY=VALUE inside a block), after --liquid-case")
    ap.add_argument("--drag-viscosity", help="DiFeliceDragCoeffs dragViscosity of the run")
    ap.add_argument("--cfd", action="append", default=[], metavar="ENTRY=VALUE",
                    help="system/cfdDict entry of the run (added, or changed if the case has it)")
    ap.add_argument("--dem", action="append", default=[], metavar="ENTRY=VALUE",
                    help="system/demDict entry of the run (added, or changed if the case has it)")
    ap.add_argument("--grain-energy-max", type=float,
                    help="J: bound of max_t [KE_p(t) - (PE_p(0) - PE_p(t))]")
    ap.add_argument("--divergence", action="store_true",
                    help="instead: maxVelocity 1 m/s must stop the run with the place and time, "
                         "keeping the outputs written so far")
    a = ap.parse_args()

    case = os.path.join(a.workdir, "W+P-quick")
    shutil.rmtree(a.workdir, ignore_errors=True)
    os.makedirs(a.workdir)
    outputs.copy_inputs(os.path.join(a.root, "cases", "W+P-quick"), case)
    fc.set_entry(os.path.join(case, "system/controlDict"), "endTime", repr(a.end))
    if a.liquid_case:
        # The liquid block (from "liquid" at a line start to its closing brace at a line start)
        # of the other case replaces this one's; both are this repository's case files.
        def liquid_block(path):
            text = open(path).read()
            m = re.search(r"^liquid\b.*?^\}\n", text, re.M | re.S)
            if not m:
                fc.fail(f"no liquid block in {path}")
            return text, m
        scene_path = os.path.join(case, "constant", "sceneProperties")
        text, m = liquid_block(scene_path)
        _, src = liquid_block(os.path.join(a.root, "cases", a.liquid_case, "constant",
                                           "sceneProperties"))
        with open(scene_path, "w") as f:
            f.write(text[:m.start()] + src.group(0) + text[m.end():])
    def set_entries(path, entries):  # an entry the case has is changed, another one added
        given = foamdict.read_dict(path)
        for kv in entries:
            key, value = kv.split("=", 1)
            if "." in key:  # BLOCK.ENTRY=VALUE: set or insert inside the block (created if absent)
                *blocks, leaf = key.split(".")
                tree = {leaf: value}
                for b in reversed(blocks):
                    tree = {b: tree}
                foamdict.edit_file(path, tree, create_blocks=True)
            elif key in given:
                fc.set_entry(path, key, value)
            else:
                with open(path, "a") as f:
                    end = "" if value.lstrip().startswith("{") else ";"  # a block has no ';'
                    f.write(f"{key} {value}{end}   // test option\n")
    coupling = os.path.join(case, "constant", "couplingProperties")
    set_entries(coupling, a.couple)
    set_entries(os.path.join(case, "constant", "sceneProperties"), a.scene)
    set_entries(os.path.join(case, "system", "cfdDict"), a.cfd)
    set_entries(os.path.join(case, "system", "demDict"), a.dem)
    with open(coupling, "a") as f:
        if a.drag_viscosity:
            f.write(f"DiFeliceDragCoeffs {{ dragViscosity {a.drag_viscosity}; }}   // test option\n")
    env = dict(os.environ, MIXFLOW_ROOT=a.root, PATH=a.bindir + os.pathsep + os.environ["PATH"])
    env.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")
    if a.divergence:
        with open(os.path.join(case, "constant", "couplingProperties"), "a") as f:
            f.write("maxVelocity 1.0;   // test: the collapse exceeds it within 0.2 s\n")
        # One settle at friction 0.1 (sample 0.586, top 0.31 m): the controlled sample's top lies
        # on a cell face (0.300 m), and the air above the gate passes 1 m/s at 3 ms, before the
        # second time-series row this test needs (at 0.586: 21 ms).
        dem_dict = os.path.join(case, "system", "demDict")
        text = open(dem_dict).read()
        with open(dem_dict, "w") as f:
            f.write(re.sub(r"^settle\s*\{[^}]*\}", "settle { friction 0.1; maxTime 3; packingControl off; }",
                           text, flags=re.M))
    r = subprocess.run(["bash", os.path.join(case, "Allrun"), str(a.np)], env=env, cwd=case,
                       capture_output=True, text=True)
    if a.divergence:
        log = open(os.path.join(case, "log.mixflowCoupled")).read()
        dem_rows = rows(os.path.join(case, "postProcessing", "dem", "timeSeries.csv"))
        msg = [ln for ln in log.splitlines() if "the fluid diverged at t =" in ln]
        print(f"exit {r.returncode}; message: {msg[0] if msg else None}; "
              f"{len(dem_rows)} time-series rows kept")
        if r.returncode == 0 or not msg or " at (" not in msg[0] or len(dem_rows) < 2:
            fc.fail("the run did not stop with the place and time, or lost its outputs")
        print("PASS")
        return
    if r.returncode != 0:
        fc.fail(f"Allrun failed ({r.returncode}):\n{r.stdout[-3000:]}\n{r.stderr[-3000:]}")

    ok = check_correctors(case)

    pp = os.path.join(case, "postProcessing")
    ex = rows(os.path.join(pp, "coupling", "exchange.csv"))
    worst_ar = max(float(x["actionReaction"]) for x in ex)
    worst_vol = max(abs(float(x["volumeError"])) for x in ex)
    print(f"{len(ex)} exchanges: worst action-reaction {worst_ar:.3e} (limit 1e-10), "
          f"worst volume error {worst_vol:.3e} (limit 1e-9)")
    ok &= worst_ar <= 1e-10 and worst_vol <= 1e-9

    liq = rows(os.path.join(pp, "liquid", "timeSeries.csv"))
    worst_liq = max(abs(float(x["volume_balance"])) for x in liq)
    print(f"liquid volume balance: worst {worst_liq:.3e} over {len(liq)} steps (limit 1e-6)")
    ok &= worst_liq <= 1e-6

    dem = rows(os.path.join(pp, "dem", "timeSeries.csv"))
    settled = foamdict.read_dict(os.path.join(case, "dem", "settled.state"))["settled"]
    n0 = int(settled["particles"])
    # The settle warns when the sample's fraction is more than 3 % off the target.
    target = float(foamdict.read_dict(os.path.join(case, "constant", "sceneProperties"))["sample"]
                   ["solidFraction"])
    off = abs(float(settled["sampleFraction"]) / target - 1)
    with open(os.path.join(case, "log.mixflowDem")) as f:
        warned = "[dem] warning: the settled sample solid fraction" in f.read()
    print(f"settled fraction {float(settled['sampleFraction']):.4f} against target {target}: "
          f"{100 * off:.1f} % off, warned: {warned}")
    ok &= warned == (off > 0.03)
    last = dem[-1]
    total = (int(last["particles"]) + int(last["deleted_outlet"]) + int(last["deleted_top"]) +
             int(last["lost"]))
    print(f"particles: settled {n0}, at t = {float(last['time_s']):.3f} s remaining "
          f"{last['particles']} + outlet {last['deleted_outlet']} + top {last['deleted_top']} + "
          f"lost {last['lost']} = {total}")
    ok &= total == n0 and float(last["time_s"]) >= a.end - 1e-3

    # The grains' energy budget (kinetic = translational + rotational).
    pe0 = float(dem[0]["pe_J"])
    excess = max(float(x["ke_translational_J"]) + float(x["ke_rotational_J"]) -
                 (pe0 - float(x["pe_J"])) for x in dem)
    print(f"grains: largest kinetic energy beyond the released potential energy {excess:.4g} J"
          + (f" (limit {a.grain_energy_max:g} J)" if a.grain_energy_max is not None else ""))
    if a.grain_energy_max is not None:
        ok &= excess <= a.grain_energy_max

    # Saturation: V_liquid(0) against the pore volume of the settled box.
    height = float(settled["height"])
    scene = foamdict.read_dict(os.path.join(case, "constant", "sceneProperties"))
    L, W = float(scene["sample"]["length"]), float(scene["sample"]["width"])
    vp = math.pi / 6 * float(scene["particles"]["diameter"])**3
    pore = L * height * W - n0 * vp
    v0 = float(liq[0]["volume_domain_m3"])
    # The cell row the settled top cuts is part liquid (alpha) and part particles (eps_f of the
    # whole cell): the liquid there is off by at most the particle volume the row could hold,
    # phi L W dy (dy the cell height); a wrong fill (no liquid, or liquid in the particles) is not.
    dy = 0.6 / round(0.6 / 0.06)
    bound = 0.6056 * L * W * dy
    print(f"initial liquid {v0:.6e} m3 vs pore volume of the settled box {pore:.6e} m3 "
          f"({(v0 / pore - 1) * 100:+.2f} %; bound from the cut cell row "
          f"{bound / pore * 100:.1f} %)")
    ok &= abs(v0 - pore) <= bound

    # Flow height at the back wall: the liquid surface height (pores counted full) of the
    # saturated sample is its settled height, within the cell row the top cuts (dy); the liquid
    # volume depth is the pore part of it, below it by the grains' share of the column.
    surf0 = float(liq[0]["back_wall_surface_m"])
    depth0 = float(liq[0]["back_wall_depth_m"])
    print(f"back wall at t = 0: liquid surface {surf0:.4f} m vs settled height {height:.4f} m "
          f"(bound dy = {dy:.3f} m); liquid volume depth {depth0:.4f} m")
    ok &= abs(surf0 - height) <= dy and depth0 < surf0 - 0.3 * height

    # mixflowExtract on the coupled case, in bins no finer than its cells (0.0606 m; the
    # extractor refuses finer ones).
    NX, NY = 19, 5
    with open(os.path.join(case, "system", "extractDict"), "w") as f:
        f.write("FoamFile { version 2.0; format ascii; class dictionary; object extractDict; }\n"
                f"grid {{ x (-0.012 1.188 {NX}); y (-0.012 0.348 {NY}); }}\n"
                f"windows {{ start 0; end {a.end!r}; width 0.1; }}\n"
                "fluid { source openfoam; }\n"
                "liquidDensity 1000;\n")
    r = subprocess.run([os.path.join(a.bindir, "mixflowExtract"), "-case", case],
                       capture_output=True, text=True, env=env)
    print(r.stdout[-1500:])
    if r.returncode != 0:
        fc.fail(f"mixflowExtract failed ({r.returncode}):\n{r.stderr[-3000:]}")
    import h5py
    import numpy as np
    with h5py.File(os.path.join(pp, "mixture", "mixture.h5"), "r") as h:
        nw = h["windows/t0"].shape[0]
        nx, ny = h["grid/x_edges"].shape[0] - 1, h["grid/y_edges"].shape[0] - 1
        print(f"mixture.h5: {nw} windows, {ny} x {nx} bins")
        ok &= nw == math.ceil(a.end / 0.1 - 1e-6) and (nx, ny) == (NX, NY)
        expect_units = {"alpha_s": "1", "u_s": "m/s", "u_f": "m/s", "p_f": "Pa", "p_s": "Pa",
                        "lambda_u": "1"}
        for name, unit in expect_units.items():
            d = h["fields/" + name]
            got = d.attrs.get("units")
            got = got.decode() if isinstance(got, bytes) else got
            print(f"  {name}: shape {d.shape}, units {got!r}")
            ok &= d.shape == (nw, ny, nx) and got == unit
        a_s = h["fields/alpha_s"][0]
        vol = float(np.nansum(a_s) * (1.2 / NX) * (0.36 / NY) * W)
        nwin = int(dem[0]["particles"])
        err = abs(vol / (nwin * vp) - 1)
        print(f"  window 0: particle volume in bins {vol:.6e} m3 vs N Vp {nwin * vp:.6e} m3 "
              f"(relative {err:.2e}, limit 1e-9)")
        ok &= err <= 1e-9
        # With the DEM's contact snapshots the stress is taken along the contact lines.
        source = h.attrs["stress_source"]
        source = source.decode() if isinstance(source, bytes) else source
        want = "contacts" if "contactSnapshots=on" in a.dem else "virial"
        print(f"  stress from {source} (expected {want})")
        ok &= source == want
    if not ok:
        fc.fail("mixture case checks failed (see above)")
    print("PASS")


if __name__ == "__main__":
    main()
