#!/usr/bin/env bash
# The void fraction's jumps against the exchange interval: the quick HB&P and B&P (cases/W+P-quick
# with HB+P's or B+P's liquid, E x 1e-3, DEM step 3.9e-5 s, 0.5 s) at several exchangeEvery with
# the plain divided split (dividedCoeffs smoothing 0) and with the face smoothing the case sets
# (0.5), and the smoothing width at 2 DEM steps. Writes WORK/<variant>/<N>/ and
# results/convergence/void_jumps.csv (energy released by the grains, granular front, their kinetic
# energy at 0.5 s). Usage: void_jumps.sh [WORK] (default runs/void_jumps). About 30 min of one core.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
work=$(realpath -m "${1:-$root/runs/void_jumps}")
. "$root/results/convergence/quick_run.sh"
run() {  # variant liquid-case exchangeEvery smoothing
  quick_run "$1" "$2" "$3" --couple dividedCoeffs.smoothing="$4"
}
for n in 25 6 2 1; do
  run hb_plain HB+P $n 0
  run hb_smoothed HB+P $n 0.5
  run bp_plain B+P $n 0
  run bp_smoothed B+P $n 0.5
done
run hb_smoothing0.25 HB+P 2 0.25
run hb_smoothing1 HB+P 2 1
/usr/bin/python3 "$root/results/convergence/quick_ladder_csv.py" "$work" \
  "$root/results/convergence/void_jumps.csv"
