"""The ``coatsim`` command: one Typer app, each command in its own module.

Every CoatsimError becomes one line on stderr and its exit code (coatsim.cli.process).
"""

from __future__ import annotations

import typer

from coatsim.cli import check_program, coat, convert, execute, plan, program, run, schema, segment, sweep

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


@app.callback()
def _main(
    version: bool = typer.Option(False, "--version", callback=_version, is_eager=True, help="Print the version and exit."),
) -> None:
    """coatsim: curves -> tangent-continuous arc/line robot programs -> simulated arm -> coating."""


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
