"""A synthetic CFD-DEM mixture case with known constant drifts for the calibration tests, made
with python/mixflow/synthcase.py and extracted with the real mixflowExtract (so the h5
layout is the extractor's own).

Per (window, bin): u_f = LU u_s + e_u, w_f = LW w_s + e_w, p_f / rho_f = LP p_s / rho_s + e_p.
The noise e = sigma (E - 1), E exponential: mean 0 (least squares is unbiased) but median
-0.31 sigma, with a long positive tail, as the measured ratios' (W+P-quick: p90 49 against a
median 6.4). It does not scale with the solid velocity, so in slow bins (60 %, u_s 0.06-0.10 m/s,
just above the flowing threshold 0.054 m/s) the ratio u_f/u_s carries -0.31 sigma / u_s."""
import subprocess
import sys

import numpy as np

from mixflow import synthcase

LU, LW, LP = 1.3, 0.8, 0.6
SIGMA_U, SIGMA_W, SIGMA_P = 0.1, 0.02, 0.01  # m/s, m/s, m2/s2 (10 Pa of liquid pressure)
RHO_S, RHO_F = 2500.0, 1000.0
SHAPE = (6, 4, 16)  # windows, y bins, x bins: 384 samples over 64 spatial bins


def truth(seed=7, shape=SHAPE):
    rng = np.random.default_rng(seed)
    slow = rng.random(shape) < 0.6
    us = np.where(slow, rng.uniform(0.06, 0.10, shape), rng.uniform(0.5, 1.5, shape))
    ws = rng.choice([-1.0, 1.0], shape) * rng.uniform(0.005, 0.3, shape)
    ps = rng.uniform(50.0, 2000.0, shape)

    def noise(sigma):
        return sigma * (rng.exponential(1.0, shape) - 1.0)

    uf = LU * us + noise(SIGMA_U)
    wf = LW * ws + noise(SIGMA_W)
    pf = RHO_F * (LP * ps / RHO_S + noise(SIGMA_P))
    return dict(us=us, ws=ws, ps=ps, uf=uf, wf=wf, pf=pf)


def make(case, extract_exe, seed=7, shape=SHAPE):
    """Writes and extracts the case; returns truth(seed)."""
    t = truth(seed, shape)
    synthcase.bin_field_case(case, t["us"], t["ws"], t["ps"], t["uf"], t["wf"], t["pf"],
                             rho_s=RHO_S, rho_f=RHO_F)
    r = subprocess.run([extract_exe, "-case", case], capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"mixflowExtract failed on {case}:\n{r.stdout[-3000:]}{r.stderr[-3000:]}")
    return t
