#!/usr/bin/python3
"""`mixflow bulk-model-results`: python/mixflow/commands/bulk_model_results.py (python/README.md)."""
import sys

from mixflow.cli import main

sys.exit(main(["bulk-model-results", *sys.argv[1:]]))
