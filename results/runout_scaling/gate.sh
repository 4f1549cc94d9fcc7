#!/usr/bin/env bash
# What the gate's lift changes in the dry column P: the quick tier (3 d periodic slice, E x 1e-4,
# 3 253 grains) with the paper's instant removal and with the plate lifted at 1 m/s and at
# Lobovsky et al.'s 4.53 m/s (sceneProperties gate, docs/parameters.md), each to 2 s from the same
# settle, and the instant removal again with the grains' friction x (1 + 1e-8) for the collapse's
# chaos. Writes WORK/<gate>/P and results/runout_scaling/gate.csv (granular fronts and released
# energy at 0.25-2 s, the final front). Usage: gate.sh [WORK] (default runs/gate_dry). About 8 min.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
work=$(realpath -m "${1:-$root/runs/gate_dry}")
run() {  # name, then --set entries
  local name=$1
  shift
  mixflow suite --tier quick --scenes P --work "$work/$name" --set controlDict.endTime=2 "$@"
}
run instant
run lifted_1 --set sceneProperties.gate.removal=lifted --set sceneProperties.gate.speed=1
run lifted_4.53 --set sceneProperties.gate.removal=lifted --set sceneProperties.gate.speed=4.53
run instant_perturbed --set sceneProperties.particles.friction=0.700000007
/usr/bin/python3 "$root/results/gate_table.py" "$work" \
  "$root/results/runout_scaling/gate.csv" P instant lifted_1 lifted_4.53 instant_perturbed
