"""A stopped mixture run's checkpoint (mixflow.checkpoint): its last field write, the particles'
restart and its outputs so far, thinned, to commit so that the run goes on in another session or
on another machine.

usage: mixflow scene-checkpoint CASE --out DIR
  writes DIR/<scene> from the stopped run directory CASE (replacing an older checkpoint)
usage: mixflow scene-checkpoint --restore DIR/<scene> --work WORK
  copies the checkpoint to WORK/<scene>, where `mixflow suite --work WORK` resumes it
"""

import argparse
import os
import sys

from mixflow.checkpoint import checkpoint_scene, restore


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("case", nargs="?", help="a stopped mixture run directory (a suite run's "
                    "<work>/<scene>, stopped after a field write)")
    ap.add_argument("--out", help="the checkpoints' directory: <scene>/ for the case")
    ap.add_argument("--restore", metavar="CHECKPOINT", help="a checkpoint to copy into --work")
    ap.add_argument("--work", help="with --restore: the suite's work directory")
    a = ap.parse_args(argv)
    try:
        if a.restore:
            if a.case or not a.work:
                return "mixflow scene-checkpoint: --restore CHECKPOINT takes --work WORK and no CASE"
            run_dir = os.path.join(a.work, os.path.basename(os.path.normpath(a.restore)))
            restore(a.restore, run_dir)
            print(f"{a.restore} -> {run_dir}: `mixflow suite --work {a.work}` resumes it")
            return 0
        if not a.case or not a.out:
            return "mixflow scene-checkpoint: give CASE and --out DIR (or --restore and --work)"
        case = os.path.normpath(a.case)
        out = os.path.join(a.out, os.path.basename(case))
        sizes = checkpoint_scene(case, out)
    except ValueError as e:
        return f"mixflow scene-checkpoint: {e}"
    print(f"{case} -> {out}: {len(sizes)} files, {sum(sizes.values()) / 1024:.0f} kB")
    return 0


if __name__ == "__main__":
    sys.exit(main())
