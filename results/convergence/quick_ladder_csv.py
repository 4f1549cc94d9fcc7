"""The quick-scene ladders' table: WORK/<variant>/<exchangeEvery>/W+P-quick runs to one CSV row each
(energy released by the grains, granular front and their kinetic energy at 0.5 s, and whether
the run passed run_mixture_case.py's conservation checks: a run marked checks_failed did not).
Usage: quick_ladder_csv.py WORK OUT.csv (interval_mechanism.sh, void_jumps.sh)."""
import csv
import glob
import os
import sys

END_S = 0.5


def main(work, out):
    rows = []
    pattern = os.path.join(work, "*", "*", "W+P-quick", "postProcessing", "dem", "timeSeries.csv")
    for series in sorted(glob.glob(pattern)):
        variant, n = series[len(work) + 1:].split(os.sep)[:2]
        with open(series) as f:
            r = list(csv.DictReader(ln for ln in f if not ln.startswith("#")))
        end = min(r, key=lambda x: abs(float(x["time_s"]) - END_S))
        rows.append({"variant": variant, "exchangeEvery": int(n),
                     "time_s": round(float(end["time_s"]), 4),
                     "released_J": round(float(r[0]["pe_J"]) - float(end["pe_J"]), 4),
                     "front_m": round(float(end["front_x_m"]), 4),
                     "ke_J": round(float(end["ke_translational_J"]), 4),
                     "checks": "failed" if os.path.exists(os.path.join(
                         work, variant, n, "checks_failed")) else "passed"})
    rows.sort(key=lambda x: (x["variant"], -x["exchangeEvery"]))
    with open(out, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    print(out, len(rows), "rows")


if __name__ == "__main__":
    main(*sys.argv[1:])
