"""Command-line layer: parse arguments, call one stage function, print, return the exit code.

Every CoatsimError becomes one line on stderr and its exit code; nothing else is done here.
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Optional

import typer

from coatsim.errors import CoatsimError

app = typer.Typer(
    add_completion=False,
    no_args_is_help=True,
    pretty_exceptions_enable=False,
    help="coatsim: curves -> tangent-continuous arc/line robot programs -> simulated arm -> coating.",
)


def fail(message: str, code: int = 2) -> None:
    """Print a one-line error and exit with ``code``."""
    typer.echo(f"coatsim: error: {message}", err=True)
    raise typer.Exit(code)


@app.command()
def schema() -> None:
    """Print the JSON Schema of scenario files (point your editor's YAML plugin at it)."""
    from coatsim.scenario import json_schema

    typer.echo(json_schema(), nl=False)


def main() -> None:
    """Console entry point: run the app, turning CoatsimError into a one-line error."""
    try:
        app(standalone_mode=False)
    except CoatsimError as exc:
        typer.echo(f"coatsim: error: {exc}", err=True)
        sys.exit(exc.exit_code)
    except typer.Exit as exc:
        sys.exit(exc.exit_code)
    except typer.Abort:
        typer.echo("coatsim: aborted", err=True)
        sys.exit(130)
    except Exception as exc:  # click usage errors and the like
        import click

        if isinstance(exc, click.ClickException):
            exc.show()
            sys.exit(2 if isinstance(exc, click.UsageError) else exc.exit_code)
        raise
    sys.exit(0)


if __name__ == "__main__":
    main()
