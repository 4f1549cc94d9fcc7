#!/usr/bin/python3
"""`mixflow stability-plots`: python/mixflow/commands/stability_plots.py (python/README.md)."""
import sys

from mixflow.cli import main

sys.exit(main(["stability-plots", *sys.argv[1:]]))
