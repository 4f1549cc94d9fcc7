"""The bulkProperties writer of calibrate_drifts.py (foamdict.edit_dict underneath): an existing file
keeps every byte outside the drifts entries it sets, a missing drifts block is appended, a missing
file is created, and drifts outside the bulk model's range are refused with nothing written.

usage: test_calibrate_writer.py WORKDIR"""
import os
import shutil
import sys

from mixflow.commands import calibrate_drifts as cd  # noqa: E402
from mixflow.foamdict import parse_dict, read_dict, unquote  # noqa: E402
from mixflow.synthcase import checker  # noqa: E402

BEFORE = """FoamFile { version 2.0; format ascii; class dictionary; object bulkProperties; }
// Bulk model of W+P: hand-tuned solid, drifts from an earlier calibration.
solidFraction 0.6056;          // optional
"""
DRIFTS = """drifts
{
    lambdaU 1.0;    // first guess
    lambdaW 1.0;
    lambdaP 1.0;
    source  "hand";
}"""
AFTER = """
solid
{
    viscosity  0.03;   /* nu_s, m2/s */
    tanPhi     0.4663;
    yieldPressure buoyancyReduced;
}
relaxation 0.7;
"""
NEW = {"lambda_u": 1.29469, "lambda_w": 0.795638, "lambda_p": -0.25}


def fake_result(values):
    """The parts of a calibrate() result that write_target reads."""
    return {"h5": "/x/mixture.h5", "sha256": "ab" * 32, "estimator": "wls",
            "selection": {"windows_used": [0.1, 1.0], "source_sample_solid_fraction": 0.6},
            "drifts": {q: {"value": v} for q, v in values.items()}}


def main():
    work = sys.argv[1]
    failures = []
    check = checker(failures)
    shutil.rmtree(work, ignore_errors=True)
    target = os.path.join(work, "bulk")
    os.makedirs(os.path.join(target, "constant"))
    bp = os.path.join(target, "constant", "bulkProperties")

    # 1. An existing file with drifts between other entries and blocks.
    with open(bp, "w") as f:
        f.write(BEFORE + DRIFTS + AFTER)
    cd.write_target(target, fake_result(NEW), "/x")
    with open(bp) as f:
        text = f.read()
    check(text.startswith(BEFORE + "drifts\n{\n"), "bytes before the drifts block unchanged")
    check(text.endswith("\n}" + AFTER), "bytes after the drifts block unchanged (solid, relaxation)")
    d = parse_dict(text)
    check([d["drifts"][k] for k in ("lambdaU", "lambdaW", "lambdaP")] == ["1.29469", "0.795638",
                                                                          "-0.25"],
          f"drifts set to the new values: {d['drifts']}")
    check(unquote(d["drifts"]["source"]).startswith("calibrate_drifts.py: /x/mixture.h5 sha256 "
                                                     + "ab" * 32 + ", estimator wls, windows 0.1-1 s"),
          f"drifts.source replaced: {d['drifts']['source']}")
    check(set(d) == {"FoamFile", "solidFraction", "drifts", "solid", "relaxation"} and
          d["solid"] == {"viscosity": "0.03", "tanPhi": "0.4663", "yieldPressure": "buoyancyReduced"},
          "other entries and blocks read back as before")
    check("lambdaU 1.29469;    // first guess" in text, "an entry's comment stays on its line")
    # lambda_p -0.25 is allowed at alpha_s 0.6056 (bound (0.01 - 0.6056) / 0.3944 = -1.51).
    again = text
    cd.write_target(target, fake_result(NEW), "/x")
    with open(bp) as f:
        check(f.read() == again, "a second identical calibration changes no byte")

    # 2. Out of the bulk model's range (prepare/BulkModel.cpp): refused, file untouched.
    try:
        cd.write_target(target, fake_result(dict(NEW, lambda_p=-2.0)), "/x")
        check(False, "lambdaP -2 refused")
    except cd.InputError as e:
        msg = str(e)
        check("drifts.lambdaP" in msg and "[-1.51, 1000]" in msg and "solidFraction" in msg,
              f"lambdaP -2 refused naming entry, range and alpha_s' origin: {msg}")
    with open(bp) as f:
        check(f.read() == again, "refused drifts: bulkProperties unchanged")

    # 3. No drifts block: appended after the last byte, the rest kept.
    with open(bp, "w") as f:
        f.write(BEFORE + AFTER.lstrip("\n"))
    cd.write_target(target, fake_result(NEW), "/x")
    with open(bp) as f:
        text = f.read()
    check(text.startswith(BEFORE + AFTER.lstrip("\n")) and
          read_dict(bp)["drifts"]["lambdaW"] == "0.795638",
          "a file without drifts keeps its text as a prefix and gains the block")

    # 4. No file: created with a FoamFile header; alpha_s from the target's sceneProperties.
    os.remove(bp)
    with open(os.path.join(target, "constant", "sceneProperties"), "w") as f:
        f.write("sample { solidFraction 0.2; }\n")
    res = fake_result(dict(NEW, lambda_p=-0.2))
    try:
        cd.write_target(target, res, "/x")
        ok = True
    except cd.InputError as e:
        print(e)
        ok = False
    check(ok, "lambdaP -0.2 passes at sample.solidFraction 0.2 (bound (0.01 - 0.2) / 0.8 = -0.2375)")
    d = read_dict(bp)
    check(d["FoamFile"]["object"] == "bulkProperties" and d["drifts"]["lambdaP"] == "-0.2",
          f"new file with header and drifts: {sorted(d)}")
    with open(bp + ".calibration.json") as f:
        check('"solid_fraction_from"' in f.read(), "the JSON is written next to bulkProperties")
    print(f"{len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
