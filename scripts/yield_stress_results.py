#!/usr/bin/python3
"""`mixflow yield-stress-results`: python/mixflow/commands/yield_stress_results.py (python/README.md)."""
import sys

from mixflow.cli import main

sys.exit(main(["yield-stress-results", *sys.argv[1:]]))
