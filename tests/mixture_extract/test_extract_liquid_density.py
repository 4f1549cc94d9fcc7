#!/usr/bin/env python3
"""mixflowExtract takes the liquid's density from the case:
without liquidDensity in extractDict, lambda_p_density = (p_f / rho_f) / (p_s / rho_s) uses
constant/sceneProperties liquid.density (1260 kg/m3 here, a glycerol-like liquid), not 1000; an explicit
liquidDensity wins, with a warning naming both values; a scene without a liquid and without
liquidDensity is refused before anything is written when the density convention needs it.

usage: test_extract_liquid_density.py MIXFLOWEXTRACT WORKDIR"""
import os
import sys

import h5py
import numpy as np

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
from mixflow import synthcase as sc  # noqa: E402

exe, work = sys.argv[1], sys.argv[2]
os.makedirs(work, exist_ok=True)
failures = []
check = sc.checker(failures)


def run(case, *extra):
    return sc.run_extract(exe, case, *extra)


times = [round(0.01 * k, 10) for k in range(10)]
case = os.path.join(work, "glycerol")
sc.drift_case(case, times, times, liquid_density=1260)
dict_path = os.path.join(case, "system/extractDict")
base_dict = open(dict_path).read()


def lambda_p_density(h5):
    with h5py.File(h5, "r") as f:
        lp = f["fields/lambda_p_density"][:, :2, :]
        ps, pf = f["fields/p_s"][:, :2, :], f["fields/p_f"][:, :2, :]
        return f.attrs.get("liquid_density_kg_m3"), f.attrs.get("liquid_density_source", ""), lp, ps, pf


# 1. No liquidDensity: the scene's liquid.density.
rc, out = run(case)
check(rc == 0 and "warning" not in out, "mixture case without liquidDensity extracts, no warning")
rho, src, lp, ps, pf = lambda_p_density(os.path.join(case, "postProcessing/mixture/mixture.h5"))
expect = (pf / 1260) / (ps / 2500)
err = np.max(np.abs(lp / expect - 1))
print(f"rho_f = {rho} kg/m3 from '{src}'; lambda_p_density {lp.min():.4f}..{lp.max():.4f} "
      f"(with 1000 kg/m3 it would be {(lp * 1.26).min():.4f}..{(lp * 1.26).max():.4f})")
check(rho == 1260 and "sceneProperties: entry 'liquid.density'" in src and err < 1e-12,
      f"lambda_p_density uses liquid.density 1260 kg/m3 (relative error {err:.1e})")

# 2. An explicit liquidDensity wins, with a warning naming both.
open(dict_path, "w").write(base_dict + "liquidDensity 1000;\n")
rc, out = run(case, "-output", "explicit")
warn = [ln for ln in out.splitlines() if "warning" in ln]
print("\n".join(warn))
rho2, src2, lp2, _, _ = lambda_p_density(os.path.join(case, "explicit.h5"))
check(rc == 0 and any("liquidDensity" in w and "1000" in w and "1260" in w and "wins" in w for w in warn),
      "explicit liquidDensity 1000: warning names both values and which wins")
check(rho2 == 1000 and "entry 'liquidDensity'" in src2 and np.allclose(lp2, lp * 1.26, rtol=1e-12),
      "explicit liquidDensity 1000 is used (lambda_p_density x 1.26)")

# 3. A scene without a liquid and without liquidDensity: refused before anything is written.
dry = os.path.join(work, "no_liquid")
sc.drift_case(dry, times, times, content="particles", liquid_density=None)
rc, out = run(dry)
print(out.strip().splitlines()[-1])
check(rc == 2 and "system/extractDict" in out and "'liquidDensity'" in out and "> 0" in out
      and "sceneProperties (content particles) has no liquid.density" in out
      and not os.path.exists(os.path.join(dry, "postProcessing/mixture")),
      "no liquid density anywhere: input error naming the file, the entry and the range; nothing written")
open(os.path.join(dry, "system/extractDict"), "a").write("pressureConvention raw;\n")
rc, out = run(dry)
check(rc == 0, "the same with pressureConvention raw (no density needed) extracts")

print(f"{len(failures)} failure(s)")
sys.exit(1 if failures else 0)
