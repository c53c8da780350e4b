"""The command's process: CoatsimErrors, usage errors, signals, memory exhaustion, an output that
cannot be written and bugs each become one line on stderr and their exit code; CoatsimWarnings
print as one line, other libraries' warnings not at all (``COATSIM_TRACEBACK=1`` shows them)."""

from __future__ import annotations

import errno
import os
import signal
import sys
import threading
import warnings
from typing import Callable

import typer

from coatsim.core.errors import CoatsimError, CoatsimWarning, one_line

#: errno values of a standard stream or an output that cannot take more: a full device, a closed pipe
_OUTPUT_ERRNOS = {errno.ENOSPC, errno.EPIPE, errno.EIO, errno.EDQUOT, errno.EBADF, errno.EFBIG}


class _Signalled(BaseException):
    """Raised by the SIGINT/SIGTERM handlers; a BaseException of our own, so that neither click
    nor a library swallows it, while every ``finally`` (temporary files, folder locks) runs."""

    def __init__(self, signum: int):
        super().__init__(signum)
        self.signum = signum


def _raise_signalled(signum: int, frame: object) -> None:
    raise _Signalled(signum)


def _say(text: str) -> None:
    """One line on stderr (written to the descriptor when the stream itself fails)."""
    line = one_line(text) + "\n"
    try:
        sys.stderr.write(line)
        sys.stderr.flush()
    except Exception:
        try:
            os.write(2, line.encode("utf-8", "replace"))
        except OSError:
            pass


def _one_line_warnings(show_other: Callable) -> Callable:
    """A ``warnings.showwarning`` that prints a CoatsimWarning as one line on stderr."""

    def show(message, category, filename, lineno, file=None, line=None) -> None:
        if issubclass(category, CoatsimWarning):
            _say(f"coatsim: warning: {message}")
        else:
            show_other(message, category, filename, lineno, file, line)

    return show


INTERNAL_ERROR_EXIT = 70  # EX_SOFTWARE of sysexits.h
_SIGNAL_EXITS = {signal.SIGINT: (130, "interrupted"), signal.SIGTERM: (143, "terminated")}
_OUT_OF_MEMORY = ("coatsim: error: out of memory; use coarser settings (a larger step, spacing or tolerance) or allow "
                  "the process more memory")


def _stdout_failed(exc: OSError) -> int:
    _quiet_stdout()
    _say(f"coatsim: error: cannot write the output ({exc.strerror or exc}); free space on the device or "
         "send the output elsewhere")
    return 2


def _caused_by_memory(exc: BaseException) -> bool:
    seen = exc.__cause__ or exc.__context__
    return isinstance(seen, MemoryError) or "memory" in str(exc).lower()


def _run(app: typer.Typer) -> int:
    """Run the app and turn every failure into one line on stderr; return the exit code."""
    from coatsim.cli.flags import budget_words

    try:
        # Without standalone mode click returns typer.Exit's code instead of raising it.
        code = app(standalone_mode=False)
        sys.stdout.flush()
    except CoatsimError as exc:
        _say(f"coatsim: error: {exc.reworded(budget_words(exc))}")
        return exc.exit_code
    except typer.Exit as exc:
        return exc.exit_code
    except (_Signalled, KeyboardInterrupt, typer.Abort) as exc:
        status, word = _SIGNAL_EXITS[getattr(exc, "signum", signal.SIGINT)]
        _say(f"coatsim: {word}")
        return status
    except MemoryError:
        _say(_OUT_OF_MEMORY)
        return 3
    except typer.TyperException as exc:  # usage errors
        if len(sys.argv) <= 1:  # `coatsim` alone: the help, as it is shown for --help, exit 2
            typer.echo(exc.format_message(), err=True)
            return exc.exit_code
        # one line, like every other error; `coatsim COMMAND --help` shows the usage
        _say(f"coatsim: error: {exc.format_message()} (see --help)")
        return exc.exit_code
    except OSError as exc:
        if exc.errno not in _OUTPUT_ERRNOS:
            return _internal(exc)
        return _stdout_failed(exc)
    except SystemError as exc:  # a C extension failing under memory pressure
        if _caused_by_memory(exc):
            _say(_OUT_OF_MEMORY)
            return 3
        return _internal(exc)
    except Exception as exc:
        return _internal(exc)
    return code if isinstance(code, int) else 0


def _internal(exc: Exception) -> int:
    if os.environ.get("COATSIM_TRACEBACK"):
        raise exc
    first = (str(exc).strip().splitlines() or [""])[0][:200]
    _say(f"coatsim: internal error: {type(exc).__name__}: {first} (a bug in coatsim; COATSIM_TRACEBACK=1 shows the "
         "traceback)")
    return INTERNAL_ERROR_EXIT


def _quiet_stdout() -> None:
    """Point stdout at /dev/null after it failed, so that the interpreter's last flush cannot
    print a second error."""
    try:
        fd = os.open(os.devnull, os.O_WRONLY)
        os.dup2(fd, sys.stdout.fileno())
        os.close(fd)
    except (OSError, ValueError):
        pass


def run_app(app: typer.Typer) -> int:
    """Run ``app`` as the console command and return its exit code: 0 ok, 1 gate failed, 2 invalid
    input, 3 cannot execute, 70 internal error, 130 interrupted (SIGINT), 143 terminated (SIGTERM)."""
    from coatsim.core.progress import start_clock
    from coatsim.core.runtime import single_threaded_numerics

    start_clock()
    single_threaded_numerics()
    handlers = {}
    if threading.current_thread() is threading.main_thread():
        handlers = {signum: signal.signal(signum, _raise_signalled) for signum in _SIGNAL_EXITS}
    try:
        with warnings.catch_warnings():
            if not os.environ.get("COATSIM_TRACEBACK"):
                warnings.simplefilter("ignore")  # libraries' warnings say nothing a user can act on
            warnings.simplefilter("always", CoatsimWarning)
            warnings.showwarning = _one_line_warnings(warnings.showwarning)
            status = _run(app)
    finally:
        for signum, handler in handlers.items():
            signal.signal(signum, handler)
    try:
        sys.stdout.flush()
    except (OSError, ValueError) as exc:
        if status == 0 and isinstance(exc, OSError):
            status = _stdout_failed(exc)
        _quiet_stdout()
    return status
