#!/usr/bin/env bash
# What the gate's lift changes in a mixture: W&P at the reference tier (0.12 m periodic slice, 2-D
# fluid at 0.075 m, E x 1e-3) with the paper's instant removal and with both plates lifted at
# Lobovsky et al.'s 4.53 m/s (sceneProperties gate, docs/parameters.md), to 3 s on the same
# settled grains. Writes WORK/<gate>/W+P and results/mixtures/gate.csv (granular and liquid
# fronts, released energy, back-wall height at 0.25-3 s). Usage: gate.sh [WORK] (default
# runs/gate_mixture). About 15 min serially.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
work=$(realpath -m "${1:-$root/runs/gate_mixture}")
mixflow suite --tier reference --scenes W+P --work "$work/instant"
mixflow suite --tier reference --scenes W+P --work "$work/lifted_4.53" \
  --settled-from "$work/instant" \
  --set sceneProperties.gate.removal=lifted --set sceneProperties.gate.speed=4.53
/usr/bin/python3 "$root/results/gate_table.py" "$work" "$root/results/mixtures/gate.csv" W+P \
  instant lifted_4.53
