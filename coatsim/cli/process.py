"""The command's process: CoatsimErrors, usage errors, signals, memory exhaustion and bugs each
become one line on stderr and their exit code; CoatsimWarnings print as one line."""

from __future__ import annotations

import os
import signal
import threading
import warnings
from typing import Callable

import typer

from coatsim.core.errors import CoatsimError, CoatsimWarning


class _Signalled(BaseException):
    """Raised by the SIGINT/SIGTERM handlers; a BaseException of our own, so that neither click
    nor a library swallows it, while every ``finally`` (temporary files, folder locks) runs."""

    def __init__(self, signum: int):
        super().__init__(signum)
        self.signum = signum


def _raise_signalled(signum: int, frame: object) -> None:
    raise _Signalled(signum)


def _one_line_warnings(show_other: Callable) -> Callable:
    """A ``warnings.showwarning`` that prints a CoatsimWarning as one line on stderr."""

    def show(message, category, filename, lineno, file=None, line=None) -> None:
        if issubclass(category, CoatsimWarning):
            typer.echo(f"coatsim: warning: {message}", err=True)
        else:
            show_other(message, category, filename, lineno, file, line)

    return show


INTERNAL_ERROR_EXIT = 70  # EX_SOFTWARE of sysexits.h
_SIGNAL_EXITS = {signal.SIGINT: (130, "interrupted"), signal.SIGTERM: (143, "terminated")}


def _run(app: typer.Typer) -> int:
    """Run the app and turn every failure into one line on stderr; return the exit code."""
    try:
        # Without standalone mode click returns typer.Exit's code instead of raising it.
        code = app(standalone_mode=False)
    except CoatsimError as exc:
        typer.echo(f"coatsim: error: {exc}", err=True)
        return exc.exit_code
    except typer.Exit as exc:
        return exc.exit_code
    except (_Signalled, KeyboardInterrupt, typer.Abort) as exc:
        status, word = _SIGNAL_EXITS[getattr(exc, "signum", signal.SIGINT)]
        typer.echo(f"coatsim: {word}", err=True)
        return status
    except MemoryError:
        typer.echo("coatsim: error: out of memory; use coarser settings (a larger step, spacing or tolerance) "
                   "or allow the process more memory", err=True)
        return 3
    except typer.TyperException as exc:  # usage errors
        # one line, like every other error; `coatsim COMMAND --help` shows the usage
        typer.echo(f"coatsim: error: {exc.format_message()} (see --help)", err=True)
        return exc.exit_code
    except Exception as exc:
        if os.environ.get("COATSIM_TRACEBACK"):
            raise
        first = (str(exc).strip().splitlines() or [""])[0][:200]
        typer.echo(f"coatsim: internal error: {type(exc).__name__}: {first} (a bug in coatsim; "
                   "COATSIM_TRACEBACK=1 shows the traceback)", err=True)
        return INTERNAL_ERROR_EXIT
    return code if isinstance(code, int) else 0


def run_app(app: typer.Typer) -> int:
    """Run ``app`` as the console command and return its exit code: 0 ok, 1 gate failed, 2 invalid
    input, 3 cannot execute, 70 internal error, 130 interrupted (SIGINT), 143 terminated (SIGTERM)."""
    from coatsim.core.runtime import single_threaded_numerics

    single_threaded_numerics()
    handlers = {}
    if threading.current_thread() is threading.main_thread():
        handlers = {signum: signal.signal(signum, _raise_signalled) for signum in _SIGNAL_EXITS}
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("always", CoatsimWarning)
            warnings.showwarning = _one_line_warnings(warnings.showwarning)
            status = _run(app)
    finally:
        for signum, handler in handlers.items():
            signal.signal(signum, handler)
    return status
