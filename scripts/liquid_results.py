#!/usr/bin/python3
"""`mixflow liquid-results`: python/mixflow/commands/liquid_results.py (python/README.md)."""
import sys

from mixflow.cli import main

sys.exit(main(["liquid-results", *sys.argv[1:]]))
