#!/usr/bin/python3
"""`mixflow stability-dem`: python/mixflow/commands/stability_dem.py (python/README.md)."""
import sys

from mixflow.cli import main

sys.exit(main(["stability-dem", *sys.argv[1:]]))
