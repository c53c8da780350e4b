"""Running sweep points on Dask distributed: a LocalCluster, or an existing scheduler.

Without an address a ``LocalCluster`` of worker processes (one thread each, one per core by
default) runs on this machine; with ``tcp://host:port`` the points go to that scheduler's
workers, wherever they run (started by hand with ``dask scheduler`` / ``dask worker``, or by
dask-jobqueue on SLURM/PBS, dask-kubernetes on Kubernetes). Each input file travels once, as a
task of its own that the points reading it depend on. A worker that dies is replaced and its point rescheduled by
Dask (``distributed.scheduler.allowed-failures`` times); a point that still cannot finish comes
back as a failed outcome, never as an exception.
"""

from __future__ import annotations

import logging
import os
import sys
import threading
from contextlib import contextmanager
from pathlib import Path
from typing import Callable, Iterator, Optional, Sequence

from coatsim.core.errors import ExecutionError, InputError
from coatsim.core.fileio import read_input
from coatsim.core.progress import progress
from coatsim.sweep.task import PointOutcome, PointTask, failed, one_line, run_point, variant_names


def default_workers() -> int:
    """One worker per core this process may use."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # not on Linux
        return max(1, os.cpu_count() or 1)


class DaskSession:
    """A connected ``distributed.Client`` (``with DaskSession(...) as client``): to ``scheduler``,
    or to a LocalCluster of ``workers`` processes (at most one per task). Leaving the block
    closes the client; a local cluster then shuts down in the background (its workers take
    seconds to stop) until ``wait_closed``."""

    def __init__(self, scheduler: Optional[str], workers: Optional[int], n_tasks: int):
        self.scheduler, self.n_workers = scheduler, max(1, min(workers or default_workers(), n_tasks))
        self._cluster = self._client = self._closing = None

    def __enter__(self):
        import dask
        from distributed import Client, LocalCluster

        if self.scheduler is None:
            # one point per worker thread at a time (not Dask's default 1.1, which queues a
            # second one): a worker that dies then takes down, and counts against, only its point
            with dask.config.set({"distributed.scheduler.worker-saturation": 1.0}):
                try:
                    self._cluster = LocalCluster(n_workers=self.n_workers, threads_per_worker=1, processes=True,
                                                 dashboard_address=None, silence_logs=logging.CRITICAL)
                except (RuntimeError, OSError) as exc:
                    raise ExecutionError(f"cannot start a local Dask cluster of {self.n_workers} worker(s): "
                                         f"{one_line(str(exc))}; start one with `dask scheduler` / `dask worker` "
                                         "and pass --scheduler") from None
            self._client = Client(self._cluster)
            return self._client
        _check_address(self.scheduler)
        try:
            self._client = Client(self.scheduler)  # waits distributed.comm.timeouts.connect (30 s)
        except (OSError, TimeoutError, ValueError) as exc:
            raise InputError(f"--scheduler {self.scheduler}: cannot connect ({one_line(str(exc)) or type(exc).__name__}); "
                             "start one with `dask scheduler` and `dask worker ADDRESS`") from None
        try:
            _check_workers(self._client, self.scheduler)
        except BaseException:
            self._client.close()
            raise
        return self._client

    def __exit__(self, kind, value, trace) -> None:
        self._client.close()
        if self._cluster is None:
            return
        if kind is not None:  # interrupted or failed: stop now
            self._cluster.close()
            return
        self._closing = threading.Thread(target=self._cluster.close, name="coatsim-cluster-close")
        self._closing.start()

    def wait_closed(self) -> None:
        if self._closing is not None:
            self._closing.join()


def _check_address(scheduler: str) -> None:
    """Refuse an address Dask cannot connect to at once (no port, a port out of range, a protocol no
    comm backend serves), rather than after its connect timeout."""
    from distributed.comm.addressing import parse_address, parse_host_port
    from distributed.comm.registry import backends

    try:
        protocol, location = parse_address(scheduler)
        if protocol not in backends:
            raise ValueError(f"no Dask comm speaks {protocol}:// (it knows {', '.join(sorted(backends))})")
        if protocol in ("tcp", "tls"):
            port = parse_host_port(location)[1]
            if not 1 <= port <= 65535:
                raise ValueError(f"port {port} is not 1 .. 65535")
    except ValueError as exc:
        raise InputError(f"--scheduler {scheduler}: not a scheduler address ({one_line(str(exc))}); give it as "
                         "`dask scheduler` prints it, e.g. tcp://HOST:8786") from None


def _check_workers(client, scheduler: str) -> None:
    """Every worker already connected runs the same coatsim as this client."""
    from importlib.metadata import PackageNotFoundError, version

    try:
        mine = version("coatsim")
    except PackageNotFoundError:  # running from a source tree that is not installed
        return
    found = client.run(version, "coatsim", on_error="return")
    wrong = {w: v for w, v in found.items() if v != mine}
    if wrong:
        worker, got = sorted(wrong.items())[0]
        what = "no coatsim" if isinstance(got, Exception) else f"coatsim {got}"
        raise InputError(f"--scheduler {scheduler}: worker {worker} has {what}, this client coatsim {mine} "
                         f"({len(wrong)} of {len(found)} workers differ); install the same coatsim on every worker")
    if not found:
        print(f"coatsim: the scheduler at {scheduler} has no workers yet; waiting for some to join", file=sys.stderr)


def run_tasks(client, tasks: Sequence[tuple[PointTask, dict[str, Path]]], on_outcome: Callable[[PointOutcome], None],
              progress: bool) -> None:
    """Submit every task (with its input files) and hand each outcome to ``on_outcome`` as it
    arrives."""
    from distributed import as_completed

    shared: dict[Path, object] = {}
    futures = {}
    for task, files in tasks:
        inputs = {}
        for name, path in files.items():
            if path not in shared:
                # a task that returns the bytes, not scattered data: if the worker holding them
                # dies, the scheduler recomputes them from the task instead of losing the point
                shared[path] = client.submit(file_bytes, read_input(path, "input file"), key=f"coatsim-input-{name}", pure=False)
            inputs[name] = shared[path]
        future = client.submit(run_point, task, inputs, key=f"coatsim-point-{task.point}-{task.key[:16]}", pure=False)
        futures[future] = task
    with _progress(len(futures), progress) as advance:
        for future in as_completed(list(futures)):
            task = futures.pop(future)
            try:
                outcome = future.result()
            except Exception as exc:  # the worker died too often, or cannot load the task
                outcome = failed(task, variant_names(task.scenario.get("variants", ())), _lost(exc))
            future.release()
            on_outcome(outcome)
            advance(outcome)


def draw_on_workers(client, table, axes: Sequence[str], variants: Sequence[str], metrics: Sequence[str]) -> dict:
    """The sweep.html figures drawn on the cluster's workers (which have matplotlib loaded
    already), by metric; those that could not be drawn there are left out."""
    from coatsim.sweep.html import metric_figure

    futures = {m: client.submit(metric_figure, table, tuple(axes), tuple(variants), m, pure=False) for m in metrics}
    drawn = {}
    for metric, future in futures.items():
        try:
            drawn[metric] = future.result()
        except Exception:  # a worker lost: the client draws it
            pass
    return drawn


def file_bytes(data: bytes) -> bytes:
    """An input file's bytes, as a task of their own (shared by the points that read the file)."""
    return data


def _lost(exc: Exception) -> str:
    from distributed import KilledWorker

    if isinstance(exc, KilledWorker):
        return (f"the workers running this point died {exc.allowed_failures + 1} times (out of memory or killed); "
                "it was not finished")
    return f"the worker could not run this point: {type(exc).__name__}: {one_line(str(exc))}"


@contextmanager
def _progress(total: int, enabled: bool) -> Iterator[Callable[[PointOutcome], None]]:
    """A rich progress bar of finished points on stderr when ``enabled`` (and the time budget
    checked as each point finishes)."""
    bad = 0
    with progress("points", total, enabled) as step:

        def advance(outcome: PointOutcome) -> None:
            nonlocal bad
            bad += outcome.status != "ok"
            step(1, f"points ({bad} failed)" if bad else "points")

        yield advance
