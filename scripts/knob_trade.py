#!/usr/bin/python3
"""`mixflow knob-trade`: python/mixflow/commands/knob_trade.py (python/README.md)."""
import sys

from mixflow.cli import main

sys.exit(main(["knob-trade", *sys.argv[1:]]))
