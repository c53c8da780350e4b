"""Progress of long work: a rich bar on stderr when it is a terminal (nothing otherwise), and the
wall-time budget ``seconds`` (coatsim.core.budgets) checked at every step, so that a user can bound
any long command (``coatsim --budget seconds=600 ...``) and it stops with a one-line error
instead of running on."""

from __future__ import annotations

import sys
import time
from contextlib import contextmanager
from typing import Callable, Iterator, Optional

from coatsim.core.budgets import check_budget

#: Called as ``advance(amount=1, description=None)`` after each step of the work.
Advance = Callable[..., None]
#: Called with the name of the step that starts now.
Step = Callable[[str], None]

_clock: list[float] = []  # when the command started (set by the command line; a library call has no bound)


def start_clock() -> None:
    """Start the command's clock: the budget ``seconds`` bounds the time from here."""
    _clock[:] = [time.monotonic()]


def check_time(what: str) -> None:
    """Stop (BudgetExceeded) when the command has run longer than the budget ``seconds``."""
    if _clock:
        check_budget(f"{what}: seconds of wall time", time.monotonic() - _clock[0], "seconds",
                     "give the command less work (a coarser tolerance, spacing or step)")


@contextmanager
def progress(label: str, total: Optional[float], show: Optional[bool] = None) -> Iterator[Advance]:
    """A step function for ``total`` steps of work named ``label`` (None: an unknown total). A
    bar shows on a terminal (``show`` overrides); every step checks the time budget."""
    if show is None:
        show = sys.stderr.isatty()
    if not show:
        def quiet(amount: float = 1.0, description: Optional[str] = None) -> None:
            check_time(label)

        yield quiet
        return
    from rich.console import Console
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

    columns = (TextColumn("{task.description:<40}"), BarColumn(), MofNCompleteColumn(), TimeElapsedColumn())
    with Progress(*columns, console=Console(stderr=True), transient=True) as bar:
        task = bar.add_task(label, total=total)

        def advance(amount: float = 1.0, description: Optional[str] = None) -> None:
            check_time(label)
            bar.update(task, advance=amount, description=description or label)

        yield advance


def labelled(advance: Advance) -> Step:
    """A step function that names the step starting now (and checks the time budget)."""
    return lambda label: advance(1, label)
