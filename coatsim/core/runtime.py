"""Process settings for running coatsim's numerics, applied by entry points (never at import).

coatsim computes on one thread per process and gets its parallelism from processes (Dask
workers). Multi-threaded OpenMP regions around tiny problems cost far more than they save:
scipy's batched ``linalg.solve`` on a 3 x 3 system (inside every cubic spline of three points,
as toppra builds for short moves) takes 8 ms of CPU with a thread team on two busy cores and
0.02 ms on one thread. Dask's nanny sets the same for its workers.
"""

from __future__ import annotations

import gc
import os
from contextlib import contextmanager
from typing import Iterator


def single_threaded_numerics() -> None:
    """One OpenMP thread unless the user chose otherwise; call before numerical libraries load
    (the runtime reads the setting once)."""
    os.environ.setdefault("OMP_NUM_THREADS", "1")


@contextmanager
def long_lived_imports() -> Iterator[None]:
    """Imports made for one command, whose objects live as long as it: the cyclic garbage
    collector off while they run (importing leaves few cycles to collect, and each pass would
    walk every object made so far), then every object alive frozen out of the collector's
    generations (``gc.freeze``), so that the full collections of the command's work do not walk
    the modules, classes and functions again (a quarter of a second of CPU time on a full run of
    paper_spiral). Run that work under ``keep_frozen``, which gives them back to the collector
    when it ends (for in-process callers: tests, notebooks)."""
    enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        gc.freeze()
        if enabled:
            gc.enable()


@contextmanager
def keep_frozen() -> Iterator[None]:
    """The objects ``long_lived_imports`` froze kept out of the collector's passes while the body
    runs, given back to it when the body ends."""
    try:
        yield
    finally:
        gc.unfreeze()
