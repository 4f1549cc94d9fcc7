#!/usr/bin/env python3
"""Where a coupled run's liquid kinetic energy sits: its split by the cells' liquid fraction.

usage: liquid_ke_by_alpha.py CASE TIME [TIME ...]

Reads TIME/U, voidfraction and alpha.liquid (ASCII, as the cases write them) of a mixture case
on a uniform mesh (the generated channel meshes; equal cell volumes). For the bands
alpha < 0.2, 0.2-0.5, 0.5-0.99 and >= 0.99, it prints the number of cells, their share of
sum eps alpha |U|^2 (the liquid kinetic energy of postProcessing/liquid, up to 1/2 rho_l V) and
their largest |U|. A large share at small alpha means that air velocities, carried by the VOF
mixture velocity, dominate the liquid's kinetic energy (coupling/README.md, "Exchange interval").
"""
import os
import re
import sys

import numpy as np


def read_field(path, vector):
    text = open(path).read()
    text = text[text.index("internalField"):]
    m = re.search(r"nonuniform List<\w+>\s*(\d+)", text)
    if not m:
        sys.exit(f"{path}: internalField is not a nonuniform ASCII list")
    n = int(m.group(1))
    body = text[m.end():]
    body = body[body.index("(") + 1:]
    if vector:
        vals = re.findall(r"\(([^()]*)\)", body)[:n]
        return np.array([[float(x) for x in v.split()] for v in vals])
    return np.array([float(x) for x in body.split(")")[0].split()[:n]])


def main(argv):
    if len(argv) < 2:
        sys.exit(__doc__)
    case = argv[0]
    for t in argv[1:]:
        d = os.path.join(case, t)
        u = read_field(os.path.join(d, "U"), True)
        eps = read_field(os.path.join(d, "voidfraction"), False)
        alpha = read_field(os.path.join(d, "alpha.liquid"), False)
        ke = eps * alpha * (u ** 2).sum(axis=1)
        speed = np.sqrt((u ** 2).sum(axis=1))
        print(f"{case} t = {t}:")
        for lo, hi in ((0.0, 0.2), (0.2, 0.5), (0.5, 0.99), (0.99, 1.01)):
            k = (alpha >= lo) & (alpha < hi)
            top = speed[k].max() if k.any() else 0.0
            print(f"  alpha in [{lo}, {min(hi, 1.0)}{')' if hi < 1 else ']'}: {k.sum()} cells, "
                  f"share of liquid KE {ke[k].sum() / ke.sum():.3f}, max |U| {top:.2f} m/s")


if __name__ == "__main__":
    main(sys.argv[1:])
