"""mixflow's Python package: the code the scripts, benchmarks and tests share (python/README.md).

An entry point puts this package's folder on sys.path with one line, e.g. from scripts/:
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
"""

import os

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # the checkout
