#!/usr/bin/python3
"""`mixflow viscous-packing`: python/mixflow/commands/viscous_packing.py (python/README.md)."""
import sys

from mixflow.cli import main

sys.exit(main(["viscous-packing", *sys.argv[1:]]))
