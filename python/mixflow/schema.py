"""The declared entries of the case dictionaries, as the C++ declares them once
(common/SceneProperties.cpp, DemDict.cpp, CfdDict.cpp, ...): `mixflowSchema -json` of the build
prints them, with type, default, range or words, unit and meaning; they are read once a process.

The program is the build's: $MIXFLOW_BUILD/bin, else this checkout's build/bin, else PATH.
"""

import functools
import json
import os
import shutil
import subprocess

from . import ROOT


class SchemaError(RuntimeError):
    """mixflowSchema is missing or did not answer."""


def program():
    """Path of the build's mixflowSchema, or None."""
    if os.environ.get("MIXFLOW_BUILD"):
        candidates = [os.path.join(os.environ["MIXFLOW_BUILD"], "bin", "mixflowSchema")]
    else:
        candidates = [os.path.join(ROOT, "build", "bin", "mixflowSchema"), shutil.which("mixflowSchema")]
    return next((c for c in candidates if c and os.access(c, os.X_OK)), None)


@functools.lru_cache(maxsize=None)
def declarations():
    """{file: {dotted entry: {"type", "required", "auto", "default", "range", "words", "unit",
    "meaning"}}}, e.g. declarations()["constant/sceneProperties"]["sample.solidFraction"]."""
    exe = program()
    if exe is None:
        where = (os.path.join(os.environ["MIXFLOW_BUILD"], "bin") if os.environ.get("MIXFLOW_BUILD")
                 else os.path.join(ROOT, "build", "bin") + " or on PATH")
        raise SchemaError(f"mixflowSchema not found in {where}: the declared "
                          "defaults come from the build (scripts/build.sh; MIXFLOW_BUILD names "
                          "another build directory)")
    res = subprocess.run([exe, "-json"], capture_output=True, text=True)
    if res.returncode != 0:
        raise SchemaError(f"{exe} -json failed ({res.returncode}): {res.stderr.strip()} (a build "
                          "older than its sources? rebuild with scripts/build.sh)")
    return json.loads(res.stdout)


def default(file, entry):
    """The declared default of ENTRY (dotted, e.g. "sample.solidFraction") of FILE (e.g.
    "constant/sceneProperties"): a number, a word, True/False (switch), None (required, auto)."""
    try:
        return declarations()[file][entry]["default"]
    except KeyError:
        raise SchemaError(f"{file}: no declared entry '{entry}' (mixflowSchema -json)") from None


def value(tree, file, entry):
    """ENTRY (dotted) of TREE, the parsed dictionary FILE (mixflow.foamdict): its value string
    when the dictionary sets it, else the declared default."""
    *blocks, key = entry.split(".")
    node = tree
    for b in blocks:
        node = node.get(b, {}) if isinstance(node, dict) else {}
    if isinstance(node, dict) and key in node:
        return node[key]
    return default(file, entry)
