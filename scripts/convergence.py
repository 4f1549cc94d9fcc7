#!/usr/bin/python3
"""`mixflow convergence`: python/mixflow/commands/convergence.py (python/README.md)."""
import sys

from mixflow.cli import main

sys.exit(main(["convergence", *sys.argv[1:]]))
