"""The settled bed of run_settled_bed.py through mixflowExtract (--extract): the DEM dumps its
particle snapshots with the per-atom contact virial (LIGGGHTS compute stress/atom, the columns
the scenes dump, dem/SnapshotFiles.cpp), the fluid writes every SNAPSHOT_S, and a side case
holds what the extractor reads (sceneProperties of the bed, the snapshots' series, the fluid
time directories linked from the run, the cell centres and volumes of the box mesh).

The check: in the saturated bed at rest the pore liquid is hydrostatic, so the excess pore
pressure is nil and the pore-pressure ratio chi = p_f_excess / (p_s + p_f_excess), the bulk
model's drifts.porePressureRatio, is its neutral value 0 (docs/bulk_model.md): |chi| <= 0.05 in
every bin of the bed that has one (chi is a share of the grains' load, so 0.05 is 5 % of it; p_s
comes from the contact forces, not from the extractor's own convention)."""
import glob
import os
import re
import shutil
import subprocess

import h5py
import numpy as np

from mixflow import synthcase

SNAPSHOT_S = 0.05  # s between particle snapshots and fluid writes
COLUMNS = ("id type x y z vx vy vz fx fy fz omegax omegay omegaz radius mass c_pstress[1] "
           "c_pstress[2] c_pstress[3] c_pstress[4] c_pstress[5] c_pstress[6]")
CHI_TOL = 0.05


def dem_commands(dt_dem):
    """LIGGGHTS lines: the contact virial and the snapshot dumps (VTK and its binary twin) every
    SNAPSHOT_S from step 0 (the coupled run's t = 0)."""
    every = int(round(SNAPSHOT_S / dt_dem))
    return ("compute pstress all stress/atom\n"
            f"dump snap all custom/vtk {every} VTK/particles/particles_*.vtk {COLUMNS}\n"
            f"dump snapbin all custom {every} VTK/particles/particles_*.bin {COLUMNS}\n")


def write_cells(path, box):
    """constant/C and constant/V of the box mesh (cell order i + nx (j + ny k), blockMesh's)."""
    centres = np.array(list(box.centres()))
    synthcase.foam_field(os.path.join(path, "constant", "C"), "volVectorField", centres)
    synthcase.foam_field(os.path.join(path, "constant", "V"), "volScalarField",
                         np.full(len(centres), box.cell_volume))


def side_case(case, side, box, d, rho_p, rho_l, height, end, dt_dem):
    """The extractor's view of the coupled CASE in SIDE (made anew); returns SIDE."""
    shutil.rmtree(side, ignore_errors=True)
    synthcase.scene(side, L=box.L[0], H=height, W=box.L[2], channel=(2 * box.L[0], box.L[1]), d=d,
                    end_time=end, write_interval=SNAPSHOT_S, content="mixture",
                    liquid_density=rho_l, particle_density=rho_p)
    entries = []
    for f in glob.glob(os.path.join(case, "VTK", "particles", "particles_*.vtk")):
        m = re.search(r"particles_(\d+)\.vtk$", f)  # not the particles_boundingBox_* files
        if m:
            step = int(m.group(1))
            entries.append((f"particles/particles_{step}.vtk", step * dt_dem))
    os.symlink(os.path.join(case, "VTK"), os.path.join(side, "VTK"))
    synthcase.series(side, sorted(entries, key=lambda e: e[1]))
    for name in os.listdir(case):
        try:
            t = float(name)
        except ValueError:
            continue
        if t > 0:
            os.symlink(os.path.join(case, name), os.path.join(side, name))
    write_cells(side, box)
    nx, ny = box.n[0], box.n[1]
    synthcase.write(os.path.join(side, "system/extractDict"),
                    f"grid {{ x (0 {box.L[0]!r} {nx}); y (0 {box.L[1]!r} {ny}); }}\n"
                    f"windows {{ start 0.1; end {end!r}; width 0.1; }}\n"
                    "fluid { source openfoam; liquidFraction alpha.water; }\n")
    synthcase.finish(side)
    return side


def run(exe, case, workdir, box, d, rho_p, rho_l, height, end, dt_dem, check):
    """Extracts the settled bed and checks chi; returns the measured numbers."""
    side = side_case(case, os.path.join(workdir, "extract"), box, d, rho_p, rho_l, height, end,
                     dt_dem)
    r = subprocess.run([exe, "-case", side, "-overwrite"], capture_output=True, text=True)
    if not check(r.returncode == 0, f"mixflowExtract on the settled bed (exit {r.returncode})"):
        print(r.stdout[-3000:] + r.stderr[-3000:])
        return {}
    with h5py.File(os.path.join(side, "postProcessing/mixture/mixture.h5"), "r") as h:
        chi = h["fields/pore_pressure_ratio"][()]
        valid = h["masks/valid_pore_pressure_ratio"][()].astype(bool)
        excess, hydro = h["fields/p_f_excess"][()], h["fields/p_f_hydrostatic"][()]
        ps, lpd = h["fields/p_s"][()], h["fields/lambda_p_density"][()]
        lpk = h["fields/lambda_p_kinematic"][()]
    if not check(valid.any(), "the bed has bins with a pore-pressure ratio"):
        return {}
    worst = float(np.max(np.abs(chi[valid])))
    print(f"pore-pressure ratio in {int(valid.sum())} (window, bin) pairs of the bed: "
          f"{np.nanmin(chi[valid]):+.4f} to {np.nanmax(chi[valid]):+.4f}; p_f_excess "
          f"{np.nanmin(excess[valid]):+.4g} to {np.nanmax(excess[valid]):+.4g} Pa against "
          f"hydrostatic {np.nanmin(hydro[valid]):.4g} to {np.nanmax(hydro[valid]):.4g} Pa and p_s "
          f"{np.nanmin(ps[valid]):.4g} to {np.nanmax(ps[valid]):.4g} Pa; lambda_p_density "
          f"{np.nanmin(lpd[valid]):.3g} to {np.nanmax(lpd[valid]):.3g}, lambda_p_kinematic "
          f"{np.nanmin(lpk[valid]):.3g} to {np.nanmax(lpk[valid]):.3g} in the same bins")
    check(worst <= CHI_TOL,
          f"saturated bed at rest: |chi| <= {CHI_TOL} (the neutral value 0 within 5 % of the "
          f"grains' load): worst {worst:.4f}")
    return {"chi_max_abs": worst, "chi_bins": int(valid.sum()),
            "lambda_p_density_range": [float(np.nanmin(lpd[valid])), float(np.nanmax(lpd[valid]))]}
