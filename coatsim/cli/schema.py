"""``coatsim schema``: the JSON Schema of scenario files."""

from __future__ import annotations

import typer


def schema() -> None:
    """Print the JSON Schema of scenario files (point your editor's YAML plugin at it)."""
    from coatsim.run.scenario import json_schema

    typer.echo(json_schema(), nl=False)
