# Sourced by the quick-scene ladders (void_jumps.sh, mobility.sh): one run of cases/W+P-quick to
# 0.5 s through tests/coupling/run_mixture_case.py into $work/<variant>/<exchangeEvery>, skipped
# once done. A run that fails the runner's conservation checks is kept and marked (checks_failed);
# quick_ladder_csv.py tabulates them. Needs $root and $work.
quick_run() {  # variant liquid-case (W+P: the case's water) exchangeEvery [run_mixture_case.py options]
  local variant=$1 liquid=$2 n=$3 w="$work/$1/$3"
  shift 3
  [ -f "$w/done" ] && return
  rm -rf "$w" && mkdir -p "$(dirname "$w")"
  local liquid_opt=()
  [ "$liquid" != W+P ] && liquid_opt=(--liquid-case "$liquid")
  /usr/bin/python3 "$root/tests/coupling/run_mixture_case.py" --root "$root" \
    --bindir "${MIXFLOW_BUILD:-$root/build}/bin" --workdir "$w" "${liquid_opt[@]}" \
    --end 0.5 --couple exchangeEvery="$n" "$@" >"$w.log" 2>&1 || touch "$w/checks_failed"
  touch "$w/done"
}
