"""The dry runout law (l_inf - L)/L = lambda a^alpha: its fit and the deposit's thickness front
(mixflow runout-fit, report.py, lube_small_columns.py)."""

import math


def fit_power_law(a, r):
    """Least squares on log r = log lambda + alpha log a."""
    xs = [math.log(v) for v in a]
    ys = [math.log(v) for v in r]
    n = len(xs)
    mx, my = sum(xs) / n, sum(ys) / n
    sxx = sum((x - mx) ** 2 for x in xs)
    sxy = sum((x - mx) * (y - my) for x, y in zip(xs, ys))
    alpha = sxy / sxx
    return alpha, math.exp(my - alpha * mx)


def power_law_slope_error(a, r):
    """Standard error of fit_power_law's alpha (residual variance over n - 2 degrees of
    freedom); None for fewer than three points."""
    xs = [math.log(v) for v in a]
    ys = [math.log(v) for v in r]
    n = len(xs)
    if n < 3:
        return None
    alpha, lam = fit_power_law(a, r)
    mx = sum(xs) / n
    res = sum((y - math.log(lam) - alpha * x) ** 2 for x, y in zip(xs, ys))
    return math.sqrt(res / (n - 2) / sum((x - mx) ** 2 for x in xs))


def thickness_front(rows, L, d, column="h_top_m"):
    """First bin beyond L whose width-averaged column top (or, with column h_volume_m, whose
    grain volume as a packed depth) is below one grain: its left edge. ROWS: a deposit profile's
    (dem/depositProfile.csv, outputs.read_rows)."""
    xs = [float(r["x_m"]) for r in rows]
    dx = xs[1] - xs[0]
    for r, x in zip(rows, xs):
        if x > L and float(r[column]) < d:
            return max(L, x - 0.5 * dx)
    return xs[-1] + 0.5 * dx
