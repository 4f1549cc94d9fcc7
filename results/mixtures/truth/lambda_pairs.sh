#!/usr/bin/env bash
# The drifts' convergence error at the truth tier: each mixture over its first END seconds at its
# exchange interval and one step finer (W&P and B&P every 27 against every 9 DEM steps to 1 s,
# HB&P every 9 against every 3 to 0.5 s), both from the shipped sample. Each finished run's drifts
# (mixflow mixture-lambdas) go to lambda_convergence/<scene>-every<N>.json here; mixflow
# mixture-results pairs them (partner minus run for each median, quantile and slope).
#
# The drifts need every field write of a run, which a checkpoint does not keep, so each run is
# sized to finish inside a session: measured 0.9 h (W&P every 27), 0.8 h (B&P every 27) and 1.0 h
# (W&P every 9) of wall time on one core; HB&P every 9 about 1 h, the other finer ones 1.2-2 h.
# A stopped run resumes where it stopped when the script is rerun on the same machine; a run
# whose JSON is committed is skipped afterwards, so a pair may span sessions and machines.
# Usage: results/mixtures/truth/lambda_pairs.sh [RUNS] (default runs); SCENES="W+P" for some.
set -euo pipefail
root=$(cd "$(dirname "$0")/../../.." && pwd)
runs=$(realpath -m "${1:-$root/runs}")/lambda_pairs
out=$root/results/mixtures/truth/lambda_convergence
cd "$root"
mixflow() { /usr/bin/python3 -m mixflow "$@"; }
wanted() { [ -z "${SCENES:-}" ] || [[ " $SCENES " == *" $1 "* ]]; }

# drifts SCENE END EVERY
drifts() {
  local scene=$1 end=$2 n=$3
  if [ -f "$out/$scene-every$n.json" ]; then
    echo "lambda_pairs.sh: $scene every $n has its drifts: $out/$scene-every$n.json"
    return
  fi
  wanted "$scene" || return 0
  mixflow suite --tier truth --scenes "$scene" --work "$runs/$scene-every$n" \
    --set controlDict.endTime="$end" --set couplingProperties.exchangeEvery="$n"
  mixflow mixture-lambdas --work "$runs/$scene-every$n" --scenes "$scene" \
    --out "$out/$scene-every$n.json"
  echo "lambda_pairs.sh: wrote $out/$scene-every$n.json; commit it"
}

drifts W+P 1.0 27
drifts W+P 1.0 9
drifts B+P 1.0 27
drifts B+P 1.0 9
drifts HB+P 0.5 9
drifts HB+P 0.5 3
mixflow mixture-results --work results/li_zhao_2018/records/truth \
  --partner results/li_zhao_2018/records/partners --out results/mixtures/truth
