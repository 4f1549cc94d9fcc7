"""What the result scripts derive from a finished scene's outputs (report.py, mixture_results.py,
tier_trade.py): the Scene (its time series, summary and sample), particle snapshots, fronts, the
Froude rule's subcritical time, back-wall heights, energies and Eqs. 13-14, Savage numbers, stage
changes and the dry runout law. Each derived number is None where the outputs do not allow it.
Needs numpy (Debian's /usr/bin/python3)."""

import itertools
import json
import math
import os
import sys

import numpy as np

from .foamcase import execution_time, execution_times, read_internal_field, time_dirs
from .foamdict import read_dict, unquote
from .froude import first_time, subcritical_after_arrival
from .outputs import END_TOLERANCE_S, STAGE_TIMES, interpolated as at, read_rows
from .paper import D_P, DRY_SERIES, G, PAPER_NAME
from .runout import fit_power_law, power_law_slope_error, thickness_front


def col(rows, key):
    return np.array([r.get(key, np.nan) for r in rows], dtype=float)


class Scene:
    """One scene's outputs in the work directory (attributes None where absent)."""

    def __init__(self, work, name):
        self.name, self.paper_name = name, PAPER_NAME.get(name, name)
        self.dir = os.path.join(work, name)
        self.done = os.path.isfile(os.path.join(self.dir, ".done"))
        self.exists = os.path.isdir(self.dir)
        self.failed = os.path.isfile(os.path.join(self.dir, ".failed"))
        self.tier = self.content = None
        self.tier_set = ""  # the suite's --set entries for this run (system/tier)
        self.dem = self.liquid = self._exchange = self.summary = None
        self.deposit = self.velocity = self.profiles = None
        self.width = self.H = self.L = None
        if not self.done:
            return
        tier_file = os.path.join(self.dir, "system", "tier")
        if os.path.isfile(tier_file):
            rec = read_dict(tier_file)
            self.tier, self.content = rec.get("tier"), rec.get("content")
            self.tier_set = unquote(rec.get("set", ""))
        sp = read_dict(os.path.join(self.dir, "constant", "sceneProperties"))
        self.content = self.content or sp.get("content")
        self.L, self.H, self.width = (float(sp["sample"][k]) for k in ("length", "height", "width"))
        pp = os.path.join(self.dir, "postProcessing")
        opt = {"dem": "dem/timeSeries.csv", "liquid": "liquid/timeSeries.csv",
               "deposit": "dem/depositProfile.csv",
               "velocity": "dem/velocityProfile.csv", "profiles": "liquid/profiles.csv"}
        for attr, rel in opt.items():
            path = os.path.join(pp, rel)
            if os.path.isfile(path):
                setattr(self, attr, read_rows(path))
        path = os.path.join(pp, "dem", "summary.json")
        if os.path.isfile(path):
            with open(path) as f:
                self.summary = json.load(f)
            self.tier = self.tier or self.summary.get("tier")

    @property
    def exchange(self):
        """postProcessing/coupling/exchange.csv's rows, read at first use: one row per exchange,
        so a run at one DEM step per exchange holds about 150 MB per simulated second."""
        if self._exchange is None and self.done:
            path = os.path.join(self.dir, "postProcessing", "coupling", "exchange.csv")
            self._exchange = read_rows(path) if os.path.isfile(path) else None
        return self._exchange

    def t_end(self):
        for rows in (self.liquid, self.dem):
            if rows:
                return rows[-1]["time_s"]
        return None


def convergence_error(row, partner):
    """partner - row for every number both have: the scalars, the numbers of a dict one level down
    (per time, per quantile) and lists of numbers of equal length; counts (int) are not errors."""
    err = {}
    for k, v in row.items():
        p = partner.get(k)
        if isinstance(v, dict) and isinstance(p, dict):
            err[k] = {q: p[q] - x for q, x in v.items()
                      if isinstance(x, float) and isinstance(p.get(q), float)}
        elif isinstance(v, float) and isinstance(p, float):
            err[k] = p - v
        elif (isinstance(v, list) and isinstance(p, list) and len(v) == len(p)
              and all(isinstance(x, (int, float)) for x in v + p)):
            err[k] = [b - a for a, b in zip(v, p)]
    return err


def first_finished(works, name):
    """Scene NAME from the first work directory where it finished, else from the first; one whose
    outputs cannot be read is reported and counts as not run."""
    try:
        found = [w for w in works if os.path.isfile(os.path.join(w, name, ".done"))]
        return Scene((found or works)[0], name)
    except Exception as e:  # noqa: BLE001  one unreadable scene never stops a report
        print(f"{name}: cannot read its outputs: {e}", file=sys.stderr)
        return Scene("/nonexistent", name)


def vtk_series(case_dir):
    """[(time, path)] of the particle snapshots (VTK/particles.vtk.series)."""
    path = os.path.join(case_dir, "VTK", "particles.vtk.series")
    if not os.path.isfile(path):
        return []
    with open(path) as f:
        files = json.load(f)["files"]
    return [(float(e["time"]), os.path.join(case_dir, "VTK", e["name"])) for e in files]


def vtk_points(path):
    """Particle centres of a legacy ASCII VTK file written by LIGGGHTS: array (n, 3)."""
    with open(path) as f:
        for line in f:
            if line.startswith("POINTS"):
                n = int(line.split()[1])
                break
        else:
            return np.zeros((0, 3))
        vals = []
        while len(vals) < 3 * n:
            vals += f.readline().split()
    return np.array(vals[:3 * n], dtype=float).reshape(n, 3)


def _surface_bins(points, x_max, d):
    """The bin edges of one diameter over [0, X_MAX] and each point's bin index (-1 or past the
    last bin: outside)."""
    edges = np.arange(0.0, x_max + d, d)
    return edges, np.digitize(points[:, 0], edges) - 1


def granular_surface(points, x_max, d=D_P):
    """Top of the granular layer per bin of one diameter: max y + d/2 of the bin's grains (nan
    where a bin holds fewer than 2 grains, so a lone bouncing grain is no surface)."""
    edges, idx = _surface_bins(points, x_max, d)
    h = np.full(len(edges) - 1, np.nan)
    for i in range(len(h)):
        ys = points[idx == i, 1]
        if len(ys) >= 2:
            h[i] = ys.max() + d / 2
    return 0.5 * (edges[1:] + edges[:-1]), h


def surface_grains(points, x_max, d=D_P):
    """The grains that make granular_surface(POINTS, X_MAX, D): the two highest of each bin (all
    of a bin with fewer), so the surface of the subset is the surface of all."""
    edges, idx = _surface_bins(points, x_max, d)
    keep = []
    for i in range(len(edges) - 1):
        members = np.flatnonzero(idx == i)
        keep.extend(members[np.argsort(points[members, 1])[-2:]])
    return points[np.sort(np.array(keep, dtype=int))]


# Derived numbers

def liquid_front(s):
    return (col(s.liquid, "time_s"), col(s.liquid, "front_bed_m")) if s.liquid else None


def liquid_depth_front(s, t, depth=0.5 * D_P):
    """Largest x where the liquid's volume depth (profiles.csv depth_m) falls through DEPTH,
    interpolated between columns, at the profile write nearest t (within 0.02 s; None otherwise).
    Unlike front_bed_m (the bed cell row at alpha >= 0.5, half a cell deep) its threshold is a
    physical depth, the same on every mesh."""
    if not s.profiles:
        return None
    times = sorted({r["time_s"] for r in s.profiles}, key=lambda x: abs(x - t))
    if not times or abs(times[0] - t) > 0.02:
        return None
    pts = sorted((r["x_m"], r["depth_m"]) for r in s.profiles if r["time_s"] == times[0])
    front = None
    for (x0, h0), (x1, h1) in zip(pts, pts[1:]):
        if h0 >= depth > h1:
            front = x0 + (h0 - depth) / (h0 - h1) * (x1 - x0)
    return front


def solver_log(s):
    """The scene's solver log: log.mixflowCoupled, log.mixflowDem or log.mixflowFoam; None."""
    for name in ("log.mixflowCoupled", "log.mixflowDem", "log.mixflowFoam"):
        if os.path.isfile(os.path.join(s.dir, name)):
            return os.path.join(s.dir, name)
    return None


def solver_cpu(s):
    """CPU seconds of the scene's solver process, summed over a resumed run's attempts; None."""
    log = solver_log(s)
    return execution_time(log) if log else None


def stage_times(s):
    """Where a mixture run's wall time went: postProcessing/coupling/stageTimes.csv summed per
    stage (rank 0's DEM interval and exchange stages), the solver's clock time, and the rest
    (fluid step, writes, start-up) = clock - stages; None without both."""
    path = os.path.join(s.dir, STAGE_TIMES)
    log = solver_log(s)
    clock = execution_times(log) if log else None
    if not os.path.isfile(path) or not clock:
        return None
    with open(path) as f:  # '#' comment lines, the header, then one row per exchange
        lines = (ln for ln in f if not ln.startswith("#"))
        keys = next(lines, "").strip().split(",")
        first = next(lines, None)
        if first is None:
            return None
        try:  # numpy's parser; the rows' reader skips a row a stopped run cut short
            sums = np.loadtxt(itertools.chain([first], lines), delimiter=",", ndmin=2).sum(axis=0)
        except ValueError:
            rows = read_rows(path)
            if not rows:
                return None
            sums = [sum(r[k] for r in rows) for k in keys]
    out = {k: float(v) for k, v in zip(keys, sums) if k not in ("time", "demStep")}
    out["clock_s"] = clock["clock_s"]
    out["fluid_and_rest"] = clock["clock_s"] - sum(v for k, v in out.items() if k != "clock_s")
    return out


def deposit_difference(s, ref):
    """Relative L1 difference of two scenes' end profiles h(x) (depositProfile.csv, volume
    depth): sum |h - h_ref| / sum h_ref over the shared bins; None without both profiles or when
    they are of different times (a ladder value taken on past the others' end)."""
    if not s.deposit or not ref.deposit:
        return None
    if abs(float(s.deposit[0]["time_s"]) - float(ref.deposit[0]["time_s"])) > END_TOLERANCE_S:
        return None
    h, h_ref = col(s.deposit, "h_volume_m"), col(ref.deposit, "h_volume_m")
    n = min(len(h), len(h_ref))
    total = float(np.nansum(h_ref[:n]))
    return float(np.nansum(np.abs(h[:n] - h_ref[:n])) / total) if total > 0 else None


def deposit_tail(s):
    """The end deposit's front by packed volume depth (first bin beyond L whose grain volume is
    less than one packed grain layer) beside the column-top front (front_thickness_x_m's rule),
    and the share of the deposit's grain volume beyond the volume front. On a slice 2-3 columns
    wide one grain in a column raises its top, so a sheet or spray of a few grains ahead of the
    body moves the column-top front and not the volume front; None without a profile."""
    if not s.deposit:
        return None
    front = thickness_front(s.deposit, s.L, D_P, column="h_volume_m")
    x, h = col(s.deposit, "x_m"), col(s.deposit, "h_volume_m")
    total = float(np.nansum(h))
    return {"time_s": float(s.deposit[0]["time_s"]), "volume_front_m": front,
            "top_front_m": thickness_front(s.deposit, s.L, D_P),
            "volume_beyond_volume_front": float(np.nansum(h[x > front]) / total) if total > 0
            else None}


def liquid_over_gate(s):
    """The liquid volume (alpha.liquid x voidfraction x V, m3) beyond the gate (x > L) in the
    column's upper half (y > H/2) at each field write, {time_s: m3}: the liquid that drains over
    the gate's top corner, ahead of the grains, which is where the implicit drag's schemes part
    first. None without the cell centres and volumes in 0/ (Cx, Cy, V) or field writes in the
    case directory (reconstructed, on ranks)."""
    zero = os.path.join(s.dir, "0")
    if not s.done or not all(os.path.isfile(os.path.join(zero, f)) for f in ("Cx", "Cy", "V")):
        return None
    x, y, vol = (np.array(read_internal_field(os.path.join(zero, f))) for f in ("Cx", "Cy", "V"))
    upper = (x > s.L) & (y > 0.5 * s.H)
    out = {}
    for t, name in time_dirs(s.dir):
        fields = [os.path.join(s.dir, name, f) for f in ("alpha.liquid", "voidfraction")]
        if t == 0 or not all(os.path.isfile(f) for f in fields):
            continue
        alpha, eps = (np.array(read_internal_field(f, len(x))) for f in fields)
        out[f"{t:.3g}"] = float(np.sum((alpha * eps * vol)[upper]))
    return out or None


def granular_front(s):
    return (col(s.dem, "time_s"), col(s.dem, "front_x_m")) if s.dem else None


def subcritical(s):
    """(t0, t - t0) of the Froude rule of mixflow liquid-results, or (t0, None)."""
    if not s.liquid:
        return None, None
    t0, ts = subcritical_after_arrival(s.liquid)
    return t0, (None if ts is None or t0 is None else ts - t0)


def subcritical_volume_depth(s):
    """t - t0 of the same rule with h = the liquid volume depth in Fr (froudeDepth volume), for a
    run whose section_froude used the surface height; None if not available or never."""
    if not s.liquid or "section_surface_m" not in s.liquid[0]:
        return None
    rows = [dict(r, section_froude=(r["section_velocity_m_s"] /
                                    math.sqrt(G * r["section_depth_m"])
                                    if r["section_depth_m"] > 0 else math.nan))
            for r in s.liquid]
    t0, ts = subcritical_after_arrival(rows)
    return None if t0 is None or ts is None else ts - t0


def back_wall_key(s):
    """The series column of the flow height at the back wall: the liquid surface height
    (back_wall_surface_m, the pores of a saturated granular layer counted full: the paper's
    "maximum flow height near the left boundary wall"), or, in a run written before that column
    existed, the liquid volume depth (the same without particles, about eps_f times the surface
    height in a saturated mixture)."""
    return "back_wall_surface_m" if s.liquid and "back_wall_surface_m" in s.liquid[0] \
        else "back_wall_depth_m"


def back_wall(s, t):
    if not s.liquid or s.liquid[-1]["time_s"] < t:
        return None
    return at(s.liquid, back_wall_key(s), t) / s.H


def particle_energies(s):
    """(t, E_kp, E_pp) per metre of width (J/m): translational + rotational kinetic energy."""
    if not s.dem:
        return None
    t = col(s.dem, "time_s")
    ek = col(s.dem, "ke_translational_J") + np.nan_to_num(col(s.dem, "ke_rotational_J"))
    return t, ek / s.width, col(s.dem, "pe_J") / s.width


def energy_excess(s):
    """Energy the scene made: max over t of E_k(t) - (E_p(0) - E_p(t)), grains (translational +
    rotational) and liquid together, J per metre of width, with (t, E_k, released) there. A
    closed scene without inflow only dissipates, so this stays <= 0 but for the elastic energy
    the settled sample stores in its contacts (not in E_p; the dry scene P shows its size) and
    what a numerical scheme creates. Grains or liquid leaving through the outlet take their
    energies along, which keeps the inequality. None without energies."""
    parts = [particle_energies(s)] if s.dem else []  # (t, E_k, E_p) per metre of width
    if s.liquid:
        parts.append((col(s.liquid, "time_s"), col(s.liquid, "kinetic_energy_J") / s.width,
                      col(s.liquid, "potential_energy_J") / s.width))
    if not parts:
        return None
    t = parts[0][0]
    t = t[t <= min(p[0][-1] for p in parts)]
    ek = sum(np.interp(t, tp, k) for tp, k, _ in parts)
    released = sum(p[0] - np.interp(t, tp, p) for tp, _, p in parts)
    i = int(np.argmax(ek - released))
    return {"excess_J_per_m": ek[i] - released[i], "t_s": t[i], "kinetic_J_per_m": ek[i],
            "released_J_per_m": released[i]}


def e_pd(mix, dry):
    """Eq. 13 with energies per metre of width: (loss_mixture - loss_dry) / loss_dry,
    loss = E_pp0 - E_pp - E_kp; the dry loss interpolated at the mixture's times."""
    a, b = particle_energies(mix), particle_energies(dry)
    if a is None or b is None:
        return None
    ta, eka, epa = a
    tb, ekb, epb = b
    loss_m = epa[0] - epa - eka
    loss_d = np.interp(ta, tb, epb[0] - epb - ekb, right=np.nan)
    with np.errstate(divide="ignore", invalid="ignore"):
        r = (loss_m - loss_d) / loss_d
    ok = (loss_d > 1e-3 * epb[0]) & np.isfinite(r)
    return ta[ok], r[ok]


def e_fc(s):
    """Eq. 14: (E_pf0 - (E_pf + E_kf)) / E_pf0 of the liquid."""
    if not s.liquid:
        return None
    ep, ek = col(s.liquid, "potential_energy_J"), col(s.liquid, "kinetic_energy_J")
    return col(s.liquid, "time_s"), (ep[0] - (ep + ek)) / ep[0]


def savage(s):
    """(t, N_sav, column): the paper's form (Eq. 16 as printed, d_p; column savage_paper) where
    the time series has it, else another N_sav column that is not Iverson's d_p^2/h form."""
    cols = list(s.dem[0]) if s.dem else []
    pick = [c for c in ("savage_paper", "savage") if c in cols] or \
        [c for c in cols if c.startswith("savage") and not c.endswith("_m") and "iverson" not in c]
    if not pick:
        return None
    return col(s.dem, "time_s"), col(s.dem, pick[0]), pick[0]


def collision_interval(t, n, threshold=0.1):
    """First and last time of the longest run with N_sav > threshold."""
    best, start = None, None
    for i, v in enumerate(list(n) + [-1]):
        if v > threshold and start is None:
            start = i
        elif not v > threshold and start is not None:
            if best is None or t[i - 1] - t[start] > best[1] - best[0]:
                best = (t[start], t[i - 1])
            start = None
    return best


def stage_change(t, x):
    """Time the front's speed first falls below half its peak after the peak (speed from
    0.05 s differences): the end of the fast stage."""
    if t is None or len(t) < 3:
        return None
    grid = np.arange(t[0], t[-1], 0.05)
    if len(grid) < 3:
        return None
    v = np.gradient(np.interp(grid, t, x), grid)
    k = int(np.argmax(v))
    slow = np.nonzero(v[k:] < 0.5 * v[k])[0]
    return float(grid[k + slow[0]]) if len(slow) else None


def outflow_start(s):
    if not s.liquid:
        return None
    return first_time(s.liquid, lambda r: r["volume_outlet_m3"] > 1e-3 * r["volume_domain_m3"])


def runout_law(scenes):
    """Fit of (l_inf - L)/L = lambda a^alpha over the finished P-I-* scenes (both front rules), of
    one tier: the one most of them ran at (the finer on a tie), since tiers differ in stiffness and
    geometry; the others are listed in "left_out"."""
    done = [scenes[n] for n in DRY_SERIES if scenes[n].done and scenes[n].summary]
    tiers = [s.tier for s in done]
    rank = {"quick": 0, "reference": 1, "paper-window": 2, "paper": 3}
    tier = max(set(tiers), key=lambda t: (tiers.count(t), rank.get(t, -1))) if tiers else None
    left_out = [s.name for s in done if s.tier != tier]
    rows = []
    for s in done:
        if s.tier != tier:
            continue
        name = s.name
        L = s.summary["sample"]["length_m"]
        a = s.summary["settled"]["height_m"] / L
        thick = thickness_front(s.deposit, L, D_P)
        rows.append({"scene": name, "a": a, "runout": s.summary["runout_m"] / L, "thick": (thick - L) / L,
                     "stop_reason": s.summary.get("stop_reason"), "end_time_s": s.summary.get("end_time_s")})
    if len(rows) < 2:
        return {"rows": rows, "tier": tier, "left_out": left_out}
    a = [r["a"] for r in rows]
    alpha, lam = fit_power_law(a, [r["runout"] for r in rows])
    alpha_t, lam_t = fit_power_law(a, [r["thick"] for r in rows])
    return {"rows": rows, "tier": tier, "left_out": left_out, "alpha": alpha, "lambda": lam,
            "alpha_standard_error": power_law_slope_error(a, [r["runout"] for r in rows]),
            "alpha_thickness": alpha_t, "lambda_thickness": lam_t,
            "alpha_thickness_standard_error": power_law_slope_error(a, [r["thick"] for r in rows])}


# Writing them

def fmt(v, nd=3):
    """Our numbers: NA as '-', floats to ND significant digits."""
    if v is None:
        return "-"
    if isinstance(v, float):
        return f"{v:.{nd}g}"
    return str(v)


def clean(o):
    """JSON-safe copy: NaN/inf -> None, numpy numbers -> Python ones."""
    if isinstance(o, dict):
        return {str(k): clean(v) for k, v in o.items()}
    if isinstance(o, (list, tuple)):
        return [clean(v) for v in o]
    if isinstance(o, (np.floating, float)):
        return None if not math.isfinite(float(o)) else float(o)
    if isinstance(o, np.integer):
        return int(o)
    if isinstance(o, np.bool_):
        return bool(o)
    return o
