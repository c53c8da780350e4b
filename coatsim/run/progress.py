"""Progress of a run: a rich bar on stderr, one step per stage and variant, or nothing."""

from __future__ import annotations

from contextlib import contextmanager
from typing import Callable, Iterator

Step = Callable[[str], None]


@contextmanager
def progress_steps(total: int, enabled: bool) -> Iterator[Step]:
    """A rich progress bar on stderr when ``enabled``; otherwise a no-op step function."""
    if not enabled:
        yield lambda label: None
        return
    from rich.console import Console
    from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn

    columns = (TextColumn("{task.description:<40}"), BarColumn(), TextColumn("{task.completed}/{task.total}"),
               TimeElapsedColumn())
    with Progress(*columns, console=Console(stderr=True), transient=True) as bar:
        task = bar.add_task("starting", total=total)

        def step(label: str) -> None:
            bar.update(task, advance=1, description=label)

        yield step
