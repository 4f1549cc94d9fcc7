#!/usr/bin/python3
"""`mixflow calibrate`: python/mixflow/commands/calibrate.py (python/README.md)."""
import sys

from mixflow.cli import main

sys.exit(main(["calibrate", *sys.argv[1:]]))
