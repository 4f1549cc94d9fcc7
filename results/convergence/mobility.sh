#!/usr/bin/env bash
# What holds the quick yield-stress mixtures (cases/W+P-quick, E x 1e-3, face smoothing 0.5,
# exchange every 2 DEM steps, 0.5 s). HB&P's liquid at yield stress tau_c 0, 3, 10, 30.002 Pa with
# its kappa and n (mobility must fall monotonically), and as water (tau_c 0, kappa 1e-3, n 1);
# the fluid sampled at the grain by cell (the cell's values) and cellPoint (interpolated)
# sampling, at cells of 0.04, 0.06 (the case's) and 0.08 m, for HB&P, B&P and W&P, and 0.03 m for
# HB&P and B&P; HB&P with cellPoint at one DEM step per exchange;
# the plastic liquids' viscosity cap (mu_0) at 1e3, 1e4 (the cases') and 1e5 Pa s with either
# sampling at 0.06 m. Sub-cell
# shear that the sampling counts as slip gives a plastic drag spurious strength. Writes
# WORK/<variant>/<exchangeEvery>/ and results/convergence/mobility.csv (energy released by the
# grains, granular front, their kinetic energy at 0.5 s).
# Usage: mobility.sh [WORK] (default runs/mobility). About 1 h of one core.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
work=$(realpath -m "${1:-$root/runs/mobility}")
. "$root/results/convergence/quick_run.sh"
for ys in 0 3 10 30.002; do
  quick_run "hb_yield_stress_$ys" HB+P 2 --scene liquid.yieldStress="$ys"
done
# The same liquid by two routes: HB&P's Herschel-Bulkley liquid with tau_c 0, kappa 1e-3 Pa s and
# n 1 is W&P's water (w_cell_0.06); the water with its viscosity x (1 + 1e-12) is the round-off
# floor of that comparison.
quick_run hb_as_water HB+P 2 --couple interpolation=cell --cfd cellSize=0.06 \
  --scene liquid.yieldStress=0 --scene liquid.consistency=1e-3 --scene liquid.flowIndex=1
quick_run w_noise W+P 2 --couple interpolation=cell --cfd cellSize=0.06 \
  --scene liquid.viscosity=0.001000000000001
for liquid in HB+P B+P W+P; do
  tag=$(echo "$liquid" | tr 'A-Z+' 'a-z_' | sed 's/_p$//')
  for dx in 0.04 0.06 0.08; do
    quick_run "${tag}_cell_$dx" "$liquid" 2 --couple interpolation=cell --cfd cellSize="$dx"
    quick_run "${tag}_cellPoint_$dx" "$liquid" 2 --couple interpolation=cellPoint --cfd cellSize="$dx"
  done
done
quick_run hb_cellPoint_0.06 HB+P 1 --couple interpolation=cellPoint --cfd cellSize=0.06
for sampling in cell cellPoint; do  # the plastic mixtures towards cells of one diameter
  quick_run "hb_${sampling}_0.03" HB+P 2 --couple interpolation="$sampling" --cfd cellSize=0.03
  quick_run "b_${sampling}_0.03" B+P 2 --couple interpolation="$sampling" --cfd cellSize=0.03
done
for cap in 1e3 1e5; do  # the regularisation at vanishing shear; 1e4 is the *_0.06 runs above
  for liquid in HB+P B+P; do
    tag=$(echo "$liquid" | tr 'A-Z+' 'a-z_' | sed 's/_p$//')
    for sampling in cell cellPoint; do
      quick_run "${tag}_${sampling}_cap$cap" "$liquid" 2 --couple interpolation="$sampling" \
        --cfd cellSize=0.06 --scene liquid.viscosityCap="$cap"
    done
  done
done
/usr/bin/python3 "$root/results/convergence/quick_ladder_csv.py" "$work" \
  "$root/results/convergence/mobility.csv"
