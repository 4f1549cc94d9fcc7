#!/usr/bin/env bash
# The yield-stress mixtures' fluid sampling and cell size at the truth tier (E x 1, HB&P every 9,
# B&P every 27 DEM steps, shipped samples), to 0.5 s: `cell` against `cellPoint` sampling for
# HB&P and B&P, 0.075 against 0.05 m cells for HB&P (its 0.075 m run is the sampling ladder's
# `cell`). Ladders interpolation_truth and cellSize_truth in summary.json. Each run resumes; about
# 45 min of one core per HB&P run, 20 min per B&P run.
# Usage: truth_sampling.sh [WORK] (default runs/convergence).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
work=$(realpath -m "${1:-$root/runs/convergence}")
conv() { /usr/bin/python3 -m mixflow convergence --tier truth --end 0.5 --work "$work" "$@"; }
for scene in HB+P B+P; do
  conv --scene "$scene" --knob couplingProperties.interpolation --values cell,cellPoint \
    --label interpolation_truth
done
# HB&P on 0.05 m cells; its 0.075 m run is the sampling ladder's `cell` (the same inputs), so the
# ladder only reads the two.
/usr/bin/python3 -m mixflow suite --tier truth --scenes HB+P --work "$work/cellSize_truth/0.05" \
  --set cfdDict.cellSize=0.05 --set controlDict.endTime=0.5
ln -sfn "$work/interpolation_truth/cell" "$work/cellSize_truth/0.075"
conv --scene HB+P --knob cfdDict.cellSize --values 0.075,0.05 --label cellSize_truth --report-only
