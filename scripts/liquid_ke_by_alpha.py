#!/usr/bin/python3
"""`mixflow liquid-ke-by-alpha`: python/mixflow/commands/liquid_ke_by_alpha.py (python/README.md)."""
import sys

from mixflow.cli import main

sys.exit(main(["liquid-ke-by-alpha", *sys.argv[1:]]))
