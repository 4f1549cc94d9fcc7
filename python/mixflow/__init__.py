"""mixflow's Python package: the code the `mixflow` command, the benchmarks and the tests share
(python/README.md). scripts/install-deps.sh installs it (editable) into Debian's python3."""

import os

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # the checkout
