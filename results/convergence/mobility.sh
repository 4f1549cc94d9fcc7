#!/usr/bin/env bash
# What holds the quick yield-stress mixtures (cases/W+P-quick, E x 1e-3, face smoothing 0.5,
# exchange every 2 DEM steps, 0.5 s). HB&P's liquid at yield stress tau_c 0, 3, 10, 30.002 Pa with
# its kappa and n (mobility must fall monotonically); the fluid sampled at the grain by cell
# (the cell's values) and cellPoint (interpolated) sampling, at cells of 0.04, 0.06 (the case's)
# and 0.08 m, for HB&P, B&P and W&P, and 0.03 m for HB&P and B&P; HB&P with cellPoint at one DEM step per exchange. Sub-cell
# shear that the sampling counts as slip gives a plastic drag spurious strength. Writes
# WORK/<variant>/<exchangeEvery>/ and results/convergence/mobility.csv (energy released by the
# grains, granular front, their kinetic energy at 0.5 s).
# Usage: mobility.sh [WORK] (default runs/mobility). About 45 min of one core.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
work=$(realpath -m "${1:-$root/runs/mobility}")
run() {  # variant liquid-case (W+P: the case's water) exchangeEvery, then run_mixture_case.py options
  local variant=$1 liquid=$2 n=$3 w="$work/$1/$3"
  shift 3
  [ -f "$w/done" ] && return
  rm -rf "$w" && mkdir -p "$(dirname "$w")"
  local liquid_opt=()
  [ "$liquid" != W+P ] && liquid_opt=(--liquid-case "$liquid")
  # A run that fails the runner's conservation checks is kept and marked (checks_failed).
  /usr/bin/python3 "$root/tests/coupling/run_mixture_case.py" --root "$root" \
    --bindir "${MIXFLOW_BUILD:-$root/build}/bin" --workdir "$w" "${liquid_opt[@]}" \
    --end 0.5 --couple exchangeEvery="$n" "$@" >"$w.log" 2>&1 || touch "$w/checks_failed"
  touch "$w/done"
}
for ys in 0 3 10 30.002; do
  run "hb_yield_stress_$ys" HB+P 2 --scene liquid.yieldStress="$ys"
done
for liquid in HB+P B+P W+P; do
  tag=$(echo "$liquid" | tr 'A-Z+' 'a-z_' | sed 's/_p$//')
  for dx in 0.04 0.06 0.08; do
    run "${tag}_cell_$dx" "$liquid" 2 --couple interpolation=cell --cfd cellSize="$dx"
    run "${tag}_cellPoint_$dx" "$liquid" 2 --couple interpolation=cellPoint --cfd cellSize="$dx"
  done
done
run hb_cellPoint_0.06 HB+P 1 --couple interpolation=cellPoint --cfd cellSize=0.06
for sampling in cell cellPoint; do  # the plastic mixtures towards cells of one diameter
  run "hb_${sampling}_0.03" HB+P 2 --couple interpolation="$sampling" --cfd cellSize=0.03
  run "b_${sampling}_0.03" B+P 2 --couple interpolation="$sampling" --cfd cellSize=0.03
done
/usr/bin/python3 "$root/results/convergence/quick_ladder_csv.py" "$work" \
  "$root/results/convergence/mobility.csv"
