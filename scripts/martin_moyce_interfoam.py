#!/usr/bin/python3
"""`mixflow martin-moyce-interfoam`: python/mixflow/commands/martin_moyce_interfoam.py (python/README.md)."""
import sys

from mixflow.cli import main

sys.exit(main(["martin-moyce-interfoam", *sys.argv[1:]]))
