#!/usr/bin/env bash
# The geometry ladder at the quick tier (cases/tiers/quick: E x 1e-4, exchange every 10, 2-D fluid
# on 0.075 m cells): each mixture on the tier's 0.072 m periodic slice against the paper's channel,
# 0.6 m wide with frictional side walls and a 3-D fluid (same cells), to 1.5 s; beside it the slice
# on another packing (settle.seed 2), the noise floor a geometry change is read against. Runs in
# WORK/geometry_quick/{slice,reseeded,channel}/<scene>; writes the ladder `geometry_quick` of
# results/convergence/summary.json (mixflow convergence --report-only: the slice against the
# channel, both against the reseeded slice) and results/convergence/geometry/<scene>/tier_trade.{json,md}
# (mixflow tier-trade: observables at 0.25-1.5 s and the cost; changes: the slice against the
# reseeded slice, the channel against the slice).
# Usage: geometry.sh [WORK] (default runs/convergence); SCENES="W+P" for some scenes only.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
work=$(realpath -m "${1:-$root/runs/convergence}")/geometry_quick
mixflow() { /usr/bin/python3 -m mixflow "$@"; }
cd "$root"
for s in ${SCENES:-W+P HB+P B+P}; do
  mixflow suite --tier quick --scenes "$s" --work "$work/slice"
  mixflow suite --tier quick --scenes "$s" --work "$work/reseeded" --set demDict.settle.seed=2
  mixflow suite --tier quick --scenes "$s" --work "$work/channel" \
    --set sceneProperties.sample.width=0.6 --set sceneProperties.channel.sideWalls=walls \
    --set cfdDict.dimensions=3
  mixflow tier-trade --scene "$s" --times 0.25,0.5,1,1.5 --paper-cost "" \
    --tiers "reseeded=$work/reseeded,slice=$work/slice,channel=$work/channel" \
    --out "results/convergence/geometry/$s"
  mixflow convergence --report-only --scene "$s" --tier quick --knob geometry \
    --values slice,channel --label geometry_quick --work "$(dirname "$work")" \
    --against "$work/reseeded" --made-by "results/convergence/geometry.sh (SCENES=$s)"
done
