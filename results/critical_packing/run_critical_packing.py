#!/usr/bin/python3
"""Critical packing (critical-state solid fraction) of mixflow's grains by plane shear at imposed
normal stress (GDR MiDi 2004; da Cruz et al. 2005).

A box periodic in x and y (10 d x 6 d) holds ~1200 free grains between two rough walls, each a
square lattice (spacing d) of grains with a random z offset within +-0.25 d. The bottom wall is
frozen; the top wall translates rigidly, at speed V in x, and in z under the group-average
contact force plus -P A (fix aveforce). No gravity. The grains and the contact law are the
project's (cases/P/constant/sceneProperties; dem/LiggghtsCommands.cpp): Hertz, tangential
history, rolling friction cdt, limitForce on, d = 0.024 m, rho = 2500 kg/m3, E = 70 GPa x
youngModulusFactor, nu = 0.3, e = 0.7, friction 0.7, rolling friction 0.1, dt = 0.1 T_Rayleigh.

Each shear run (shear.in, I a variable) starts from the previous run's end state (largest I
first, after a compression without shear, prepare.in); V = I sqrt(P/rho) h / d with h the gap
between the wall surfaces. The solid fraction phi, the stress tensor (contact part from
stress/atom, kinetic part from the velocity fluctuations) and the shear rate (slope of <vx>(z))
are measured in the central slab, 5 d away from each wall surface (mean wall-grain centre -/+ d/2),
over the steady window (nominal strain after the transient); the mean velocity is linear in z
only beyond about 5 d from the walls. A slab 3 d from the walls gives the check fit_margin_3d. The local inertial number
I = gdot d / sqrt(P/rho) uses the measured slope and the measured central normal stress.
phi(I) = phi_c - b I is fitted by weighted least squares.

Usage: run_critical_packing.py [--analyse-only] [--cases TAG,...]
Writes critical_packing.csv, critical_packing.json, critical_packing.png in this directory.
"""
import argparse, json, math, os, resource, subprocess, sys, time
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import gen

D, RHO, E0, NU = gen.D, gen.RHO, 70e9, 0.3
H_COL, PHI_COL, G = 0.6, 0.6056, 9.81
P = RHO * PHI_COL * G * H_COL / 2          # 4456 Pa: mid-depth pressure of the column
RAYLEIGH_FRACTION = 0.1
CENTRE_MARGIN = 5.0                        # d from each wall surface (3 d as a check)
CHECK_MARGIN = 3.0
DSTRAIN_DUMP, DSTRAIN_AVE = 0.05, 0.02
NICE = ["nice", "-n", "15"]

# (tag, youngModulusFactor, I, total strain, transient strain, restart to start from)
CASES = [
    ("y1e-3_I0.2",   1e-3, 0.2,   12.0, 2.0, "prep_y1e-3"),
    ("y1e-3_I0.1",   1e-3, 0.1,   12.0, 2.0, "y1e-3_I0.2"),
    ("y1e-3_I0.05",  1e-3, 0.05,  12.0, 2.0, "y1e-3_I0.1"),
    ("y1e-3_I0.02",  1e-3, 0.02,  12.0, 2.0, "y1e-3_I0.05"),
    ("y1e-3_I0.01",  1e-3, 0.01,  12.0, 2.0, "y1e-3_I0.02"),
    ("y1e-3_I0.005", 1e-3, 0.005, 10.0, 2.0, "y1e-3_I0.01"),
    ("y1e-2_I0.1",   1e-2, 0.1,   10.0, 2.0, "y1e-3_I0.1"),
    ("y1e-2_I0.02",  1e-2, 0.02,  10.0, 2.0, "y1e-2_I0.1"),
    ("y1e-3_I0.002", 1e-3, 0.002,  6.0, 2.0, "y1e-3_I0.005"),
]
PREP_STEPS = 20000                         # prepare: 0.78 s at youngModulusFactor 1e-3


def dt_for(yfac):
    return RAYLEIGH_FRACTION * gen.rayleigh_time(E0 * yfac, NU)


def common_vars(yfac, geo):
    return {"yfac": yfac, "E0": E0, "dt": repr(dt_for(yfac)), "nskin": 0.2 * D, "P": repr(P),
            "area": repr(geo["area"]), "ntop": geo["ntop"]}


def liggghts(infile, variables, log, workdir):
    cmd = NICE + ["/usr/bin/liggghts", "-in", os.path.join(HERE, infile), "-log", log,
                  "-echo", "none"]
    for k, v in variables.items():
        cmd += ["-var", k, str(v)]
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.time()
    with open(os.path.join(workdir, log + ".screen"), "w") as out:
        subprocess.run(cmd, cwd=workdir, stdout=out, stderr=subprocess.STDOUT, check=True)
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
    return cpu, time.time() - t0, " ".join(cmd)


def run_cases(work, tags):
    os.makedirs(work, exist_ok=True)
    os.symlink(os.path.join(HERE, "materials.in"), os.path.join(work, "materials.in")) \
        if not os.path.exists(os.path.join(work, "materials.in")) else None
    geo = gen.write_data(os.path.join(work, "cell.data"))
    cpu_log = os.path.join(work, "cpu.json")
    cpu = json.load(open(cpu_log)) if os.path.exists(cpu_log) else {}
    for tag, yfac, I, strain, trans, start in CASES:
        if tags and tag not in tags:
            continue
        if os.path.exists(os.path.join(work, tag + ".restart")):
            continue
        if start.startswith("prep_") and not os.path.exists(os.path.join(work, start + ".restart")):
            v = common_vars(yfac, geo)
            v.update(data="cell.data", restart=start + ".restart",
                     nsteps=PREP_STEPS)
            c, w, cmd = liggghts("prepare.in", v, start + ".log", work)
            cpu[start] = c
            print(f"{start}: cpu {c:.0f} s, wall {w:.0f} s", flush=True)
        v = common_vars(yfac, geo)
        v.update(restin=start + ".restart", restout=tag + ".restart", tag=tag, I=I, rho=RHO, d=D,
                 strain=strain, dstrainDump=DSTRAIN_DUMP, dstrainAve=DSTRAIN_AVE)
        c, w, cmd = liggghts("shear.in", v, tag + ".log", work)
        cpu[tag] = c
        json.dump(cpu, open(cpu_log, "w"), indent=1)
        print(f"{tag}: cpu {c:.0f} s, wall {w:.0f} s", flush=True)
    json.dump(cpu, open(cpu_log, "w"), indent=1)
    return geo


# ---------------------------------------------------------------- analysis
_DUMP_CACHE = {}


def read_dump(path):
    if path in _DUMP_CACHE:
        return _DUMP_CACHE[path]
    _DUMP_CACHE.clear()
    snaps = []
    with open(path) as f:
        while True:
            line = f.readline()
            if not line:
                break
            step = int(f.readline()); f.readline(); n = int(f.readline())
            f.readline(); f.readline(); f.readline(); f.readline(); f.readline()
            a = np.loadtxt([f.readline() for _ in range(n)])
            snaps.append((step, a))
    _DUMP_CACHE[path] = snaps
    return snaps


def slab_volume_of_spheres(zc, lo, hi, r):
    """Volume of spheres (centres zc, radius r) inside lo < z < hi."""
    a = np.clip(lo - zc, -r, r); b = np.clip(hi - zc, -r, r)
    f = lambda u: math.pi * (r * r * u - u ** 3 / 3.0)
    return f(b) - f(a)


def mean_overlap(a, box):
    """Mean and max relative overlap delta/d over free-free contacts of one snapshot."""
    free = a[a[:, 1] == 1][:, 2:5]
    dx = free[:, None, :] - free[None, :, :]
    dx[..., 0] -= box[0] * np.round(dx[..., 0] / box[0])
    dx[..., 1] -= box[1] * np.round(dx[..., 1] / box[1])
    r = np.sqrt((dx ** 2).sum(-1))
    iu = np.triu_indices(len(free), 1)
    r = r[iu]
    ov = (D - r[r < D]) / D
    z = 2.0 * len(ov) / len(free)
    return float(ov.mean()), float(ov.max()), z


def analyse_run(work, tag, yfac, I, strain, trans, geo, margin=CENTRE_MARGIN, profiles=True):
    area = geo["area"]; m = RHO * math.pi / 6 * D ** 3
    log = open(os.path.join(work, tag + ".log.screen")).read()
    line = [l for l in log.splitlines() if l.startswith("SHEAR I")][-1].split()
    gdot_nom, h0, V = float(line[4]), float(line[6]), float(line[8])
    dt = dt_for(yfac)
    snaps = read_dump(os.path.join(work, f"dump_{tag}.txt"))
    rows = []; prof_phi = []; prof_v = []
    for step, a in snaps:
        gam = gdot_nom * dt * step
        if gam < trans - 1e-9:
            continue
        t = a[:, 1]
        zb = a[t == 2, 4].mean() + D / 2; zt = a[t == 3, 4].mean() - D / 2
        lo, hi = zb + margin * D, zt - margin * D
        fr = a[t == 1]
        vol = area * (hi - lo)
        phi = slab_volume_of_spheres(fr[:, 4], lo, hi, D / 2).sum() / vol
        inside = fr[(fr[:, 4] > lo) & (fr[:, 4] < hi)]
        z, vx, vy, vz = inside[:, 4], inside[:, 5], inside[:, 6], inside[:, 7]
        slope, icpt = np.polyfit(z, vx, 1)
        dvx = vx - (slope * z + icpt)
        s = inside[:, 8:14]                      # xx yy zz xy xz yz, stress*volume (pair)
        szz = (-s[:, 2].sum() + m * (vz * vz).sum()) / vol
        sxz = (-s[:, 4].sum() + m * (dvx * vz).sum()) / vol
        sxx = (-s[:, 0].sum() + m * (dvx * dvx).sum()) / vol
        syy = (-s[:, 1].sum() + m * (vy * vy).sum()) / vol
        rows.append((gam, phi, slope, szz, sxz, (sxx + syy + szz) / 3, zt - zb))
        if profiles:   # phi and <vx>/V in bins of d/2 from the bottom wall surface
            edges = zb + D * np.arange(0, (zt - zb) / D, 0.5)
            prof_phi.append([slab_volume_of_spheres(fr[:, 4], e, e + 0.5 * D, D / 2).sum()
                             / (area * 0.5 * D) for e in edges[:-1]])
            zz = (fr[:, 4] - zb) / D
            prof_v.append([fr[(zz >= k * 0.5) & (zz < k * 0.5 + 0.5), 5].mean() / V
                           for k in range(len(edges) - 1)])
    r = np.array(rows)
    gam, phi, gd, szz, sxz, pm, h = r.T
    # standard error of a correlated series: sqrt(var * tau / n), tau the integrated
    # autocorrelation (in snapshots) summed up to its first zero crossing
    def mean_se(x):
        y = x - x.mean(); n = len(y); v = (y * y).mean()
        tau = 1.0
        for k in range(1, n // 2):
            a = (y[:n - k] * y[k:]).mean() / v
            if a <= 0:
                break
            tau += 2 * a
        return float(x.mean()), float(math.sqrt(v * tau / n))
    nb = max(2, int(round(gam[-1] - gam[0])))       # blocks of one unit of strain, as a check
    blocks = np.array_split(np.arange(len(gam)), nb)
    phi_block_se = float(np.std([phi[b].mean() for b in blocks], ddof=1) / math.sqrt(nb))
    _y = phi - phi.mean(); _n = len(_y); _tau = 1.0
    for k in range(1, _n // 2):
        a = (_y[:_n - k] * _y[k:]).mean() / (_y * _y).mean()
        if a <= 0:
            break
        _tau += 2 * a
    phi_corr_strain = float(_tau * (gam[1] - gam[0]))
    phi_m, phi_se = mean_se(phi)
    gd_m, gd_se = mean_se(gd)
    szz_m, szz_se = mean_se(szz)
    mu_series = np.abs(sxz) / szz
    mu_m = float(abs(sxz.mean()) / szz_m)
    _, mu_se = mean_se(mu_series)
    I_loc = gd_m * D / math.sqrt(szz_m / RHO)
    I_se = I_loc * math.hypot(gd_se / gd_m, 0.5 * szz_se / szz_m)
    # top-wall forces from the time series (averages over DSTRAIN_AVE)
    ts = np.loadtxt(os.path.join(work, f"ts_{tag}.txt"))
    tsg = gdot_nom * dt * ts[:, 0]
    w = tsg >= trans
    Pw = ts[w, 5].mean() / area
    tauw = -ts[w, 6].mean() / area
    ov = mean_overlap(snaps[-1][1], (gen.LX, gen.LY))
    # phi over the whole-gap transient for the plot of the time series
    return {"tag": tag, "youngModulusFactor": yfac, "I_target": I, "I": I_loc, "I_se": I_se,
            "gdot": gd_m, "gdot_nominal_wall": V / h0, "V_wall": V, "P_central": szz_m,
            "P_central_se": szz_se, "P_wall": float(Pw), "phi": phi_m, "phi_se": phi_se,
            "phi_std_snapshots": float(phi.std(ddof=1)),
            "phi_second_minus_first_half": float(phi[len(phi) // 2:].mean() - phi[:len(phi) // 2].mean()), "mu": mu_m, "mu_se": mu_se,
            "mu_wall": float(tauw / Pw), "gap_d": float(h.mean() / D),
            "strain_window": [float(gam[0]), float(gam[-1])], "n_snapshots": len(gam),
            "phi_se_blocks_of_unit_strain": phi_block_se,
            "phi_correlation_strain": phi_corr_strain, "mean_overlap_over_d": ov[0], "max_overlap_over_d": ov[1],
            "coordination_geometric": ov[2], "dt": dt,
            "series": {"strain": gam.tolist(), "phi": phi.tolist()},
            "profile": profile(prof_phi, prof_v) if profiles else None}


def profile(pp, pv):
    n = min(len(p) for p in pp)
    return {"z_over_d": (0.25 + 0.5 * np.arange(n)).tolist(),
            "phi": np.mean([p[:n] for p in pp], axis=0).tolist(),
            "vx_over_V": np.nanmean([p[:n] for p in pv], axis=0).tolist()}


def fit_line(I, phi, se):
    w = 1.0 / np.asarray(se) ** 2
    A = np.vstack([np.ones_like(I), -np.asarray(I)]).T
    cov = np.linalg.inv(A.T @ (A * w[:, None]))
    coef = cov @ (A.T @ (w * phi))
    res = phi - A @ coef
    chi2 = float((w * res ** 2).sum()); dof = len(I) - 2
    # scale the covariance by the reduced chi^2 when the scatter exceeds the error bars
    scale = max(1.0, chi2 / dof) if dof > 0 else 1.0
    err = np.sqrt(np.diag(cov) * scale)
    return {"phi_c": float(coef[0]), "phi_c_error": float(err[0]), "b": float(coef[1]),
            "b_error": float(err[1]), "chi2": chi2, "dof": dof, "error_scaled_by_chi2": scale > 1}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--analyse-only", action="store_true")
    ap.add_argument("--cases", default="")
    ap.add_argument("--work", default=os.path.join(HERE, "work"))
    args = ap.parse_args()
    tags = [t for t in args.cases.split(",") if t]
    if args.analyse_only:
        geo = gen.write_data(os.path.join(args.work, "cell.data"))
    else:
        geo = run_cases(args.work, tags)
    cpu = json.load(open(os.path.join(args.work, "cpu.json")))
    runs = []
    for tag, yfac, I, strain, trans, start in CASES:
        if os.path.exists(os.path.join(args.work, tag + ".restart")):
            r = analyse_run(args.work, tag, yfac, I, strain, trans, geo)
            r["cpu_s"] = cpu.get(tag, float("nan"))
            r5 = analyse_run(args.work, tag, yfac, I, strain, trans, geo, margin=CHECK_MARGIN,
                             profiles=False)
            r["check_margin_3d"] = {k: r5[k] for k in ("I", "I_se", "phi", "phi_se", "mu",
                                                        "gdot", "P_central")}
            runs.append(r)
    ref = [r for r in runs if r["youngModulusFactor"] == 1e-3 and r["I_target"] <= 0.1]
    fit = fit_line(np.array([r["I"] for r in ref]), np.array([r["phi"] for r in ref]),
                   np.array([r["phi_se"] for r in ref]))
    fit["youngModulusFactor"] = 1e-3
    fit["I_range"] = [min(r["I"] for r in ref), max(r["I"] for r in ref)]
    fit["runs"] = [r["tag"] for r in ref]
    allref = [r for r in runs if r["youngModulusFactor"] == 1e-3]
    fit_all = fit_line(np.array([r["I"] for r in allref]), np.array([r["phi"] for r in allref]),
                       np.array([r["phi_se"] for r in allref]))
    fit_all["runs"] = [r["tag"] for r in allref]
    c5 = [r["check_margin_3d"] for r in ref]
    fit5 = fit_line(np.array([c["I"] for c in c5]), np.array([c["phi"] for c in c5]),
                    np.array([c["phi_se"] for c in c5]))
    fit5["note"] = "same runs, central slab 3 d from each wall surface instead of 5 d"
    estar = E0 * 1e-3 / (2 * (1 - NU ** 2))
    # central slab: CENTRE_MARGIN d from each wall surface
    with open(os.path.join(HERE, "critical_packing.csv"), "w") as f:
        f.write("tag,youngModulusFactor,I_target,I,I_se,shear_rate_1_s,P_central_Pa,P_wall_Pa,"
                "phi_mean,phi_std_error,phi_correlation_strain,mu_central,mu_wall,strain_start,strain_end,gap_d,"
                "mean_overlap_over_d,cpu_s\n")
        for r in runs:
            f.write(f"{r['tag']},{r['youngModulusFactor']:g},{r['I_target']:g},{r['I']:.5f},"
                    f"{r['I_se']:.5f},{r['gdot']:.4f},{r['P_central']:.1f},{r['P_wall']:.1f},"
                    f"{r['phi']:.5f},{r['phi_se']:.5f},{r['phi_correlation_strain']:.2f},{r['mu']:.4f},{r['mu_wall']:.4f},"
                    f"{r['strain_window'][0]:.2f},{r['strain_window'][1]:.2f},{r['gap_d']:.2f},"
                    f"{r['mean_overlap_over_d']:.2e},{r['cpu_s']:.0f}\n")
    cmd = ("nice -n 15 /usr/bin/python3 run_critical_packing.py  (runs every case serially in "
           "work/, then analyses; --analyse-only re-analyses an existing work/)")
    out = {"phi_c": fit["phi_c"], "phi_c_error": fit["phi_c_error"], "fit": fit,
           "fit_including_I_0.2": fit_all, "fit_margin_3d": fit5,
           "pressure_Pa": P, "kappa_Estar_over_P": {"1e-3": estar / P, "1e-2": 10 * estar / P},
           "project_sample_phi": PHI_COL,
           "project_sample_is": "dense" if PHI_COL > fit["phi_c"] else "loose",
           "loose_sample_phi": 0.569,
           "loose_sample_is": "dense" if 0.569 > fit["phi_c"] else "loose",
           "cpu_s_total": float(sum(cpu.values())),
           "runs": [{k: v for k, v in r.items() if k not in ("series", "profile")} for r in runs],
           "profiles": {r["tag"]: r["profile"] for r in runs},
           "method": __doc__.split("Usage:")[0].strip(), "command": cmd}
    json.dump(out, open(os.path.join(HERE, "critical_packing.json"), "w"), indent=1)
    plot(runs, fit, os.path.join(HERE, "critical_packing.png"))
    print(json.dumps({k: out[k] for k in ("phi_c", "phi_c_error", "fit", "kappa_Estar_over_P",
                                          "cpu_s_total")}, indent=1))


def plot(runs, fit, path):
    import matplotlib; matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(2, 2, figsize=(13, 9)); ax = ax.ravel()
    for yf, c, lab in ((1e-3, "C0", "youngModulusFactor 1e-3"), (1e-2, "C3", "youngModulusFactor 1e-2")):
        rs = [r for r in runs if r["youngModulusFactor"] == yf]
        if not rs: continue
        ax[0].errorbar([r["I"] for r in rs], [r["phi"] for r in rs], yerr=[r["phi_se"] for r in rs],
                       xerr=[r["I_se"] for r in rs], fmt="o", color=c, capsize=3, label=lab)
        ax[1].errorbar([r["I"] for r in rs], [r["mu"] for r in rs], yerr=[r["mu_se"] for r in rs],
                       fmt="o", color=c, capsize=3, label=lab + " (central stress)")
        ax[1].plot([r["I"] for r in rs], [r["mu_wall"] for r in rs], "x", color=c,
                   label=lab + " (top wall)")
    Imax = max(r["I"] for r in runs) * 1.05
    x = np.linspace(0, Imax, 50)
    ax[0].plot(x, fit["phi_c"] - fit["b"] * x, "k-",
               label=f"fit I<=0.1 ({CENTRE_MARGIN:g} d slab): phi_c = {fit['phi_c']:.4f} ± {fit['phi_c_error']:.4f}")
    ax[0].axhline(PHI_COL, color="g", ls="--", label=f"project column {PHI_COL}")
    ax[0].axhline(0.569, color="m", ls=":", label="project loose sample 0.569")
    ax[0].set_xlabel(f"I (central slab, {CENTRE_MARGIN:g} d from the walls)"); ax[0].set_ylabel("solid fraction (central slab)")
    ax[0].set_xlim(0, Imax); ax[0].legend(fontsize=8)
    ax[1].set_xlabel("I"); ax[1].set_ylabel("mu = tau / P"); ax[1].set_xlim(0, Imax)
    ax[1].legend(fontsize=8)
    for r in runs:
        ax[2].plot(r["series"]["strain"], r["series"]["phi"], lw=0.8,
                   label=r["tag"])
    ax[2].set_xlabel("nominal strain (steady window)"); ax[2].set_ylabel("phi (central slab)")
    ax[2].legend(fontsize=7)
    axv = ax[3].twinx(); axv.set_ylabel("<vx> / V (dashed)"); axv.set_ylim(0, 1)
    for i, r in enumerate(runs):
        p = r["profile"]
        ax[3].plot(p["z_over_d"], p["phi"], lw=0.9, color=f"C{i}", label=r["tag"])
        axv.plot(p["z_over_d"], p["vx_over_V"], lw=0.9, ls="--", color=f"C{i}")
    ax[3].axvline(CENTRE_MARGIN, color="k", lw=0.5)
    ax[3].axvline(CHECK_MARGIN, color="k", lw=0.5, ls=":")
    ax[3].set_xlabel("z / d from the bottom wall surface")
    ax[3].set_ylabel("phi in bins of d/2 (solid)")
    ax[3].set_ylim(0.45, 0.62); ax[3].legend(fontsize=7)
    fig.suptitle(f"Critical packing by plane shear at P = {P:.0f} Pa (rough walls, 10d x 6d, no gravity)")
    fig.tight_layout(); fig.savefig(path, dpi=120)


if __name__ == "__main__":
    main()
