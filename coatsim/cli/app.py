"""The ``coatsim`` command: one Typer app, each command in its own module.

Every CoatsimError becomes one line on stderr and its exit code (coatsim.cli.process).
"""

from __future__ import annotations

from typing import Optional

import typer

from coatsim.cli.flags import speaking_flags
from coatsim.cli import check_program, coat, convert, execute, plan, program, run, schema, segment, sweep

BUDGET_HELP = ("Change a resource budget for this command, NAME=N (repeatable; N may be inf): curve_points, "
               "drawing_entities, sweep_points, input_bytes, seconds, ... (docs/reference/budgets.md).")

app = typer.Typer(
    add_completion=False,
    no_args_is_help=True,
    pretty_exceptions_enable=False,
    rich_markup_mode=None,  # help texts are plain: "[default: ...]" must not be read as markup
    help="coatsim: curves -> tangent-continuous arc/line robot programs -> simulated arm -> coating.",
)


def _version(value: bool) -> None:
    if value:
        from coatsim import __version__

        typer.echo(f"coatsim {__version__}")
        raise typer.Exit(0)


def _budgets(settings: Optional[list[str]]) -> None:
    """--budget NAME=VALUE: change a resource budget for this command (and the Dask workers it starts)."""
    if not settings:
        return
    import os

    from coatsim.core.budgets import ENV, parse_settings

    merged = parse_settings(os.environ.get(ENV, ""))
    for text in settings:
        with speaking_flags({ENV: "--budget"}):
            merged.update(parse_settings(text))
    os.environ[ENV] = ",".join(f"{name}={value!r}" for name, value in merged.items())


@app.callback()
def _main(
    version: bool = typer.Option(False, "--version", callback=_version, is_eager=True, help="Print the version and exit."),
    budget: Optional[list[str]] = typer.Option(None, "--budget", metavar="NAME=N", help=BUDGET_HELP),
) -> None:
    """coatsim: curves -> tangent-continuous arc/line robot programs -> simulated arm -> coating."""
    _budgets(budget)


app.command()(segment.segment)
app.command()(run.run)
app.command()(sweep.sweep)
app.command()(schema.schema)
app.command()(coat.coat)
app.command()(program.program)
app.command()(execute.execute)
app.command()(convert.convert)
app.command("check-program")(check_program.check_program)
app.command()(plan.plan)
