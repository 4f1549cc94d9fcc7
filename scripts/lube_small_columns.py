#!/usr/bin/python3
"""`mixflow lube-small-columns`: python/mixflow/commands/lube_small_columns.py (python/README.md)."""
import sys

from mixflow.cli import main

sys.exit(main(["lube-small-columns", *sys.argv[1:]]))
