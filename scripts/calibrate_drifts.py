#!/usr/bin/python3
"""`mixflow calibrate-drifts`: python/mixflow/commands/calibrate_drifts.py (python/README.md)."""
import sys

from mixflow.cli import main

sys.exit(main(["calibrate-drifts", *sys.argv[1:]]))
