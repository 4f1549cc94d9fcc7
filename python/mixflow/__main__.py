"""`python3 -m mixflow VERB ...`: the mixflow command (mixflow/cli.py)."""
import sys

from .cli import main

sys.exit(main())
