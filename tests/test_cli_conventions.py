"""Command-line conventions shared by every command: --version, help texts with their defaults."""

from __future__ import annotations

import re

import pytest
import typer

from coatsim import __version__
from coatsim.cli.app import app

COMMANDS = sorted(typer.main.get_command(app).commands)


def test_version(run_cli):
    code, out, err = run_cli(["--version"])
    assert code == 0 and out == f"coatsim {__version__}\n" and err == ""


@pytest.mark.parametrize("name", COMMANDS)
def test_help_shows_every_default(name, run_cli):
    """Every option with a default value says so (once typer's rich markup swallowed the
    "[default: ...]" written in help texts)."""
    code, out, _ = run_cli([name, "--help"])
    assert code == 0
    text = " ".join(out.split())
    command = typer.main.get_command(app).commands[name]
    for param in command.params:
        if param.param_type_name != "option" or param.name == "help" or getattr(param, "is_flag", False):
            continue
        if param.default is None and "[default: " not in (param.help or ""):
            continue  # optional with no default (e.g. --theta-tol, --plot)
        start = text.index(f" {param.opts[-1]} ")
        others = [f" {p.opts[-1]} " for p in command.params if p is not param and p.param_type_name == "option"]
        following = [text.index(o, start + 1) for o in others if o in text[start + 1:]]
        chunk = text[start:min(following, default=len(text))]
        assert "[default: " in chunk, (name, param.name, chunk)


def test_in_text_defaults_survive(run_cli):
    _, out, _ = run_cli(["execute", "--help"])
    assert "[default: the shipped coating_cell.xml]" in " ".join(out.split())
    _, out, _ = run_cli(["program", "--help"])
    assert "[default: on for builtin curves]" in " ".join(out.split())
    _, out, _ = run_cli(["run", "--help"])
    assert re.search(r"\[default: runs/NAME\]", out)
