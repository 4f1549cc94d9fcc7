"""The verbs of the `mixflow` command (mixflow/cli.py), one module each with its main()."""
