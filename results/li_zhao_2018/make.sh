#!/usr/bin/env bash
# The reproduction report from its runs: the dry and liquid scenes at the reference tier, the
# mixtures at the truth tier, each mixture beside its partner one exchange step finer (W&P and B&P
# every 9 DEM steps, HB&P every 3: each number's convergence error), then results/mixtures/truth,
# its drifts and results/li_zhao_2018. Every step is a `mixflow suite` run that skips what is
# finished and resumes what stopped (on the rank count it was started on), so the script is rerun
# until it ends with the report.
# Cost on this 2-core machine (one core each): the mixtures 1.4-2.8 h, their partners about 2.3,
# 3 and 8 h, a reference-tier dry scene a few hours, the five liquids 20 min (docs/suite.md).
# Usage: results/li_zhao_2018/make.sh [RUNS] (default runs); NP=2 for two ranks per scene.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
runs=$(realpath -m "${1:-$root/runs}")
np=${NP:-1}
suite() { /usr/bin/python3 -m mixflow suite --np "$np" "$@"; }

suite --tier reference --scenes W,HB,B,HB-I,B-I,P-I-I,P-I-II,P-I-III,P-I-IV,P-I-V,P \
  --work "$runs/reference"
for s in W+P B+P HB+P; do
  suite --tier truth --scenes "$s" --work "$runs/truth/$s-run"
done
suite --tier truth --scenes W+P --work "$runs/truth/W+P-every9" --set couplingProperties.exchangeEvery=9
suite --tier truth --scenes B+P --work "$runs/truth/B+P-every9" --set couplingProperties.exchangeEvery=9
suite --tier truth --scenes HB+P --work "$runs/truth/HB+P-every3" --set couplingProperties.exchangeEvery=3

mkdir -p "$runs/truth/all"
for s in W+P B+P HB+P; do ln -sfn "../$s-run/$s" "$runs/truth/all/$s"; done
partners="$runs/truth/W+P-every9,$runs/truth/B+P-every9,$runs/truth/HB+P-every3"
cd "$root"
/usr/bin/python3 -m mixflow mixture-results --work "$runs/truth/all" --partner "$partners" \
  --out results/mixtures/truth
/usr/bin/python3 -m mixflow mixture-lambdas --work "$runs/truth/all" --scenes W+P,B+P,HB+P \
  --out results/mixtures/truth/lambdas.json
/usr/bin/python3 -m mixflow report --work "$runs/truth/all,$runs/reference" --partner "$partners" \
  --out results/li_zhao_2018
