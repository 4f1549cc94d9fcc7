"""Helpers of the CFD and coupling tests, benchmarks and scripts: run OpenFOAM programs, write and
read ASCII case files.

Standard library only (the tests run with any python3). Fields are read from ASCII files written
with a high writePrecision; only internalField is parsed (uniform or nonuniform, scalar or vector).
"""

import os
import re
import shlex
import shutil
import subprocess
import sys

from . import ROOT, foamdict


def run_env():
    """The environment a case's Allrun runs in: the build's bin/ ($MIXFLOW_BUILD or build/) first
    on PATH, MIXFLOW_ROOT (where a copied case finds scripts/), OpenFOAM's WM_PROJECT_DIR."""
    env = dict(os.environ)
    build = os.path.abspath(os.environ.get("MIXFLOW_BUILD", os.path.join(ROOT, "build")))
    env["PATH"] = os.path.join(build, "bin") + os.pathsep + env.get("PATH", "")
    env.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")
    env["MIXFLOW_ROOT"] = ROOT
    return env


def fail(msg):
    print(f"FAIL: {msg}", flush=True)
    sys.exit(1)


class FoamFileError(Exception):
    """A case file the readers below cannot parse: the message names the file."""


def run(cmd, cwd, log_name, env_extra=None):
    """Run cmd in cwd with output to cwd/log_name; fail with the log's tail on non-zero exit."""
    log_path = os.path.join(cwd, log_name)
    print(f"+ (cd {cwd} && {' '.join(shlex.quote(c) for c in cmd)}) > {log_name}", flush=True)
    # PWD too: OpenFOAM warns "PWD is not the cwd()" when only the cwd changes.
    env = dict(os.environ, PWD=cwd)
    if env_extra:
        env.update(env_extra)
    with open(log_path, "w") as log:
        rc = subprocess.call(cmd, cwd=cwd, env=env, stdout=log, stderr=subprocess.STDOUT)
    with open(log_path) as log:
        text = log.read()
    if rc != 0:
        print(text[-4000:])
        fail(f"{cmd[0]} exited with status {rc} (log: {log_path})")
    return text


def run_tool(cmd, who, cwd=None, fatal=True):
    """Runs CMD in run_env(), its output captured; returns its stdout, or on failure exits
    naming WHO and CMD with the output's tail (fatal) or prints that and returns None."""
    print("+ " + " ".join(cmd), flush=True)
    r = subprocess.run(cmd, cwd=cwd, env=run_env(), capture_output=True, text=True)
    if r.returncode != 0:
        msg = (f"{who}: {' '.join(cmd)} failed (exit {r.returncode}):\n"
               f"{r.stdout[-2000:]}{r.stderr[-2000:]}")
        if fatal:
            sys.exit(msg)
        print(msg, flush=True)
        return None
    return r.stdout


def require_foam_env():
    if "WM_PROJECT_DIR" not in os.environ:
        fail("WM_PROJECT_DIR is not set (OpenFOAM needs it; CTest sets it from MIXFLOW_FOAM_ENV)")


def launcher_tokens(mpiexec):
    """Split an MPI launcher command line given as one string (spaces or ';')."""
    return [t for t in re.split(r"[;\s]+", mpiexec) if t]


def run_solver(solver, case, log_name, np=1, mpiexec="mpirun --allow-run-as-root --oversubscribe",
               decomposepar="decomposePar", reconstructpar="reconstructPar"):
    """Run a solver serially, or decomposed on np ranks and reconstructed (all times)."""
    if np <= 1:
        return run([solver], case, log_name)
    set_decomposition(case, np)
    run([decomposepar, "-force"], case, "log.decomposePar")
    text = run(launcher_tokens(mpiexec) + ["-x", "WM_PROJECT_DIR", "-np", str(np), solver,
                                           "-parallel"], case, log_name)
    if not re.search(rf"^nProcs\s*:\s*{np}\s*$", text, re.M):
        fail(f"{log_name} does not show a parallel run on {np} ranks")
    run([reconstructpar], case, "log.reconstructPar")
    return text


def set_decomposition(case, nprocs):
    """Write system/decomposeParDict: the 'simple' method, nprocs slabs along x."""
    write_foam_file(case, "system/decomposeParDict", "dictionary", "decomposeParDict",
                    f"numberOfSubdomains {nprocs};\nmethod simple;\n"
                    f"simpleCoeffs\n{{\n    n ({nprocs} 1 1);\n    delta 0.001;\n}}\n")


def time_dirs(case):
    """Numeric time directories of a case, sorted by value, as (value, name)."""
    out = []
    for name in os.listdir(case):
        if not os.path.isdir(os.path.join(case, name)):
            continue
        try:
            out.append((float(name), name))
        except ValueError:
            pass
    return sorted(out)


def last_match(log, pattern):
    """The match of PATTERN (re.match: from a line's start) on the last line of LOG it matches,
    or None: the final figure of a quantity a program prints as it goes."""
    last = None
    with open(log) as f:
        for line in f:
            last = re.match(pattern, line) or last
    return last


def execution_times(log):
    """{"cpu_s", "clock_s"} of an OpenFOAM solver log ('ExecutionTime = X s  ClockTime = Y s'),
    summed over the attempts a resumed run appended to it (each counts from zero); None without
    such a line or log."""
    total, last, seen = [0.0, 0.0], [0.0, 0.0], False
    pattern = re.compile(r"ExecutionTime = ([0-9.eE+-]+) s\s+ClockTime = ([0-9.eE+-]+) s")
    try:
        with open(log, errors="replace") as f:
            for line in f:
                # A one-step-per-exchange log has millions of lines: test the prefix first.
                m = line.startswith("ExecutionTime") and pattern.match(line)
                if not m:
                    continue
                t = [float(m.group(1)), float(m.group(2))]
                if t[0] < last[0]:  # a resumed attempt starts counting again
                    total = [a + b for a, b in zip(total, last)]
                last, seen = t, True
    except OSError:
        return None
    if not seen:
        return None
    return {"cpu_s": total[0] + last[0], "clock_s": total[1] + last[1]}


def execution_time(log):
    """CPU seconds of an OpenFOAM solver log (execution_times), or None."""
    t = execution_times(log)
    return t["cpu_s"] if t else None


def latest_time(case):
    times = [t for t in time_dirs(case) if t[0] > 0]
    if not times:
        fail(f"no time directory written in {case}")
    return times[-1][1]


def foam_header(cls, obj, location=None):
    loc = f'    location    "{location}";\n' if location else ""
    return ("FoamFile\n{\n    version     2.0;\n    format      ascii;\n"
            f"    class       {cls};\n{loc}    object      {obj};\n}}\n\n")


def write_foam_file(case, rel, cls, obj, body):
    path = os.path.join(case, rel)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(foam_header(cls, obj, os.path.dirname(rel)))
        f.write(body)


def set_entry(path, key, value):
    """Set the top-level entry KEY of a dictionary file to VALUE (the entry must exist)."""
    try:
        if isinstance(foamdict.read_dict(path).get(key, {}), dict):
            raise foamdict.DictError(f"no entry {key}")
        foamdict.edit_file(path, {key: str(value)})
    except foamdict.DictError:
        fail(f"cannot set {key} in {path}")


def _parse_value(tok, kind):
    if kind == "scalar":
        return float(tok)
    return tuple(float(v) for v in tok.strip("()").split())


def read_internal_field(path, ncells=None):
    """internalField of an ASCII vol field: list of floats (scalar) or 3-tuples (vector)."""
    with open(path) as f:
        text = f.read()
    m = re.search(r"^internalField\s+uniform\s+(\([^)]*\)|\S+?)\s*;", text, re.M)
    if m:
        tok = m.group(1)
        kind = "vector" if tok.startswith("(") else "scalar"
        if ncells is None:
            raise FoamFileError(f"{path}: uniform internalField needs the cell count")
        return [_parse_value(tok, kind)] * ncells
    m = re.search(r"^internalField\s+nonuniform\s+List<(scalar|vector)>\s*(\d+)\s*\(", text, re.M)
    if not m:
        raise FoamFileError(f"cannot parse internalField of {path}")
    kind, n = m.group(1), int(m.group(2))
    body = text[m.end():]
    if kind == "scalar":
        values = [float(v) for v in body[:body.index(")")].split()]
    else:
        values = [tuple(float(c) for c in v.split()) for v in re.findall(r"\(([^()]*)\)", body)[:n]]
    if len(values) != n or (ncells is not None and n != ncells):
        raise FoamFileError(f"{path}: expected {ncells if ncells is not None else n} values, found {len(values)}")
    return values


def read_label_list(path):
    """An ASCII labelList file (e.g. constant/polyMesh/owner)."""
    with open(path) as f:
        text = f.read()
    m = re.search(r"^(\d+)\s*\(", text, re.M)
    if not m:
        raise FoamFileError(f"cannot parse {path}")
    values = [int(v) for v in text[m.end():text.index(")", m.end())].split()]
    if len(values) != int(m.group(1)):
        raise FoamFileError(f"{path}: expected {m.group(1)} labels, found {len(values)}")
    return values


def read_internal_face_field(path):
    """internalField of an ASCII surfaceScalarField (e.g. phi): one value per internal face."""
    with open(path) as f:
        text = f.read()
    m = re.search(r"^internalField\s+nonuniform\s+List<scalar>\s*(\d+)\s*\(", text, re.M)
    if not m:
        m = re.search(r"^internalField\s+uniform\s+(\S+?)\s*;", text, re.M)
        if m:
            return None, float(m.group(1))
        raise FoamFileError(f"cannot parse internalField of {path}")
    body = text[m.end():]
    values = [float(v) for v in body[:body.index(")")].split()]
    if len(values) != int(m.group(1)):
        raise FoamFileError(f"{path}: expected {m.group(1)} values, found {len(values)}")
    return values, None


def _list_body(path):
    """(count, text after the opening parenthesis) of an ASCII polyMesh list file."""
    with open(path) as f:
        text = f.read()
    if re.search(r"format\s+binary", text):
        raise FoamFileError(f"{path}: binary; the readers read ASCII meshes (blockMesh's default)")
    head = re.search(r"\}\s*(?://[^\n]*\n|\s)*?(\d+)\s*\(", text)
    if not head:
        raise FoamFileError(f"cannot parse {path}")
    return int(head.group(1)), text[head.end():]


def cell_centres(case):
    """The cell centres (x, y) of CASE's mesh (constant/polyMesh, ASCII): the mean of each
    cell's vertices, exact for the parallelepiped cells blockMesh makes."""
    mesh = os.path.join(case, "constant", "polyMesh")
    missing = [n for n in ("points", "faces", "owner", "neighbour")
               if not os.path.isfile(os.path.join(mesh, n))]
    if missing:
        raise FoamFileError(f"{mesh}: no {', '.join(missing)}")
    n, body = _list_body(os.path.join(mesh, "points"))
    pts = [[float(v) for v in p.split()] for p in re.findall(r"\(([^()]*)\)", body)[:n]]
    n, body = _list_body(os.path.join(mesh, "faces"))
    faces = [[int(v) for v in f.split()] for f in re.findall(r"\d+\(([^()]*)\)", body)[:n]]
    owner = read_label_list(os.path.join(mesh, "owner"))
    neigh = read_label_list(os.path.join(mesh, "neighbour"))
    cells = [set() for _ in range(max(owner) + 1)]
    for fi, f in enumerate(faces):
        cells[owner[fi]].update(f)
        if fi < len(neigh):
            cells[neigh[fi]].update(f)
    return [tuple(sum(pts[v][k] for v in c) / len(c) for k in (0, 1)) for c in cells]


def format_scalar_list(values):
    return "nonuniform List<scalar>\n{}\n(\n{}\n)".format(
        len(values), "\n".join(f"{v:.17g}" for v in values))


def format_vector_list(values):
    return "nonuniform List<vector>\n{}\n(\n{}\n)".format(
        len(values), "\n".join("({:.17g} {:.17g} {:.17g})".format(*v) for v in values))


def copy_case(src, dst):
    shutil.rmtree(dst, ignore_errors=True)
    shutil.copytree(src, dst)


# fvSchemes of the VOF test cases (interFoam damBreak choices), shared by the CFD and coupling tests.
VOF_SCHEMES = """ddtSchemes { default Euler; }
gradSchemes { default Gauss linear; }
divSchemes
{
    div(rhoPhi,U)  Gauss linearUpwind grad(U);
    div(phi,alpha)  Gauss vanLeer;
    div(phirb,alpha) Gauss linear;
    div(((rho*nuEff)*dev2(T(grad(U))))) Gauss linear;
}
laplacianSchemes { default Gauss linear corrected; }
interpolationSchemes { default linear; }
snGradSchemes { default corrected; }
"""


def prepare_dam_break(template, case, end_time, setfields, blockmesh):
    """CASE: a copy of the interFoam damBreak tutorial TEMPLATE that runs to END_TIME, writes
    only then (17 digits) and samples nothing, meshed (BLOCKMESH) and with its initial alpha
    (SETFIELDS); tests/cfd/run_dambreak_vs_interfoam.py and bench/foam_vs_interfoam.py."""
    copy_case(template, case)
    ctrl = os.path.join(case, "system", "controlDict")
    set_entry(ctrl, "endTime", end_time)
    set_entry(ctrl, "writeInterval", end_time)
    set_entry(ctrl, "writePrecision", 17)
    with open(ctrl) as f:
        text = f.read()
    text = re.sub(r"^#sinclude.*$", "", text, flags=re.M)  # drop the sampling function object
    with open(ctrl, "w") as f:
        f.write(text)
    orig = os.path.join(case, "0", "alpha.water.orig")
    if os.path.isfile(orig):
        os.replace(orig, os.path.join(case, "0", "alpha.water"))
    run([blockmesh], case, "log.blockMesh")
    run([setfields], case, "log.setFields")
