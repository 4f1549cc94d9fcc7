#!/usr/bin/python3
"""`mixflow mixture-lambdas`: python/mixflow/commands/mixture_lambdas.py (python/README.md)."""
import sys

from mixflow.cli import main

sys.exit(main(["mixture-lambdas", *sys.argv[1:]]))
