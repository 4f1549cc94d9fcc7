#!/usr/bin/env bash
# Set-up (install, configure, build) and the whole test suite with CTest.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/scripts/build.sh"
build=${MIXFLOW_BUILD:-$root/build}
cd "$build"
ctest --output-on-failure -j "$(nproc)" "$@"
