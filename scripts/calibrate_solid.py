#!/usr/bin/python3
"""`mixflow calibrate-solid`: python/mixflow/commands/calibrate_solid.py (python/README.md)."""
import sys

from mixflow.cli import main

sys.exit(main(["calibrate-solid", *sys.argv[1:]]))
