#!/usr/bin/env bash
# Set-up (install, configure, build) and one run of a case: scripts/run.sh [CASE] [RANKS]
# Default: cases/W+P-quick (a quick mixture scene), serial. The case runs in place; outputs land inside the case directory.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/scripts/build.sh"
case_name=${1:-W+P-quick}
ranks=${2:-1}
case_dir="$root/cases/$case_name"
[ -d "$case_dir" ] || { echo "scripts/run.sh: no case '$case_name' in $root/cases" >&2; exit 2; }
export PATH="${MIXFLOW_BUILD:-$root/build}/bin:$PATH"
cd "$case_dir" && ./Allrun "$ranks"
