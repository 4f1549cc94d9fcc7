#!/usr/bin/python3
"""`mixflow report`: python/mixflow/commands/report.py (python/README.md)."""
import sys

from mixflow.cli import main

sys.exit(main(["report", *sys.argv[1:]]))
