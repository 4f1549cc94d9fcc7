#!/usr/bin/env bash
# The drifts' convergence error at the truth tier: each mixture over its first END seconds at its
# exchange interval and one step finer (W&P and B&P every 27 against every 9 DEM steps to 1 s,
# HB&P every 9 against every 3 to 0.5 s), both from the shipped sample, then mixflow
# mixture-lambdas on the pair into lambda_convergence/<scene>.json (partner minus run for each
# median, quantile and slope).
#
# The drifts need every field write of a run, which a checkpoint does not keep, so each pair is
# sized to finish inside a session: about 0.5 + 1 h (W&P), 0.6 + 1.2 h (B&P) and 0.5 + 1 h
# (HB&P) of one core. A stopped run resumes where it stopped when the script is rerun on the same
# machine; a finished scene's JSON is committed and the scene is skipped afterwards.
# Usage: results/mixtures/truth/lambda_pairs.sh [RUNS] (default runs); SCENES="W+P" for some.
set -euo pipefail
root=$(cd "$(dirname "$0")/../../.." && pwd)
runs=$(realpath -m "${1:-$root/runs}")/lambda_pairs
out=$root/results/mixtures/truth/lambda_convergence
cd "$root"
mixflow() { /usr/bin/python3 -m mixflow "$@"; }
wanted() { [ -z "${SCENES:-}" ] || [[ " $SCENES " == *" $1 "* ]]; }

# pair SCENE END EVERY FINER
pair() {
  local scene=$1 end=$2 every=$3 finer=$4
  if [ -f "$out/$scene.json" ]; then
    echo "lambda_pairs.sh: $scene has its result: $out/$scene.json"
    return
  fi
  wanted "$scene" || return 0
  for n in "$every" "$finer"; do
    mixflow suite --tier truth --scenes "$scene" --work "$runs/$scene-every$n" \
      --set controlDict.endTime="$end" --set couplingProperties.exchangeEvery="$n"
  done
  mixflow mixture-lambdas --work "$runs/$scene-every$every" --partner-work "$runs/$scene-every$finer" \
    --scenes "$scene" --out "$out/$scene.json"
  echo "lambda_pairs.sh: wrote $out/$scene.json; commit it"
}

pair W+P 1.0 27 9
pair B+P 1.0 27 9
pair HB+P 0.5 9 3
