"""A finished scene's record (mixflow.record): the files the report reads, thinned, in the run's
own layout, to commit so that a report can be made from scenes finished in other sessions.

usage: mixflow scene-record CASE [CASE ...] --out DIR
  writes DIR/<scene> for each finished run directory CASE (replacing an older record)
"""

import argparse
import os
import sys

from mixflow.outputs import DONE
from mixflow.record import STEP_S, record_scene


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("cases", nargs="+", help="finished run directories (a suite run's <work>/<scene>)")
    ap.add_argument("--out", required=True, help="the records' directory: one <scene>/ per case")
    ap.add_argument("--step-scale", type=float, default=1.0,
                    help="factor on the thinning steps (s) of the liquid series and the exchange log, "
                    + ", ".join(f"{os.path.basename(k)} {v}" for k, v in STEP_S.items()))
    args = ap.parse_args(argv)
    if not args.step_scale > 0:
        return f"mixflow scene-record: --step-scale {args.step_scale}: must be > 0"
    # Every case checked before any record is written (record_scene refuses one by one).
    missing = [c for c in args.cases if not os.path.isfile(os.path.join(c, DONE))]
    if missing:
        return ("mixflow scene-record: not finished runs (no .done): " + ", ".join(missing)
                + "; record a run once mixflow suite has finished it")
    for case in args.cases:
        case = os.path.normpath(case)
        out = os.path.join(args.out, os.path.basename(case))
        sizes = record_scene(case, out, args.step_scale)
        print(f"{case} -> {out}: {len(sizes)} files, {sum(sizes.values()) / 1024:.0f} kB")
    return 0


if __name__ == "__main__":
    sys.exit(main())
