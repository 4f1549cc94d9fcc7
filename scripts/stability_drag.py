#!/usr/bin/python3
"""`mixflow stability-drag`: python/mixflow/commands/stability_drag.py (python/README.md)."""
import sys

from mixflow.cli import main

sys.exit(main(["stability-drag", *sys.argv[1:]]))
