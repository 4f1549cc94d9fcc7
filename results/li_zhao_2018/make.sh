#!/usr/bin/env bash
# The reproduction report from its runs: the dry and liquid scenes at the reference tier, the
# mixtures at the truth tier, each mixture beside its partner one exchange step finer (W&P and B&P
# every 9 DEM steps, HB&P every 3: each number's convergence error), then results/mixtures/truth,
# its drifts and results/li_zhao_2018.
#
# Each scene, once finished, is recorded into records/<group>/<scene> here (mixflow
# scene-record: what the report reads, a few hundred kB): commit the record, and the scene is
# done for every later session and machine. A scene with a record is skipped; one without is a
# `mixflow suite` run that resumes where it stopped (on the rank count it was started on). So
# the script is rerun, a session at a time, until it ends with the report, which it makes from
# the records alone. A mixture longer than a session is stopped (Ctrl-C, or kill the suite's
# process group) and checkpointed: `mixflow scene-checkpoint RUNS/<group run>/<scene> --out
# results/li_zhao_2018/checkpoints/<group>` keeps its last field write, the particles' restart
# and its outputs so far, thinned (a few MB); commit it, and a later session on any machine
# restores it here (when RUNS has no such run) and resumes it. Its record replaces it.
# Cost on this 2-core machine (one core each): the mixtures 1.4-2.8 h, their partners about 2.3,
# 3 and 8 h, a reference-tier dry scene a few hours, the five liquids 20 min (docs/suite.md).
# Usage: results/li_zhao_2018/make.sh [RUNS] (default runs); NP=2 for two ranks per scene;
# SCENES="W HB" to run only those scenes' steps (the report is made once every scene's record
# exists, and again as each partner's lands).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
runs=$(realpath -m "${1:-$root/runs}")
cd "$root"
records=results/li_zhao_2018/records
checkpoints=results/li_zhao_2018/checkpoints
np=${NP:-1}
mixflow() { /usr/bin/python3 -m mixflow "$@"; }
wanted() { [ -z "${SCENES:-}" ] || [[ " $SCENES " == *" $1 "* ]]; }

# scene GROUP WORK SCENE [suite arguments]: run SCENE into WORK unless it has a record in GROUP,
# then record it.
scene() {
  local group=$1 work=$2 name=$3
  shift 3
  if [ -f "$records/$group/$name/.done" ]; then
    echo "make.sh: $name ($group) has its record: records/$group/$name"
    return
  fi
  wanted "$name" || return 0
  if [ ! -d "$work/$name" ] && [ -d "$checkpoints/$group/$name" ]; then
    mixflow scene-checkpoint --restore "$checkpoints/$group/$name" --work "$work"
  fi
  mixflow suite --np "$np" --scenes "$name" --work "$work" "$@"
  mixflow scene-record "$work/$name" --out "$records/$group"
  rm -rf "${checkpoints:?}/$group/$name"
  echo "make.sh: recorded $name; commit $records/$group/$name (and the removal of its checkpoint)"
}

reference_scenes="W HB B HB-I B-I P-I-I P-I-II P-I-III P-I-IV P-I-V P"
for s in $reference_scenes; do
  scene reference "$runs/reference" "$s" --tier reference
done
for s in W+P B+P HB+P; do
  scene truth "$runs/truth/$s-run" "$s" --tier truth
done
scene partners "$runs/truth/W+P-every9" W+P --tier truth --set couplingProperties.exchangeEvery=9
scene partners "$runs/truth/B+P-every9" B+P --tier truth --set couplingProperties.exchangeEvery=9
scene partners "$runs/truth/HB+P-every3" HB+P --tier truth --set couplingProperties.exchangeEvery=3

# The report needs every scene's record; a partner that is not recorded yet leaves its scene's
# "one step finer" column empty, so the report is made again as each partner lands.
missing="" partners=""
for s in $reference_scenes; do [ -f "$records/reference/$s/.done" ] || missing+=" reference/$s"; done
for s in W+P B+P HB+P; do
  [ -f "$records/truth/$s/.done" ] || missing+=" truth/$s"
  [ -f "$records/partners/$s/.done" ] || partners+=" $s"
done
if [ -n "$missing" ]; then
  echo "make.sh: scenes without a record yet:$missing; rerun to go on"
  exit 0
fi
[ -z "$partners" ] ||
  echo "make.sh: partners without a record yet:$partners (their error bars stay empty); rerun to go on"
# The drifts need the mixtures' extracted fields, which only the runs hold.
if [ -d "$runs/truth/W+P-run/W+P" ] && [ -d "$runs/truth/B+P-run/B+P" ] && [ -d "$runs/truth/HB+P-run/HB+P" ]; then
  mkdir -p "$runs/truth/all"
  for s in W+P B+P HB+P; do ln -sfn "../$s-run/$s" "$runs/truth/all/$s"; done
  mixflow mixture-lambdas --work "$runs/truth/all" --scenes W+P,B+P,HB+P \
    --out results/mixtures/truth/lambdas.json
fi
mixflow mixture-results --work "$records/truth" --partner "$records/partners" \
  --out results/mixtures/truth
mixflow report --work "$records/truth,$records/reference" --partner "$records/partners" \
  --out results/li_zhao_2018
