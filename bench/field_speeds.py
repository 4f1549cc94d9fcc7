#!/usr/bin/env python3
"""Largest fluid speeds in the written fields of coupled runs: in all cells (the air jets beside a
saturated column show here) and in liquid cells (alpha.liquid > 0.5), at each written time.

usage: field_speeds.py CASE [CASE ...] [--json OUT]
Used in bench/README.md to tell the air jets' agitation from the exchange interval's
effect at the paper's DEM stiffness."""
import argparse
import json
import math
import os
import sys

sys.dont_write_bytecode = True
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
from mixflow import foamcase as fc  # noqa: E402


def speeds(case):
    out = []
    for value, t in fc.time_dirs(case):
        if value == 0:
            continue
        U = fc.read_internal_field(os.path.join(case, t, "U"))
        alpha = fc.read_internal_field(os.path.join(case, t, "alpha.liquid"))
        mag = [math.sqrt(u[0] ** 2 + u[1] ** 2 + u[2] ** 2) for u in U]
        liquid = [m for m, a in zip(mag, alpha) if a > 0.5]
        out.append({"time_s": value, "max_speed_m_s": max(mag),
                    "max_liquid_speed_m_s": max(liquid) if liquid else 0.0})
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("cases", nargs="+")
    ap.add_argument("--json")
    a = ap.parse_args()
    names = [os.path.basename(os.path.normpath(c)) for c in a.cases]
    # Cases are named by their directory, or by their path where two share a name (variants).
    res = {(n if names.count(n) == 1 else os.path.normpath(c)): speeds(c)
           for n, c in zip(names, a.cases)}
    for name, rows in res.items():
        print(name + ": " + " | ".join(
            f"{r['time_s']:g} s: {r['max_speed_m_s']:.2f} (liquid {r['max_liquid_speed_m_s']:.3f})"
            for r in rows))
    if a.json:
        res["command"] = " ".join(["mixflow bench field_speeds"] + sys.argv[1:])
        with open(a.json, "w") as f:
            json.dump(res, f, indent=2)


if __name__ == "__main__":
    main()
