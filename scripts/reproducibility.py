#!/usr/bin/python3
"""`mixflow reproducibility`: python/mixflow/commands/reproducibility.py (python/README.md)."""
import sys

from mixflow.cli import main

sys.exit(main(["reproducibility", *sys.argv[1:]]))
