"""One sweep point as a task: what travels to a worker, what it runs, what comes back.

The worker needs only coatsim installed: the task carries the resolved scenario and the bytes
of every file it reads; the worker writes them into a scratch folder, runs the pipeline as a
function (all variants, a variant that cannot run recorded rather than raised) and returns
plain values: the metrics document, per-variant errors and, on request, every output file.
Everything is caught: a point that cannot run is an outcome, never an exception.
"""

from __future__ import annotations

import socket
import tempfile
import time
import traceback
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Mapping, Optional

import yaml

OK, FAILED = "ok", "failed"


@dataclass(frozen=True)
class PointTask:
    """A point to run: ``scenario`` names its input files by the keys of the inputs passed
    along (``sources`` maps them back to the client's paths, for messages)."""

    point: str
    key: str
    scenario: dict[str, Any]
    sources: Mapping[str, str]
    fast: bool
    keep_outputs: bool
    version: str


@dataclass(frozen=True)
class PointOutcome:
    """What a point gave: ``variants`` maps each variant to None (ran) or its error; ``error``
    is set when the point as a whole could not run; ``reusable`` says the outcome is what a rerun
    would give (so a resumed sweep may keep it; a dead worker or an internal error is not)."""

    point: str
    key: str
    variants: Mapping[str, Optional[str]]
    error: Optional[str] = None
    exit_code: Optional[int] = None
    reusable: bool = True
    metrics: Optional[str] = None
    files: Mapping[str, bytes] = field(default_factory=dict)
    seconds: float = 0.0
    cpu_seconds: float = 0.0
    host: str = ""
    version: str = ""
    traceback: Optional[str] = None

    @property
    def status(self) -> str:
        return OK if self.error is None and not any(self.variants.values()) else FAILED


def variant_names(variants) -> tuple[str, ...]:
    """The names of a resolved scenario's variants (built-in names, programs' ``name``, or a
    built-in variant in a language's name)."""
    from coatsim.run.variant_spec import variant_label

    return tuple(variant_label(v) for v in variants)


def one_line(text: str) -> str:
    """The first non-empty line of a message."""
    return next((line.strip() for line in str(text).splitlines() if line.strip()), "") or "(no message)"


def failed(task: PointTask, variants: tuple[str, ...], error: str, *, exit_code: Optional[int] = None,
           reusable: bool = False, **extra: Any) -> PointOutcome:
    """The outcome of a point that could not run at all."""
    return PointOutcome(task.point, task.key, {v: error for v in variants}, error=error, exit_code=exit_code,
                        reusable=reusable, **extra)


def run_point(task: PointTask, inputs: Mapping[str, bytes]) -> PointOutcome:
    """Run every variant of one point in a scratch folder (the function a Dask worker runs)."""
    from coatsim import __version__
    from coatsim.core.errors import CoatsimError

    started, cpu_started = time.perf_counter(), time.process_time()
    variants = variant_names(task.scenario.get("variants", ()))
    extra = {"host": socket.gethostname(), "version": __version__}
    if __version__ != task.version:
        return failed(task, variants, f"the worker runs coatsim {__version__}, the client {task.version}; install "
                      "the same version everywhere", **extra)
    with tempfile.TemporaryDirectory(prefix="coatsim-point-") as tmp:
        scratch = Path(tmp)

        def clean(message: str) -> str:
            text = one_line(message).replace(f"{scratch}/", "")
            for name, source in task.sources.items():
                text = text.replace(name, source)
            return text

        try:
            from coatsim.run.pipeline import run_scenario

            for name, data in inputs.items():
                target = scratch / name
                target.parent.mkdir(parents=True, exist_ok=True)
                target.write_bytes(data)
            scenario = scratch / "scenario.yaml"
            scenario.write_text(yaml.safe_dump(task.scenario, sort_keys=False), encoding="utf-8")
            out = scratch / "out"
            result = run_scenario(scenario, out, fast=task.fast, progress=False, keep_going=True,
                                  report=task.keep_outputs)
        except CoatsimError as exc:
            return failed(task, variants, clean(str(exc)), exit_code=exc.exit_code, reusable=True,
                          seconds=time.perf_counter() - started, cpu_seconds=time.process_time() - cpu_started,
                          **extra)
        except Exception as exc:  # a bug or the machine (memory): reported, never reused
            return failed(task, variants, clean(f"internal error: {type(exc).__name__}: {exc}"),
                          traceback=traceback.format_exc(), seconds=time.perf_counter() - started,
                          cpu_seconds=time.process_time() - cpu_started, **extra)
        files = {}
        if task.keep_outputs:
            # every output (not the run's own lock and manifest of its scratch folder)
            files = {p.relative_to(out).as_posix(): p.read_bytes() for p in sorted(out.rglob("*"))
                     if p.is_file() and not p.name.startswith(".")}
        status = {v: (clean(result.failures[v]) if v in result.failures else None) for v in variants}
        return PointOutcome(task.point, task.key, status, metrics=(out / "metrics.json").read_text(encoding="utf-8"),
                            files=files, seconds=time.perf_counter() - started,
                            cpu_seconds=time.process_time() - cpu_started, **extra)
