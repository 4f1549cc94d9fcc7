#!/usr/bin/python3
"""`mixflow runout-fit`: python/mixflow/commands/runout_fit.py (python/README.md)."""
import sys

from mixflow.cli import main

sys.exit(main(["runout-fit", *sys.argv[1:]]))
