#!/usr/bin/python3
"""`mixflow tier-trade`: python/mixflow/commands/tier_trade.py (python/README.md)."""
import sys

from mixflow.cli import main

sys.exit(main(["tier-trade", *sys.argv[1:]]))
