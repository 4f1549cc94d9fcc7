"""The `mixflow` command: one verb per tool of the study (python/README.md).

    mixflow VERB [ARGS]     runs the verb (mixflow VERB --help: its arguments)
    mixflow --help          lists the verbs

A verb's code is the module mixflow/commands/<module>.py; `mixflow bench NAME` runs the benchmark
bench/NAME.py of the checkout (bench/README.md).
"""

import importlib
import os
import subprocess
import sys

from . import ROOT

# verb: (module of mixflow.commands, what it does)
VERBS = {
    "suite": ("suite", "run the scenes of Table 1 at a fidelity tier (docs/suite.md)"),
    "report": ("report", "the reproduction report of the scenes a suite run finished"),
    "calibrate": ("calibrate", "a CFD-DEM case to a calibrated bulk run, compared (docs/calibration.md)"),
    "calibrate-drifts": ("calibrate_drifts", "the bulk model's drifts from a CFD-DEM run (docs/calibration.md)"),
    "calibrate-solid": ("calibrate_solid", "the bulk model's solid rheology on the dry P"),
    "mixture-lambdas": ("mixture_lambdas", "drift coefficients of finished mixture runs (mixflowExtract)"),
    "bulk-stages": ("bulk_stages", "the bulk model at its calibration stages against CFD-DEM"),
    "bulk-model-results": ("bulk_model_results", "results/bulk_model/: the bulk model against CFD-DEM"),
    "scene-record": ("scene_record", "a finished scene's outputs the report reads, small enough to commit"),
    "scene-checkpoint": ("scene_checkpoint", "a stopped mixture run's resumable state, small enough to commit"),
    "mixture-results": ("mixture_results", "results/mixtures/: fronts, Froude and Savage numbers"),
    "liquid-results": ("liquid_results", "post-processing of scripts/liquid_results.sh"),
    "yield-stress-results": ("yield_stress_results", "results/yield_stress/: drag-viscosity closures"),
    "tier-trade": ("tier_trade", "speed against accuracy of one scene across fidelity tiers"),
    "convergence": ("convergence", "one knob's ladder on one scene, on the same grains (results/convergence)"),
    "knob-trade": ("knob_trade", "cost against accuracy of each fidelity knob around the quick tier"),
    "reproducibility": ("reproducibility", "serial against parallel mixture runs"),
    "initial-pressure-check": ("initial_pressure_check", "the start's pressure in a yield-stress mixture"),
    "runout-fit": ("runout_fit", "the dry runout law (l_inf - L)/L = lambda a^alpha (Eq. 12)"),
    "lube-small-columns": ("lube_small_columns", "Lube et al.'s small-column claims on the paper's grains"),
    "viscous-packing": ("viscous_packing", "loose against dense collapse in a viscous liquid"),
    "martin-moyce-interfoam": ("martin_moyce_interfoam", "Martin & Moyce: mixflowFoam, interFoam, experiment"),
    "lobovsky-gate": ("lobovsky_gate", "Lobovsky et al. (2014) fronts: instant against lifted gate"),
    "martin-moyce-gate": ("martin_moyce_gate", "Martin & Moyce (1952) front: instant against lifted gates"),
    "liquid-ke-by-alpha": ("liquid_ke_by_alpha", "a coupled run's liquid kinetic energy by liquid fraction"),
    "stability-dem": ("stability_dem", "the DEM step against stiffness (results/stability)"),
    "stability-drag": ("stability_drag", "the coupling interval against the drag's relaxation number"),
    "stability-plots": ("stability_plots", "plots and boundaries of results/stability"),
}
BENCH_DIR = os.path.join(ROOT, "bench")


def command(verb, *args):
    """The argument list that runs `mixflow VERB ARGS` with this interpreter (for subprocess)."""
    return [sys.executable, "-m", "mixflow", verb, *args]


def usage():
    width = max(len(v) for v in VERBS)
    lines = ["usage: mixflow VERB [ARGS]   (mixflow VERB --help for its arguments)", "", "verbs:"]
    lines += [f"  {v:<{width}}  {h}" for v, (_, h) in VERBS.items()]
    lines += [f"  {'bench':<{width}}  run a benchmark of bench/ (mixflow bench --help lists them)"]
    return "\n".join(lines)


def benches():
    """{name: first line of its docstring} of bench/*.py."""
    out = {}
    for name in sorted(os.listdir(BENCH_DIR)) if os.path.isdir(BENCH_DIR) else []:
        if name.endswith(".py"):
            with open(os.path.join(BENCH_DIR, name)) as f:
                text = f.read(2000)
            doc = text.split('"""')[1].strip().splitlines()[0] if '"""' in text else ""
            out[name[:-3]] = doc
    return out


def bench(args):
    """mixflow bench NAME [ARGS]: bench/NAME.py ARGS with this interpreter; its exit status."""
    found = benches()
    if not args or args[0] in ("-h", "--help"):
        width = max((len(n) for n in found), default=0)
        print("usage: mixflow bench NAME [ARGS]   (mixflow bench NAME --help for its arguments)\n\n"
              f"benchmarks in {BENCH_DIR} (bench/README.md):")
        for name, doc in found.items():
            print(f"  {name:<{width}}  {doc}")
        return 0 if args else 2
    name = args[0][:-3] if args[0].endswith(".py") else args[0]
    if name not in found:
        sys.exit(f"mixflow bench: no benchmark '{args[0]}' in {BENCH_DIR} "
                 f"(there are: {', '.join(found)})")
    return subprocess.call([sys.executable, os.path.join(BENCH_DIR, name + ".py"), *args[1:]])


def main(argv=None):
    argv = sys.argv[1:] if argv is None else list(argv)
    if not argv or argv[0] in ("-h", "--help"):
        print(usage())
        return 0 if argv else 2
    verb, args = argv[0], argv[1:]
    if verb == "bench":
        return bench(args)
    if verb not in VERBS:
        print(usage(), file=sys.stderr)
        return f"mixflow: no verb '{verb}'"
    module = importlib.import_module("mixflow.commands." + VERBS[verb][0])
    sys.argv = [f"mixflow {verb}", *args]  # the verb's argument parser reads these
    return module.main()
