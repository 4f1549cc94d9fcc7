#!/usr/bin/env bash
# The DEM step at the truth tier (E x 1, shipped samples): each mixture at 0.2 T_R (demDict
# rayleighFraction 0.2, 2.48 us) with the exchange interval kept in time as near as whole steps
# allow (W&P and B&P every 13 DEM steps, 3.23e-5 s against the tier's 27 x 1.24 us = 3.35e-5 s;
# HB&P every 4, 9.9e-6 s against 9 x 1.24 us = 1.12e-5 s), to END s, against the tier's own run
# at 0.1 T_R (the scene's record, results/li_zhao_2018/records/truth: the same sample, which the
# settle's own step, demDict settle.rayleighFraction 0.1, keeps whatever the collapse's step).
# Ladder dem_step_truth in summary.json (change_against_base: 0.2 T_R minus the tier). HB&P's
# interval differs from the tier's by 11 %, so HB&P also runs at 0.1 T_R every 8 DEM steps (the
# same 9.9e-6 s as its 0.2 T_R run): ladder dem_step_truth_same_interval, change_against_base
# 0.1 T_R minus 0.2 T_R at one interval.
# Usage: dem_step.sh [WORK] [END] (default runs/convergence, 0.25 s); SCENES="W+P" for some.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
work=$(realpath -m "${1:-$root/runs/convergence}")
end=${2:-0.25}
wanted() { [ -z "${SCENES:-}" ] || [[ " $SCENES " == *" $1 "* ]]; }
conv() { /usr/bin/python3 -m mixflow convergence --tier truth --end "$end" "$@"; }
for pair in W+P:13 B+P:13 HB+P:4; do
  scene=${pair%%:*} every=${pair##*:}
  wanted "$scene" || continue
  conv --work "$work/$scene" --scene "$scene" --knob demDict.rayleighFraction --values 0.2 \
    --label dem_step_truth --set couplingProperties.exchangeEvery="$every" \
    --against "$root/results/li_zhao_2018/records/truth"
done
if wanted HB+P; then
  conv --work "$work/HB+P" --scene HB+P --knob demDict.rayleighFraction --values 0.1 \
    --label dem_step_truth_same_interval --set couplingProperties.exchangeEvery=8 \
    --against "$work/HB+P/dem_step_truth/0.2"
fi
