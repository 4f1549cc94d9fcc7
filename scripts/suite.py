#!/usr/bin/python3
"""`mixflow suite`: python/mixflow/commands/suite.py (python/README.md)."""
import sys

from mixflow.cli import main

sys.exit(main(["suite", *sys.argv[1:]]))
