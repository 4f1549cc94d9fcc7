#!/usr/bin/env bash
# Pure-liquid results into results/pure_liquids/.
# Usage: scripts/liquid_results.sh [RANKS] [side-walls]
# Runs copies of cases/W, HB, B, HB-I, B-I in WORK (default /tmp/mixflow-liquid) at a fidelity this
# machine manages (2-D: dimensions 2, one cell across the width; the cases themselves are 3-D):
#   calibration  W in an 8 m channel: the time the water front reaches x fixes the channel length
#                whose outlet it reaches at t = 1.25 s (Li & Zhao: water leaves from about 1.25 s)
#   W, HB, B     in the calibrated channel, cells 0.02 m (H/30), 4 s
#   HB-I, B-I    cells H/20 and H/10 in their own channels, 5 s and 30 s
#   cap-*        the regularisation: HB (as above) and the yield-slump test column with viscosity
#                caps 1e2, 1e3, 1e4 (default), 1e5 Pa s
# then mixflow liquid-results makes the plots, CSVs and summary.json.
# With side-walls only this runs: case W as committed (3-D, 0.03 m cells, no-slip walls at
# z = 0 and W; 156 000 cells, about 45 min serial) and the same in 2-D, both to 2.2 s, and
# liquid_results.py --side-walls compares them (side_walls.csv/.png/.json). Finished runs (log with
# "End") are not run again; delete WORK/<run> to redo one. MIXFLOW_NO_BUILD=1 skips the build
# (then MIXFLOW_BUILD names the build directory whose bin/ holds mixflowPrepare and mixflowFoam).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
ranks=${1:-1}
work=${WORK:-/tmp/mixflow-liquid}
if [ -z "${MIXFLOW_NO_BUILD:-}" ]; then bash "$root/scripts/build.sh"; fi
export PATH="${MIXFLOW_BUILD:-$root/build}/bin:$PATH"
mkdir -p "$work"

# The copies' Allrun scripts source this checkout's run functions.
export MIXFLOW_ROOT="$root"
# prepare RUN CASE: fresh copy of cases/CASE as WORK/RUN, 2-D.
prepare() {
  local run=$1 case=$2
  rm -rf "${work:?}/$run" && cp -r "$root/cases/$case" "$work/$run"
  sed -i -E 's/^dimensions +3;/dimensions  2;/' "$work/$run/system/cfdDict"
}
# set FILE KEY VALUE: replace the first "KEY value;" in FILE (indented entries too).
set_entry() {
  sed -i -E "0,/^( *)$2 +[^;]*;/s//\1$2 $3;/" "$1"
  grep -Eq "^ *$2 $3;" "$1" || { echo "cannot set $2 in $1" >&2; exit 1; }
}
done_run() { [ -f "$work/$1/log.mixflowFoam" ] && grep -q "^End" "$work/$1/log.mixflowFoam"; }
run() {
  local r=$1
  echo "$(date +%T) running $r"
  (cd "$work/$r" && ./Allrun "$ranks" > log.Allrun 2>&1) ||
    { echo "run $r failed: see $work/$r/log.Allrun" >&2; exit 1; }
}

# Side walls: W in 3-D (as committed) against 2-D, same cells and channel.
if [ "${2:-}" = side-walls ]; then
  for d in 2 3; do
    r=sidewalls-${d}d
    if ! done_run "$r"; then
      prepare "$r" W
      sed -i -E "s/^dimensions +[0-9];/dimensions  $d;/" "$work/$r/system/cfdDict"
      set_entry "$work/$r/system/controlDict" endTime 2.2
      set_entry "$work/$r/system/controlDict" writeInterval 0.05
      run "$r"
    fi
  done
  /usr/bin/python3 -m mixflow liquid-results --side-walls "$work" \
    "$root/results/pure_liquids" --command "scripts/liquid_results.sh $ranks side-walls"
  exit 0
fi

# 1. Channel-length calibration with W.
if ! done_run calibration; then
  prepare calibration W
  sed -i -E '/^channel/,/^}/s/^( *)length +[^;]*;/\1length    8.0;/' \
    "$work/calibration/constant/sceneProperties"
  set_entry "$work/calibration/system/cfdDict" cellSize 0.02
  set_entry "$work/calibration/system/controlDict" endTime 1.6
  run calibration
fi
lc=$(/usr/bin/python3 -m mixflow liquid-results --calibrate "$work/calibration" 1.25)
echo "calibrated channel length: $lc m"

# 2. W, HB, B in the calibrated channel.
for c in W HB B; do
  if ! done_run "$c"; then
    prepare "$c" "$c"
    sed -i -E "/^channel/,/^}/s/^( *)length +[^;]*;/\1length    $lc;/" \
      "$work/$c/constant/sceneProperties"
    set_entry "$work/$c/system/cfdDict" cellSize 0.02
    run "$c"
  fi
done

# 3. HB-I, B-I in their own channels.
if ! done_run HB-I; then
  prepare HB-I HB-I
  set_entry "$work/HB-I/system/cfdDict" cellSize 0.0065
  run HB-I
fi
if ! done_run B-I; then
  prepare B-I B-I
  set_entry "$work/B-I/system/cfdDict" cellSize 0.0022
  run B-I
fi

# 4. Regularisation: viscosity cap 1e2 ... 1e5 Pa s on HB and on the slump of the CTest.
for cap in 1e2 1e3 1e5; do
  r=cap-HB-$cap
  if ! done_run "$r"; then
    prepare "$r" HB
    sed -i -E "/^channel/,/^}/s/^( *)length +[^;]*;/\1length    $lc;/" \
      "$work/$r/constant/sceneProperties"
    set_entry "$work/$r/system/cfdDict" cellSize 0.02
    set_entry "$work/$r/constant/sceneProperties" viscosityCap "$cap"
    run "$r"
  fi
done
for cap in 1e2 1e3 1e4 1e5; do
  r=cap-slump-$cap
  if ! done_run "$r"; then
    prepare "$r" HB
    cat > "$work/$r/constant/sceneProperties" <<EOF
FoamFile { version 2.0; format ascii; class dictionary; object sceneProperties; }
// The Bingham slump of the CTest cfd.liquid.yield_slump (tests/cfd/run_liquid_cases.py).
content liquid;
sample { length 0.1; height 0.1; width 0.1; }
channel { length 0.6; height 0.15; }
liquid { rheology Bingham; density 1000; yieldStress 17; plasticViscosity 1.5;
         viscosityCap $cap; surfaceTension 0; }
EOF
    printf 'FoamFile { version 2.0; format ascii; class dictionary; object cfdDict; }\n%s\n' \
      "dimensions 2; cellSize 0.005; maxDeltaT 0.005;" > "$work/$r/system/cfdDict"
    printf 'FoamFile { version 2.0; format ascii; class dictionary; object controlDict; }\n%s\n' \
      "endTime 4; writeInterval 1;" > "$work/$r/system/controlDict"
    run "$r"
  fi
done

/usr/bin/python3 -m mixflow liquid-results --make "$work" "$root/results/pure_liquids" \
  --channel-length "$lc" --command "scripts/liquid_results.sh $ranks"
