#!/usr/bin/python3
"""`mixflow mixture-results`: python/mixflow/commands/mixture_results.py (python/README.md)."""
import sys

from mixflow.cli import main

sys.exit(main(["mixture-results", *sys.argv[1:]]))
