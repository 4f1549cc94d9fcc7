#!/usr/bin/env bash
# Runs the dry columns P-I-I ... P-I-V (copies of cases/ in WORK, default /tmp/mixflow-runout) and fits
# (l_inf - L)/L = lambda a^alpha into results/runout_scaling/. Usage: scripts/runout_scaling.sh [RANKS]
# Finished scenes (postProcessing/dem/summary.json present) are not run again.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
ranks=${1:-1}
work=${WORK:-/tmp/mixflow-runout}
bash "$root/scripts/build.sh"
export PATH="${MIXFLOW_BUILD:-$root/build}/bin:$PATH"
mkdir -p "$work"
export MIXFLOW_ROOT="$root"  # the copies' Allrun scripts source this checkout's RunFunctions
for c in P-I-I P-I-II P-I-III P-I-IV P-I-V; do
  if [ ! -f "$work/$c/postProcessing/dem/summary.json" ]; then
    rm -rf "${work:?}/$c" && cp -r "$root/cases/$c" "$work/$c"
    (cd "$work/$c" && ./Allrun "$ranks" > log.Allrun 2>&1) || { echo "scene $c failed: see $work/$c/log.Allrun" >&2; exit 1; }
  fi
  echo "$c done"
done
/usr/bin/python3 -m mixflow runout-fit "$work" "$root/results/runout_scaling" \
  "scripts/runout_scaling.sh $ranks"
