"""Where a coupled run's liquid kinetic energy sits: its split by the cells' liquid fraction.

usage: mixflow liquid-ke-by-alpha CASE TIME [TIME ...]

Reads TIME/U, voidfraction and alpha.liquid (ASCII, as the cases write them) of a mixture case
on a uniform mesh (the generated channel meshes; equal cell volumes). For the bands
alpha < 0.2, 0.2-0.5, 0.5-0.99 and >= 0.99, it prints the number of cells, their share of
sum eps alpha |U|^2 (the liquid kinetic energy of postProcessing/liquid, up to 1/2 rho_l V) and
their largest |U|. A large share at small alpha means that air velocities, carried by the VOF
mixture velocity, dominate the liquid's kinetic energy (coupling/README.md, "Exchange interval").
"""
import argparse
import os

import numpy as np

from mixflow.foamcase import read_internal_field  # (the tests' ASCII field reader)


def read_field(path):
    return np.array(read_internal_field(path), dtype=float)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("case", metavar="CASE")
    p.add_argument("times", metavar="TIME", nargs="+")
    a = p.parse_args(argv)
    case = a.case
    for t in a.times:
        d = os.path.join(case, t)
        u = read_field(os.path.join(d, "U"))
        eps = read_field(os.path.join(d, "voidfraction"))
        alpha = read_field(os.path.join(d, "alpha.liquid"))
        ke = eps * alpha * (u ** 2).sum(axis=1)
        speed = np.sqrt((u ** 2).sum(axis=1))
        print(f"{case} t = {t}:")
        for lo, hi in ((0.0, 0.2), (0.2, 0.5), (0.5, 0.99), (0.99, 1.01)):
            k = (alpha >= lo) & (alpha < hi)
            top = speed[k].max() if k.any() else 0.0
            print(f"  alpha in [{lo}, {min(hi, 1.0)}{')' if hi < 1 else ']'}: {k.sum()} cells, "
                  f"share of liquid KE {ke[k].sum() / ke.sum():.3f}, max |U| {top:.2f} m/s")


if __name__ == "__main__":
    main()
