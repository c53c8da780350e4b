"""The console entry point called in-process, for tests that call it outside a fixture."""

from __future__ import annotations

import contextlib
import io
import sys

import pytest

from coatsim.cli import main


def cli(*args: object) -> tuple[int, str, str]:
    """Run ``coatsim ARGS...`` in-process: (exit code, stdout, stderr)."""
    out, err = io.StringIO(), io.StringIO()
    argv, sys.argv = sys.argv, ["coatsim", *map(str, args)]
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err), pytest.raises(SystemExit) as info:
            main()
    finally:
        sys.argv = argv
    return int(info.value.code or 0), out.getvalue(), err.getvalue()
