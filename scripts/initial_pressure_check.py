#!/usr/bin/python3
"""`mixflow initial-pressure-check`: python/mixflow/commands/initial_pressure_check.py (python/README.md)."""
import sys

from mixflow.cli import main

sys.exit(main(["initial-pressure-check", *sys.argv[1:]]))
