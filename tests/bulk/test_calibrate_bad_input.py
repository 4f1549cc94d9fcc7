"""calibrate_drifts.py refuses bad input with exit status 2 and a message naming the file, the
entry or option and the allowed range, before writing anything (the target's bulkProperties and
JSON stay absent or byte-for-byte as they were).

usage: test_calibrate_bad_input.py MIXFLOWEXTRACT WORKDIR"""
import os
import shutil
import subprocess
import sys

import drift_data as dd  # noqa: E402
from mixflow.cli import command  # noqa: E402
from mixflow.synthcase import checker, write  # noqa: E402

CMD = command("calibrate-drifts") + ["--pressure", "lambdaP"]  # the targets hold lambdaP


def main():
    exe, work = sys.argv[1], sys.argv[2]
    failures = []
    check = checker(failures)
    shutil.rmtree(work, ignore_errors=True)
    case = os.path.join(work, "dem_case")
    dd.make(case, exe, seed=3, shape=(2, 2, 4))
    target = os.path.join(work, "bulk")
    bp = os.path.join(target, "constant", "bulkProperties")
    write(bp, "FoamFile { version 2.0; format ascii; class dictionary; object bulkProperties; }\n"
              "solid { tanPhi 0.5; }\n")
    with open(bp) as f:
        original = f.read()
    garbage = os.path.join(work, "garbage.h5")
    write(garbage, "not HDF5\n")
    bare = os.path.join(work, "bare")
    os.makedirs(bare)

    cases = [
        ("missing source", [os.path.join(work, "nowhere"), "--target", target],
         [os.path.join(work, "nowhere") + ": no such file", "postProcessing/mixture/mixture.h5"]),
        ("not an HDF5 file", [garbage, "--target", target],
         [garbage, "not a mixflowExtract HDF5 file"]),
        ("no flowing bin", [case, "--target", target, "--flowing-factor", "100"],
         ["no bin to calibrate lambda_u", "valid_lambda_u", "--flowing-factor, allowed > 0",
          "mixture.h5"]),
        ("flowing factor 0", [case, "--target", target, "--flowing-factor", "0"],
         ["--flowing-factor 0", "allowed > 0"]),
        ("solid fraction 1.5", [case, "--target", target, "--min-solid-fraction", "1.5"],
         ["--min-solid-fraction 1.5", "allowed [0, 1)"]),
        ("windows outside the file", [case, "--target", target, "--windows", "5:6"],
         ["--windows 5:6", "holds none of the file's 2 windows", "[0, 0.04] s"]),
        ("windows reversed", [case, "--target", target, "--windows", "0.04:0.01"],
         ["--windows '0.04:0.01'", "0 <= T0 < T1"]),
        ("unknown estimator", [case, "--target", target, "--estimator", "mean"],
         ["--estimator mean", "allowed wls, median"]),
        ("unknown weights", [case, "--target", target, "--weights", "mass"],
         ["--weights mass", "allowed particles, samples, none"]),
        ("bootstrap 5", [case, "--target", target, "--bootstrap", "5"],
         ["--bootstrap 5", ">= 10"]),
        ("target without constant/", [case, "--target", bare], [bare, "no constant/ directory"]),
        ("fields without a mesh", [case, "--target", target, "--fields"],
         [os.path.join(target, "constant", "polyMesh"), "no points, faces, owner, neighbour",
          "run mixflowPrepare and blockMesh"]),
    ]
    for what, args, needles in cases:
        r = subprocess.run(CMD + args, capture_output=True, text=True)
        msg = r.stdout + r.stderr
        check(r.returncode == 2 and all(n in msg for n in needles),
              f"{what}: exit 2 ({r.returncode}) naming {needles}: {msg.strip()[-300:]}")
    with open(bp) as f:
        check(f.read() == original, "after the refusals bulkProperties is unchanged")
    check(not os.path.exists(bp + ".calibration.json") and os.listdir(bare) == [],
          "no JSON and nothing in the target without constant/")

    # An unreadable bulkProperties: named with its line, left as it was.
    broken = original + "drifts { lambdaU 1.2;\n"
    with open(bp, "w") as f:
        f.write(broken)
    r = subprocess.run(CMD + [case, "--target", target], capture_output=True, text=True)
    msg = r.stdout + r.stderr
    check(r.returncode == 2 and bp in msg and "block 'drifts' is not closed" in msg,
          f"unclosed drifts block: exit 2 naming the file and block: {msg.strip()[-200:]}")
    with open(bp) as f:
        check(f.read() == broken, "the unreadable bulkProperties is left as it was")
    # drifts given as an entry instead of a block.
    with open(bp, "w") as f:
        f.write(original + "drifts 1.3;\n")
    r = subprocess.run(CMD + [case, "--target", target], capture_output=True, text=True)
    msg = r.stdout + r.stderr
    check(r.returncode == 2 and "'drifts' is an entry, not a block" in msg,
          f"drifts as an entry: exit 2: {msg.strip()[-200:]}")
    print(f"{len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
