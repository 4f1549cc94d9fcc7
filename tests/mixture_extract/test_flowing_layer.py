#!/usr/bin/env python3
"""Coarse-grained stress of mixflowExtract in a steady, uniform flowing granular layer: the
flowing counterpart of extract.contact_stress (a bed at rest).

Set-up: a periodic inclined chute run by the plain `liggghts` binary from the script this test
writes (<case>/dem/in.liggghts): 1820 beads of 12 mm with the project's contact law (Hertz,
tangential history, cdt rolling friction 0.1, friction 0.7, restitution 0.7; E = 7 MPa as
youngModulusFactor 1e-4 gives; dt = 1e-4 s = 0.16 Rayleigh time), periodic in x (the flow, L =
16 d) and z (W = 6 d). The grains settle on a floor for 0.4 s; those below y = 2 d are then frozen
into the rough base (not integrated, v = 0), the floor goes and gravity is tilted by theta = 27 deg
(g = 9.81 (sin, -cos, 0)): a layer 16.5 d deep above the base. In trial runs (periods down to
10 d x 5 d) the layer flows intermittently at 26 deg (creeps, nearly stops, restarts), still
drifts after 15 s at 26.5 deg and keeps accelerating at 29 deg and above; at 27 deg it flows
steadily at a mean 1.1 m/s (2 m/s at the surface). The flowing grains start from a Bagnold profile with
that surface speed, u = 2 (1 - (1 - xi)^1.5), so 2 s of spin-up reach the plateau (from rest it
takes about 12 s). Then 100 snapshots 0.02 s apart (2 s) are dumped with the project's columns
(binary dump, dem/SnapshotFiles.h) and contacts (compute pair/gran/local id force,
dem/ContactDumps.h). The spacing matters: the soft layer rings vertically at about 9 Hz (centre
of mass +-1 mm, its velocity +-50 mm/s); snapshots 0.1 s apart alias it and leave a 15 %
residual, 0.05 s apart sits near its Nyquist limit, 0.02 s resolves it.
mixflowExtract has no periodic x: a contact across x = 0 would be a line the length of the chute,
and a kernel near x = 0 or L would miss the grains beyond. So each snapshot is written for the
extractor with its periodic images within 6 d of the period (x +- L, ids offset by the id span;
every contact line reaching a bin's kernel has both ends there), each contact joining the nearest
images of its grains: every bin of [0, L] sees the periodic layer. The VTK snapshot, its binary
twin, pairs_<step>.txt and walls_<step>.txt (no wall stands) go where mixflowDem writes them.

Extraction: contact-line stress (particles { stress contacts; }), Lucy kernel w = 2 d on 1 d
bins, one window of all 100 snapshots. Rows are averaged over x (uniform flow; the row means of
the d/dx terms vanish). d/dy is the central difference over two rows, and the weight it is
compared with is rho_s alpha_s |g| over the same 2 d (Simpson's rule on the rows), so no O(dy^2)
term is left where alpha_s bends. Interior rows: from 5.5 d above the base's top (no contact line
of a frozen grain, whose support is external, then lies in the Lucy support (4 d) of the rows
the difference uses) to 3 d below the free surface (alpha_s at half its bulk value). Asserted:
  - steadiness: the flowing grains' mean velocity in the window's second half differs from the
    first half's by at most 5 %, their kinetic energy by at most 10 % (u^2): 5 % of 1.1 m/s in
    1 s is an acceleration of 0.6 % of g, an eighth of the balance tolerance (measured +2.0 %,
    +1.5 %);
  - y momentum, each interior row: d sigma_yy/dy = rho_s alpha_s g cos(theta) within 5 % of
    rho_s alpha_s |g| (tension positive: sigma_yy rises toward the surface; measured 2.1 %,
    mean 0.9 %);
  - x momentum, each interior row: d sigma_xy/dy = -rho_s alpha_s g sin(theta) within 5 %
    (sigma_xy > 0: the faster grains above drag those below downslope; measured 2.7 %, mean
    1.2 %);
  - the balance integrated from the surface: sigma_xy / -sigma_yy = tan(theta) in every interior
    row within 5 % (both carry the weight of the same grains above, so the local bound holds for
    their ratio; measured 2.1 %);
  - what is left is the flow's, not the extractor's: for each snapshot d sigma/dy = F - rho g +
    d sigma_kinetic/dy exactly, F the density of the dumped contact forces + weight (the
    contact-line split). F and sigma_kinetic are recomputed here from the snapshots with the
    same kernel (their alpha_s matches the extractor's to 1e-9, their p_s_kinetic to 1e-6;
    measured 3e-15), and the residuals equal the window's mean of F and d sigma_kinetic/dy
    within 1 % of rho_s alpha_s |g| (measured 0.02 % in y, 0.46 % in x: the extractor keeps the
    symmetric part of f (x) b, and the antisymmetric rest, from the tangential forces' couples
    against rolling resistance, has a y gradient of that size). F itself fluctuates by 30 % of
    rho_s alpha_s g per row and snapshot (collisions, the 9 Hz ringing): its mean over the 100
    snapshots is the 1-3 % residual.
Printed: the kinetic stress's share (p_s_kinetic / p_s about 2 % in the interior, of sigma_yy
1 %, of sigma_xy 0.2-0.4 %; rising to 10 % at the surface), and how far the dumped contact forces
are from those LIGGGHTS integrated: compute pair/gran/local re-evaluates them at the dump with
the step's final velocities (damping, tangential force), 0.6 % of rho_s alpha_s |g| in x here.
Wall time about 50 s on one core (LIGGGHTS 30 s).

usage: test_flowing_layer.py MIXFLOWEXTRACT LIGGGHTS WORKDIR"""
import math
import os
import shutil
import subprocess
import sys
import time

import h5py
import numpy as np

from mixflow import outputs, synthcase
from mixflow.synthcase import checker

D, RHO_S, G = 0.012, 2500.0, 9.81
THETA = math.radians(27.0)
L, W = 16 * D, 6 * D            # periods in x and z
NX, NZ, LAYERS = 13, 5, 28      # loose lattice the grains settle from: 1820 grains
BASE_TOP = 2 * D                # grains below are frozen into the rough base
DT = 1e-4
SETTLE_S, SPINUP_S = 0.4, 2.0
EVERY, SNAPSHOTS = 200, 100     # snapshots 0.02 s apart over 2 s
SURFACE_SPEED = 2.0             # m/s, the steady layer's (Bagnold start)
GRID_TOP, NY = 22 * D, 22       # 1 d bins to 4 d above the surface
KERNEL_WIDTH = 2                # Lucy w in d (cutoff 2 w)
REACH = 6 * D                   # periodic images kept within this of [0, L]
BELOW_SURFACE, ABOVE_BASE = 3 * D, 5.5 * D
TOL_STEADY_U, TOL_STEADY_KE, TOL_BALANCE, TOL_RATIO, TOL_IDENTITY = 0.05, 0.10, 0.05, 0.05, 0.01
COLS = outputs.SNAPSHOT_COLUMNS
PAIR_FORMAT = "%.0f %.0f %.0f %.9g %.9g %.9g"


def initial_data(path):
    """A loose jittered lattice with random velocities (0.1 m/s) the grains settle from."""
    rng = np.random.default_rng(1)
    ax, az, ay = L / NX, W / NZ, 1.2 * D
    i, j, k = np.meshgrid(np.arange(NX), np.arange(LAYERS), np.arange(NZ), indexing="ij")
    x = np.column_stack([(i.ravel() + 0.5) * ax, 0.5 * D + j.ravel() * ay, (k.ravel() + 0.5) * az])
    x += rng.uniform(-0.1 * D, 0.1 * D, x.shape)
    v = rng.normal(0.0, 0.1, x.shape)
    n = len(x)
    lines = [f"periodic chute layer\n\n{n} atoms\n2 atom types\n\n0 {L:.10g} xlo xhi\n"
             f"{-D:.10g} {60 * D:.10g} ylo yhi\n0 {W:.10g} zlo zhi\n\nAtoms\n"]
    lines += [f"{a + 1} 1 {D} {RHO_S} {p[0]:.10g} {p[1]:.10g} {p[2]:.10g}" for a, p in enumerate(x)]
    lines += ["\nVelocities\n"]
    lines += [f"{a + 1} {u[0]:.6g} {u[1]:.6g} {u[2]:.6g} 0 0 0" for a, u in enumerate(v)]
    synthcase.write(path, "\n".join(lines) + "\n")
    return n


def liggghts_script(case):
    """The chute: project materials (dem/LiggghtsCommands.cpp at youngModulusFactor 1e-4), settle,
    freeze the base, tilt gravity, spin up, then the snapshot and contact dumps."""
    raw = os.path.join(case, "dem", "raw")
    contact = "model hertz tangential history rolling_friction cdt"
    columns = " ".join(COLS)
    s, c = math.sin(THETA), math.cos(THETA)
    return f"""# Periodic inclined chute (tests/mixture_extract/test_flowing_layer.py)
units si
atom_style granular
atom_modify map array
boundary p f p
newton off
communicate single vel yes
processors 1 1 1
read_data {case}/dem/initial.data
neighbor {0.2 * D:.10g} bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 7000000 70000000
fix m2 all property/global poissonsRatio peratomtype 0.3 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 2 0.7 0.7 0.7 0.7
fix m4 all property/global coefficientFriction peratomtypepair 2 0.7 0.7 0.7 0.7
fix m5 all property/global coefficientRollingFriction peratomtypepair 2 0.1 0.1 0.1 0.1
pair_style gran {contact} limitForce on
pair_coeff * *
timestep {DT:.10g}
fix gravi all gravity 9.81 vector 0.0 -1.0 0.0
fix wBottom all wall/gran {contact} primitive type 2 yplane 0 limitForce on
fix integr all nve/sphere
compute pstress all stress/atom
compute pgl all pair/gran/local id force
thermo_style custom step atoms ke
thermo {round(0.1 / DT)}
run {round(SETTLE_S / DT)}
# The rough base: grains below {BASE_TOP:.10g} m frozen (not integrated); no floor under them.
region baseRegion block INF INF INF {BASE_TOP:.10g} INF INF units box
group base region baseRegion
group flow subtract all base
unfix integr
fix integr flow nve/sphere
velocity base set 0 0 0
unfix wBottom
# Start near the steady state: Bagnold's profile with the layer's surface speed.
variable h equal bound(flow,ymax)
variable ub atom {SURFACE_SPEED:.10g}*(1-(1-(y-{BASE_TOP:.10g})/(${{h}}+{0.5 * D - BASE_TOP:.10g}))^1.5)
velocity flow set v_ub 0.0 0.0
unfix gravi
fix gravi all gravity 9.81 vector {s:.12g} {-c:.12g} 0.0
compute meanVx flow reduce ave vx
compute keFlow flow ke
thermo_style custom step atoms c_keFlow c_meanVx
thermo {round(0.1 / DT)}
run {round(SPINUP_S / DT)}
reset_timestep 0
dump snap all custom {EVERY} {raw}/snap_*.bin {columns}
dump contacts all local {EVERY} {raw}/pairs_*.txt c_pgl[1] c_pgl[2] c_pgl[3] c_pgl[4] c_pgl[5] c_pgl[6]
dump_modify contacts format "{PAIR_FORMAT}"
run {(SNAPSHOTS - 1) * EVERY}
"""


def run_chute(liggghts, case):
    if os.path.exists(case):
        shutil.rmtree(case)
    os.makedirs(os.path.join(case, "dem", "raw"))
    # The case files mixflowExtract reads (the grid lies inside this channel); the chute's script
    # replaces the dem/in.liggghts written here (the same compute pstress line).
    synthcase.scene(case, L=L, H=0.25, W=W, channel=(0.8, 0.4), d=D,
                    end_time=(SNAPSHOTS - 1) * EVERY * DT, write_interval=EVERY * DT)
    n = initial_data(os.path.join(case, "dem", "initial.data"))
    script = os.path.join(case, "dem", "in.liggghts")
    synthcase.write(script, liggghts_script(case))
    t0 = time.time()
    r = subprocess.run([liggghts, "-in", script, "-log", os.path.join(case, "dem", "log.liggghts")],
                       capture_output=True, text=True, cwd=os.path.join(case, "dem"))
    if r.returncode != 0:
        print(r.stdout[-3000:], r.stderr[-3000:])
        sys.exit(1)
    print(f"liggghts: {n} grains, {SETTLE_S + SPINUP_S + (SNAPSHOTS - 1) * EVERY * DT:.1f} s "
          f"simulated in {time.time() - t0:.0f} s")


def read_pairs(path):
    """Rows id1 id2 periodic fx fy fz of a LIGGGHTS dump local file."""
    with open(path) as f:
        lines = f.read().split("\n")
    start = next(i for i, line in enumerate(lines) if line.startswith("ITEM: ENTRIES")) + 1
    count = int(lines[lines.index("ITEM: NUMBER OF ENTRIES") + 1])
    pairs = np.loadtxt(lines[start:start + count], ndmin=2) if count else np.zeros((0, 6))
    return pairs.reshape(-1, 6)


def with_images(rows, pairs):
    """The snapshot's rows and contacts with the periodic images within REACH of [0, L]: image k
    (x + k L, k = -1, 0, 1) has its ids offset by (k mod 3) x the id span; a contact joins every
    present image of its first grain to the nearest image of its second. Also returns each image
    row's index in ROWS."""
    ids = rows[:, COLS.index("id")].astype(np.int64)
    x = rows[:, COLS.index("x")]
    span = int(ids.max()) + 1
    present = np.zeros((3, span), bool)
    xpos = np.zeros(span)
    xpos[ids] = x
    parts, src = [], []
    for k in (0, -1, 1):
        keep = (x + k * L >= -REACH) & (x + k * L < L + REACH)
        src.append(np.nonzero(keep)[0])
        img = rows[keep].copy()
        img[:, COLS.index("x")] += k * L
        img[:, COLS.index("id")] += (k % 3) * span
        present[k % 3, ids[keep]] = True
        parts.append(img)
    i, j = pairs[:, 0].astype(np.int64), pairs[:, 1].astype(np.int64)
    shift = np.rint((xpos[i] - xpos[j]) / L).astype(np.int64)  # image of j nearest to i
    out = []
    for k in (0, -1, 1):
        kj = k + shift
        ok = (np.abs(kj) <= 1) & present[k % 3, i] & present[kj % 3, j]
        p = pairs[ok].copy()
        p[:, 0] = i[ok] + (k % 3) * span
        p[:, 1] = j[ok] + (kj[ok] % 3) * span
        out.append(p)
    return np.vstack(parts), np.vstack(out), np.concatenate(src)


class KernelRows:
    """Row means (over the x bins) of Lucy-kernel sums at the bin centres, averaged over the
    snapshots, computed here from the snapshots alone: density; the force density F = sum f psi
    with f = the grain's dumped contact forces (pairs file) + m g, which the contact-line stress
    balances exactly, and with f = the snapshot's total force (ma_x, ma_y: m a as LIGGGHTS
    integrated it);
    the kinetic stress -sum m v'v' psi with v' about the bin's kernel velocity, computed as
    -(sum m v v psi - rho V V) (xx yy zz xy)."""
    names = ("rho", "fx", "fy", "ma_x", "ma_y", "kxx", "kyy", "kzz", "kxy")

    def __init__(self):
        self.xb = (np.arange(round(L / D)) + 0.5) * D
        self.yb = (np.arange(NY) + 0.5) * (GRID_TOP / NY)
        self.sums = {q: np.zeros(NY) for q in self.names}
        self.count = 0

    def add(self, rows, contact_force):
        c = 2 * D * KERNEL_WIDTH  # Lucy cutoff
        x, y, m = (rows[:, COLS.index(q)] for q in ("x", "y", "mass"))
        v = rows[:, [COLS.index("vx"), COLS.index("vy"), COLS.index("vz")]]
        r = np.hypot(self.xb[None, None, :] - x[:, None, None],
                     self.yb[None, :, None] - y[:, None, None])
        psi = np.where(r < c, 5 / (math.pi * c * c) * (1 + 3 * r / c) * (1 - r / c) ** 3, 0.0) / W

        def field(q):
            return np.einsum("i,iyx->yx", q, psi)

        rho = field(m)
        mom = [field(m * v[:, a]) for a in range(3)]
        safe = np.where(rho > 0, rho, 1.0)
        values = {"rho": rho, "fx": field(contact_force[:, 0] + m * G * math.sin(THETA)),
                  "fy": field(contact_force[:, 1] - m * G * math.cos(THETA)),
                  "ma_x": field(rows[:, COLS.index("fx")]), "ma_y": field(rows[:, COLS.index("fy")])}
        for name, a, b in (("kxx", 0, 0), ("kyy", 1, 1), ("kzz", 2, 2), ("kxy", 0, 1)):
            values[name] = -(field(m * v[:, a] * v[:, b]) - mom[a] * mom[b] / safe)
        for q in self.names:
            self.sums[q] += values[q].mean(axis=1)
        self.count += 1

    def rows(self):
        return {q: s / self.count for q, s in self.sums.items()}


def write_case(case, kernel_rows):
    """Each LIGGGHTS dump with its periodic images in mixflowDem's layout (VTK and binary twin,
    contact files; the raw dumps are removed once written), the series and the extractDict.
    Returns the base's top (m) and per snapshot the flowing grains' mean u and kinetic energy."""
    raw = os.path.join(case, "dem", "raw")
    c = COLS
    entries, steadiness = [], []
    base_top = 0.0
    walls = " ".join(f"f_force_{w}[{q}]" for w in ("wBottom", "wBack") for q in (1, 2, 3))
    for k in range(SNAPSHOTS):
        step = k * EVERY
        snap, contacts = os.path.join(raw, f"snap_{step}.bin"), os.path.join(raw, f"pairs_{step}.txt")
        rows, pairs = outputs.read_binary_snapshot(snap), read_pairs(contacts)
        v = rows[:, [c.index("vx"), c.index("vy"), c.index("vz")]]
        frozen = ~v.any(axis=1)  # the base: never integrated, v = 0 exactly
        base_top = max(base_top, (rows[frozen, c.index("y")] + rows[frozen, c.index("radius")]).max())
        m = rows[~frozen, c.index("mass")]
        steadiness.append((m @ v[~frozen, 0] / m.sum(), 0.5 * m @ (v[~frozen] ** 2).sum(axis=1)))
        unordered = {(min(a, b), max(a, b)) for a, b in pairs[:, :2].astype(np.int64)}
        if len(unordered) != len(pairs):
            raise SystemExit(f"{contacts}: {len(pairs) - len(unordered)} contacts listed twice")
        contact_force = np.zeros((len(rows), 3))  # on each grain, from the pairs file
        index = np.zeros(int(rows[:, c.index("id")].max()) + 1, np.int64)
        index[rows[:, c.index("id")].astype(np.int64)] = np.arange(len(rows))
        np.add.at(contact_force, index[pairs[:, 0].astype(np.int64)], pairs[:, 3:6])
        np.add.at(contact_force, index[pairs[:, 1].astype(np.int64)], -pairs[:, 3:6])
        rows, pairs, src = with_images(rows, pairs)
        kernel_rows.add(rows, contact_force[src])
        name = f"particles/particles_{step}.vtk"
        col = {q: rows[:, [c.index(q + a) for a in "xyz"]] for q in ("", "v", "f", "omega")}
        synthcase.vtk(os.path.join(case, "VTK", name), col[""], col["v"], rows[:, c.index("mass")],
                      rows[:, c.index("radius")], rows[:, c.index("c_pstress[1]"):c.index("c_pstress[6]") + 1],
                      ids=rows[:, c.index("id")].astype(np.int64), force=col["f"], omega=col["omega"])
        outputs.write_binary_snapshot(os.path.join(case, outputs.SNAPSHOT_BIN.format(step=step)), rows,
                                      step=step, box=(-REACH, L + REACH, -D, 60 * D, 0, W))
        head = f"ITEM: TIMESTEP\n{step}\n"
        synthcase.write(os.path.join(case, f"VTK/contacts/pairs_{step}.txt"),
                        head + f"ITEM: NUMBER OF ENTRIES\n{len(pairs)}\nITEM: ENTRIES "
                        + " ".join(f"c_pgl[{q}]" for q in range(1, 7)) + "\n"
                        + "".join((PAIR_FORMAT + "\n") % tuple(p) for p in pairs))
        synthcase.write(os.path.join(case, f"VTK/contacts/walls_{step}.txt"),
                        head + f"ITEM: NUMBER OF ATOMS\n0\nITEM: ATOMS id {walls}\n")
        entries.append((name, step * DT))
        os.remove(snap)
        os.remove(contacts)
    synthcase.series(case, entries)
    synthcase.write(os.path.join(case, "system/extractDict"),
                    f"grid {{ x (0 {L:.10g} {round(L / D)}); y (0 {GRID_TOP:.10g} {NY}); }}\n"
                    f"windows {{ list ((0 {SNAPSHOTS * EVERY * DT:.10g})); }}\n"
                    "fluid { source none; }\nparticles { stress contacts; }\n"
                    f"kernel {{ shape lucy; width {KERNEL_WIDTH}; }}\n"
                    "output postProcessing/mixture/flowing;\n")
    synthcase.finish(case)
    return base_top, np.array(steadiness)


def central(q, dy):
    """Central difference over two rows (NaN in the first and last)."""
    out = np.full_like(q, np.nan)
    out[1:-1] = (q[2:] - q[:-2]) / (2 * dy)
    return out


def slab(q):
    """Simpson's mean of q over the two rows' span [y - dy, y + dy]: what a central difference of
    its integral gives, so the balance below carries no O(dy^2) error where alpha_s bends."""
    out = np.full_like(q, np.nan)
    out[1:-1] = (q[2:] + 4 * q[1:-1] + q[:-2]) / 6
    return out


def check_steady(steady, check):
    """The flowing grains' mean velocity and kinetic energy, second half of the window against the
    first."""
    half = SNAPSHOTS // 2
    u, ke = steady[:, 0], steady[:, 1]
    du, dke = u[half:].mean() / u[:half].mean() - 1, ke[half:].mean() / ke[:half].mean() - 1
    print("flowing grains: t(s)  mean u(m/s)  kinetic energy(J)")
    for k in range(0, SNAPSHOTS, 10):
        print(f"  {k * EVERY * DT:5.2f}  {u[k]:.4f}  {ke[k]:.4f}")
    check(abs(du) <= TOL_STEADY_U, f"steady: mean velocity {u[:half].mean():.4f} -> {u[half:].mean():.4f} "
          f"m/s over the window's halves, change {du:+.4f} (tolerance {TOL_STEADY_U:.0%})")
    check(abs(dke) <= TOL_STEADY_KE, f"steady: kinetic energy of the flowing grains changes by {dke:+.4f} "
          f"over the window's halves (tolerance {TOL_STEADY_KE:.0%})")


def extracted_rows(exe, case):
    """mixflowExtract on the case: the window's fields, averaged over the x bins, and the row
    centres."""
    rc, log = synthcase.run_extract(exe, case, "-overwrite")
    if rc != 0:
        print(log)
        sys.exit(1)
    with h5py.File(os.path.join(case, "postProcessing/mixture/flowing.h5"), "r") as f:
        assert f.attrs["stress_source"] == "contacts", f.attrs["stress_source"]
        assert int(f["windows/n_snapshots"][0]) == SNAPSHOTS, f["windows/n_snapshots"][()]
        ye = f["grid/y_edges"][()]
        row = {q: f[f"fields/{q}"][0].mean(axis=1) for q in
               ("alpha_s", "sigma_s_yy", "sigma_s_xy", "p_s", "p_s_kinetic", "u_s")}
    return row, 0.5 * (ye[1:] + ye[:-1])


def main():
    exe, liggghts, work = sys.argv[1:4]
    t_start = time.time()
    failures = []
    check = checker(failures)
    case = os.path.join(work, "chute")
    run_chute(liggghts, case)
    kernel = KernelRows()
    base_top, steady = write_case(case, kernel)
    check_steady(steady, check)
    row, yc = extracted_rows(exe, case)
    dy = yc[1] - yc[0]

    a = row["alpha_s"]
    # The free surface: alpha_s at half its mean over 5-10 d above the base (linear between rows).
    plateau = a[(yc > base_top + 5 * D) & (yc < base_top + 10 * D)].mean()
    j = np.nonzero((yc > base_top + 5 * D) & (a < 0.5 * plateau))[0][0]
    surface = yc[j - 1] + (a[j - 1] - 0.5 * plateau) / (a[j - 1] - a[j]) * dy
    inside = (yc > base_top + ABOVE_BASE) & (yc < surface - BELOW_SURFACE)
    print(f"base top {base_top:.4f} m, surface (alpha_s half of {plateau:.3f}) {surface:.4f} m, "
          f"interior rows {yc[inside][0]:.3f} ... {yc[inside][-1]:.3f} m")
    rho_g = RHO_S * a * G
    weight = slab(rho_g)  # rho_s alpha_s |g| over [y - dy, y + dy]
    res_y = (central(row["sigma_s_yy"], dy) - weight * math.cos(THETA)) / rho_g
    res_x = (central(row["sigma_s_xy"], dy) + weight * math.sin(THETA)) / rho_g
    ratio = row["sigma_s_xy"] / -row["sigma_s_yy"] / math.tan(THETA) - 1

    # What the residuals are: d sigma/dy = slab(F - rho g) + d sigma_kinetic/dy exactly for each
    # snapshot, F the dumped contact forces' density + rho g (the contact-line split).
    k = kernel.rows()
    check(np.abs(k["rho"][inside] / (RHO_S * a[inside]) - 1).max() <= 1e-9,
          "the kernel sums here give the extractor's alpha_s (1e-9)")
    p_kin = -(k["kxx"] + k["kyy"] + k["kzz"]) / 3
    worst = np.abs(p_kin[inside] / row["p_s_kinetic"][inside] - 1).max()
    check(worst <= 1e-6, f"p_s_kinetic = -tr(sum m v'v' psi)/3 with v' about the bin's kernel velocity, "
          f"as computed here, within {worst:.1e} (tolerance 1e-6)")
    expect_y = (slab(k["fy"]) + central(k["kyy"], dy)) / rho_g
    expect_x = (slab(k["fx"]) + central(k["kxy"], dy)) / rho_g
    reevaluated = [np.abs(slab(k["ma_" + q]) - slab(k["f" + q])) / rho_g for q in "xy"]

    print(" row  y(m)  alpha_s -syy(Pa) sxy(Pa) u_s(m/s) | res_y  F+dk(y) | res_x  F+dk(x) | "
          "sxy/-syy/tan-1 | kinetic share: p_s  syy    sxy")
    for j in range(1, len(yc) - 1):
        if a[j] < 0.05:
            continue
        print(f"{'*' if inside[j] else ' '}{j:3d} {yc[j]:.3f}  {a[j]:.3f}  {-row['sigma_s_yy'][j]:7.1f} "
              f"{row['sigma_s_xy'][j]:6.1f}  {row['u_s'][j]:6.3f}  | {res_y[j]:+.4f} {expect_y[j]:+.4f} | "
              f"{res_x[j]:+.4f} {expect_x[j]:+.4f} | {ratio[j]:+.4f}        | "
              f"{row['p_s_kinetic'][j] / row['p_s'][j]:.4f} {k['kyy'][j] / row['sigma_s_yy'][j]:.4f} "
              f"{k['kxy'][j] / row['sigma_s_xy'][j]:.4f}")
    for label, res in (("y momentum: d sigma_yy/dy = rho_s alpha_s g cos(theta)", res_y),
                       ("x momentum: d sigma_xy/dy = -rho_s alpha_s g sin(theta)", res_x)):
        worst = np.abs(res[inside]).max()
        check(worst <= TOL_BALANCE, f"{label} within {worst:.4f} of rho_s alpha_s |g| (mean |residual| "
              f"{np.abs(res[inside]).mean():.4f}; tolerance {TOL_BALANCE:.0%})")
    worst = np.abs(ratio[inside]).max()
    check(worst <= TOL_RATIO, f"sigma_xy / -sigma_yy = tan(theta) = {math.tan(THETA):.4f} within {worst:.4f} "
          f"(tolerance {TOL_RATIO:.0%})")
    for label, res, expect in (("y", res_y, expect_y), ("x", res_x, expect_x)):
        worst = np.abs(res - expect)[inside].max()
        check(worst <= TOL_IDENTITY, f"{label} residual = the window's mean contact force density + "
              f"weight (F) and kinetic-stress gradient within {worst:.4f} of rho_s alpha_s |g| "
              f"(tolerance {TOL_IDENTITY:.0%})")
    print(f"the dumped contact forces against the integrator's (m a): force densities apart by at most "
          f"{reevaluated[0][inside].max():.4f} (x), {reevaluated[1][inside].max():.4f} (y) of rho_s alpha_s |g| "
          f"(compute pair/gran/local re-evaluates them with the step's final velocities)")
    shares = {"p_s": row["p_s_kinetic"] / row["p_s"], "sigma_yy": k["kyy"] / row["sigma_s_yy"],
              "sigma_xy": k["kxy"] / row["sigma_s_xy"]}
    print("kinetic share in the interior: " + ", ".join(
        f"{q} {v[inside].min():.4f} ... {v[inside].max():.4f}" for q, v in shares.items()))
    print(f"wall time {time.time() - t_start:.0f} s")
    print(f"{len(failures)} failure(s)")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
