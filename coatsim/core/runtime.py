"""Process settings for running coatsim's numerics, applied by entry points (never at import).

coatsim computes on one thread per process and gets its parallelism from processes (Dask
workers). Multi-threaded OpenMP regions around tiny problems cost far more than they save:
scipy's batched ``linalg.solve`` on a 3 x 3 system (inside every cubic spline of three points,
as toppra builds for short moves) takes 8 ms of CPU with a thread team on two busy cores and
0.02 ms on one thread. Dask's nanny sets the same for its workers.
"""

from __future__ import annotations

import os


def single_threaded_numerics() -> None:
    """One OpenMP thread unless the user chose otherwise; call before numerical libraries load
    (the runtime reads the setting once)."""
    os.environ.setdefault("OMP_NUM_THREADS", "1")
