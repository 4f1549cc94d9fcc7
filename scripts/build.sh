#!/usr/bin/env bash
# Installs the Debian packages (once), configures (once) and builds mixflow into build/.
# Re-running is fast: nothing is reinstalled, reconfigured or rebuilt without need.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/scripts/install-deps.sh"
build=${MIXFLOW_BUILD:-$root/build}
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release
fi
cmake --build "$build" -j "$(nproc)"
