"""The command line: one module per command; all flag wording lives here."""

from coatsim.cli.main import main

__all__ = ["main"]
