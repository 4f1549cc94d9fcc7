#!/usr/bin/python3
"""`mixflow bulk-stages`: python/mixflow/commands/bulk_stages.py (python/README.md)."""
import sys

from mixflow.cli import main

sys.exit(main(["bulk-stages", *sys.argv[1:]]))
