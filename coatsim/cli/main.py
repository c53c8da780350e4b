"""The console entry point."""

from __future__ import annotations

import sys


def main() -> None:
    """Run ``coatsim`` with the process's arguments and exit with its code (see coatsim.cli.process)."""
    from coatsim.cli.app import app
    from coatsim.cli.process import run_app

    sys.exit(run_app(app))
