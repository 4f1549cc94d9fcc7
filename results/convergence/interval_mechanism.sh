#!/usr/bin/env bash
# Where the exchange-interval dependence of the yield-stress mixtures comes from: the quick HB&P
# (cases/W+P-quick with HB+P's liquid, E x 1e-3, DEM step 3.9e-5 s, 0.5 s) at several
# exchangeEvery, one coupling or liquid choice changed per variant. Writes WORK/<variant>/<N>/ and
# results/convergence/interval_mechanism.csv (energy released by the grains, granular front, their
# kinetic energy at 0.5 s). Usage: interval_mechanism.sh [WORK] (default runs/interval_mechanism).
# About 35 min serially on this machine's 2 cores. Every run takes the plain void-fraction split
# (dividedCoeffs smoothing 0), whose eps_f jumps are what these variants measured (void_jumps.sh).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
work=$(realpath -m "${1:-$root/runs/interval_mechanism}")
mkdir -p "$work/liquids/newtonian4/constant" "$work/liquids/hb_cap1e2/constant"
# A Newtonian liquid of the Bingham liquid's plastic viscosity; HB+P's liquid with its cap at 1e2.
cat >"$work/liquids/newtonian4/constant/sceneProperties" <<'END'
liquid { rheology Newtonian; density 1000; viscosity 4; surfaceTension 0.07;
         air { density 1; viscosity 1.48e-5; } }
END
sed -n '/^liquid/,/^}/p' "$root/cases/HB+P/constant/sceneProperties" |
  sed 's/viscosityCap *1e4;/viscosityCap 1e2;/' >"$work/liquids/hb_cap1e2/constant/sceneProperties"
run() {  # variant liquid N [--couple ENTRY=VALUE | --cfd ENTRY=VALUE ...]
  local variant=$1 liquid=$2 n=$3 w="$work/$1/$3"
  shift 3
  [ -f "$w/done" ] && return
  rm -rf "$w" && mkdir -p "$(dirname "$w")"
  /usr/bin/python3 "$root/tests/coupling/run_mixture_case.py" --root "$root" \
    --bindir "${MIXFLOW_BUILD:-$root/build}/bin" --workdir "$w" --liquid-case "$liquid" \
    --end 0.5 --couple exchangeEvery="$n" --couple dividedCoeffs.smoothing=0 "$@" >"$w.log" 2>&1
  touch "$w/done"
}
for n in 25 12 6 3 2 1; do run held HB+P $n; done
run outer_correctors3 HB+P 25 --cfd nOuterCorrectors=3
run outer_correctors6 HB+P 25 --cfd nOuterCorrectors=6
for n in 25 12 6 3; do run defect_kept HB+P $n --couple implicitDragDefect=kept; done
for n in 25 6 2 1; do run newtonian4 "$work/liquids/newtonian4" $n; done
for n in 25 6 2; do run hb_cap1e2 "$work/liquids/hb_cap1e2" $n; done
for n in 25 6 2; do
  run no_resolved_rate HB+P $n --couple "DiFeliceDragCoeffs={ slipCoeffs { resolvedRate off; } }"
  run drag_viscosity_max4 HB+P $n \
    --couple "DiFeliceDragCoeffs={ dragViscosity resolved; viscosityMax 4; }"
done
for n in 25 6 2 1; do
  run extrapolated HB+P $n --couple dragFluidVelocity=extrapolated
  run share HB+P $n --couple dragFluidResponse=share
done
# The Bingham mixture (B+P's liquid: yield stress 2.1 Pa, 4 Pa s) with both schemes.
for n in 25 6 2 1; do run bp_held B+P $n; done
for n in 25 6 2 1; do run bp_share B+P $n --couple dragFluidResponse=share; done
/usr/bin/python3 "$root/results/convergence/quick_ladder_csv.py" "$work" \
  "$root/results/convergence/interval_mechanism.csv"
