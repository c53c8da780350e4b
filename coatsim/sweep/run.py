"""``coatsim sweep``: expand a sweep file into points, run the missing ones on Dask, write the
results table and sweep.html.

Each point is keyed by a hash of its resolved scenario, the contents of the files it reads, the
fast flag and coatsim's version; a rerun into the same folder reuses every point whose stored
outcome has that key and runs only the rest. Results do not depend on where a point ran.
"""

from __future__ import annotations

import hashlib
import json
import sys
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Mapping, Optional, Sequence

from coatsim import __version__
from coatsim.core.errors import CoatsimError, InputError
from coatsim.core.fileio import write_text
from coatsim.core.outputs_guard import output_folder
from coatsim.sweep.cluster import default_workers
from coatsim.sweep.inputs import bundle, with_absolute_paths
from coatsim.sweep.points import Point, canonical_json, expand
from coatsim.sweep.spec import SweepFile, load_sweep
from coatsim.sweep.store import OUTPUTS, load_point, save_point, write_manifest
from coatsim.sweep.table import Table, build_table, write_csv, write_parquet
from coatsim.sweep.task import PointOutcome, PointTask, failed, variant_names

FORMAT = "coatsim.sweep/1"
MAX_WORKERS_PER_CORE = 4  # a local cluster's workers are processes of ~0.3-1 GB each


@dataclass(frozen=True, eq=False)
class SweepResult:
    """A finished sweep: its points, each point's outcome, the table and the files written;
    ``ran`` points were run now, the others reused from an earlier run."""

    outdir: Path
    axes: tuple[str, ...]
    points: tuple[Point, ...]
    outcomes: Mapping[str, PointOutcome]
    ran: tuple[str, ...]
    table: Table
    gate_failures: Mapping[str, tuple[str, ...]]
    files: tuple[Path, ...]
    seconds: float

    @property
    def failed_points(self) -> list[str]:
        return [p.id for p in self.points if self.outcomes[p.id].status != "ok"]


def cache_key(scenario: Mapping, digests: Mapping[str, str], fast: bool) -> str:
    """What a point's result depends on, hashed."""
    text = canonical_json({"coatsim": __version__, "fast": fast, "inputs": dict(digests), "scenario": dict(scenario)})
    return hashlib.sha256(text.encode()).hexdigest()


def _gate_failures(outcome: PointOutcome) -> tuple[str, ...]:
    if not outcome.metrics:
        return ()
    return tuple(g["label"] for g in json.loads(outcome.metrics).get("gates", []) if not g["passed"])


def run_sweep(path: str | Path, outdir: Optional[str | Path] = None, *, scheduler: Optional[str] = None,
              workers: Optional[int] = None, keep_outputs: bool = False, progress: Optional[bool] = None,
              metrics: Optional[Sequence[str]] = None, force: bool = False) -> SweepResult:
    """Run the sweep at ``path`` into ``outdir`` (default ``runs/<sweep file stem>``).

    ``scheduler`` is a Dask scheduler address (default: a LocalCluster of ``workers`` processes,
    one per core); ``keep_outputs`` keeps every run's full outputs; ``progress`` defaults to a
    bar when stderr is a terminal; ``metrics`` overrides the sweep file's plotted metrics; ``force``
    replaces files of the sweep's output names that coatsim did not write there.
    """
    started = time.perf_counter()
    if workers is not None and workers < 1:
        raise InputError(f"workers {workers}: give at least 1", parameters=("workers",))
    if workers is not None and workers > MAX_WORKERS_PER_CORE * default_workers():
        raise InputError(f"workers {workers}: more than {MAX_WORKERS_PER_CORE} worker processes per core "
                         f"({default_workers()} here) only make the points wait for memory; give at most "
                         f"{MAX_WORKERS_PER_CORE * default_workers()}, or use a scheduler for more machines",
                         parameters=("workers",))
    if workers is not None and scheduler is not None:
        raise InputError("workers sizes the local cluster only; with a scheduler the cluster's own workers run the "
                         "points", parameters=("workers",))
    sweep = load_sweep(path)
    plotted = list(metrics) if metrics else list(sweep.spec.metrics)
    _check_metrics(plotted)
    axes, points = expand(sweep)
    out = Path(outdir) if outdir is not None else Path("runs") / sweep.path.stem
    show = sys.stderr.isatty() if progress is None else progress
    from coatsim.run.scenario import as_dict, load_scenario

    base_variants = variant_names(as_dict(load_scenario(sweep.base_path).spec)["variants"])
    variants_of = {p.id: variant_names(p.scenario["variants"]) if p.scenario else base_variants for p in points}
    variants = list(dict.fromkeys(v for p in points for v in variants_of[p.id]))
    session = None
    with output_folder(out, OUTPUTS, "coatsim sweep", force):
        write_manifest(out, _manifest(sweep, axes, points))
        outcomes, pending = _prepare(out, sweep, points, variants_of, keep_outputs)
        if pending:
            from coatsim.sweep.cluster import DaskSession, draw_on_workers, run_tasks

            by_id = {task.point: (point, scenario) for task, _, point, scenario in pending}

            def store(outcome: PointOutcome) -> None:
                point, scenario = by_id[outcome.point]
                outcomes[outcome.point] = outcome
                save_point(out, outcome, point.params, scenario)

            session = DaskSession(scheduler, workers, len(pending))
            with session as client:
                run_tasks(client, [(t, files) for t, files, _, _ in pending], store, show)
                table = build_table(axes, points, outcomes, variants_of)
                pngs = draw_on_workers(client, table, axes, variants, plotted)
            # a local cluster shuts down while the results are written
        try:
            if session is None:
                table, pngs = build_table(axes, points, outcomes, variants_of), {}
            gates = {p.id: g for p in points if (g := _gate_failures(outcomes[p.id]))}
            ran = tuple(t.point for t, _, _, _ in pending)
            summary = _summary(sweep, axes, points, outcomes, ran, gates, time.perf_counter() - started)
            files = _write_results(out, sweep, table, axes, variants, plotted, points, gates, pngs, summary)
        finally:
            if session is not None:
                session.wait_closed()
    return SweepResult(out, axes, points, outcomes, ran, table, gates, files, time.perf_counter() - started)


def _prepare(out: Path, sweep, points: Sequence[Point], variants_of: dict[str, list[str]], keep_outputs: bool
             ) -> tuple[dict[str, PointOutcome], list[tuple[PointTask, dict[str, Path], Point, dict]]]:
    """Each point's outcome where it is known without running (invalid, unbundlable, stored from
    an earlier run with the same inputs), and the tasks of the others."""
    fast, base_dir = sweep.spec.fast, sweep.base_path.parent
    outcomes: dict[str, PointOutcome] = {}
    pending: list[tuple[PointTask, dict[str, Path], Point, dict]] = []
    for point in points:
        stub = PointTask(point.id, "", {}, {}, fast, keep_outputs, __version__)
        if point.invalid is not None:
            outcomes[point.id] = failed(stub, variants_of[point.id], point.invalid, exit_code=2, reusable=True,
                                        version=__version__)
            save_point(out, outcomes[point.id], point.params, None)
            continue
        try:
            bundled = bundle(point.scenario, base_dir)
        except InputError as exc:
            outcomes[point.id] = failed(stub, variants_of[point.id], str(exc), exit_code=2, reusable=True,
                                        version=__version__)
            save_point(out, outcomes[point.id], point.params, None)
            continue
        key = cache_key(point.scenario, bundled.digests, fast)
        stored = load_point(out, point.id, key, keep_outputs)
        if stored is not None:
            outcomes[point.id] = stored
            continue
        sources = {name: str(p) for name, p in bundled.files.items()}
        task = PointTask(point.id, key, bundled.scenario, sources, fast, keep_outputs, __version__)
        pending.append((task, dict(bundled.files), point, with_absolute_paths(point.scenario, base_dir)))
    return outcomes, pending


def _write_results(out: Path, sweep, table, axes, variants: list[str], plotted: list[str], points: Sequence[Point],
                   gates: dict, pngs: dict, summary) -> tuple[Path, Path, Path]:
    """results.parquet, results.csv and sweep.html."""
    from coatsim.sweep.html import render_sweep_html

    files = (out / "results.parquet", out / "results.csv", out / "sweep.html")
    write_parquet(files[0], table)
    write_csv(files[1], table)
    write_text(files[2], render_sweep_html(f"coatsim sweep: {sweep.path.stem}", summary, table, axes, variants,
                                           plotted, {p.id: p.label for p in points}, gates, pngs))
    return files


def _check_metrics(names: Sequence[str]) -> None:
    from coatsim.report.catalogue import METRICS

    for name in names:
        if name not in METRICS:
            raise InputError(f"metrics: {name!r} is not a metric; see the metrics catalogue", parameters=("metrics",))


def _manifest(sweep: SweepFile, axes: Sequence[str], points: Sequence[Point]) -> dict:
    return {
        "format": FORMAT,
        "sweep": str(sweep.path.resolve()),
        "base": str(sweep.base_path.resolve()),
        "fast": sweep.spec.fast,
        "coatsim": __version__,
        "axes": list(axes),
        "points": [{"point": p.id, "parameters": dict(p.params)} for p in points],
    }


def _summary(sweep: SweepFile, axes, points, outcomes, ran, gates, seconds: float) -> list[tuple[str, str]]:
    bad = sum(outcomes[p.id].status != "ok" for p in points)
    return [
        ("sweep file", str(sweep.path)),
        ("description", sweep.spec.description or "–"),
        ("base scenario", str(sweep.base_path)),
        ("mode", "fast" if sweep.spec.fast else "full"),
        ("axes", ", ".join(axes)),
        ("points", f"{len(points)}: {len(ran)} run now, {reused_count(points, ran)} reused from an earlier run, "
                   f"{sum(p.invalid is not None for p in points)} with an invalid value"),
        ("outcome", f"{len(points) - bad} ran, {bad} failed; {len(gates)} failed a gate"),
        ("coatsim", __version__),
        ("wall time", f"{seconds:.1f} s"),
    ]


def reused_count(points: Sequence[Point], ran: Sequence[str]) -> int:
    """Points whose outcome came from an earlier run."""
    return sum(p.invalid is None and p.id not in ran for p in points)


def sweep_problems(result: SweepResult) -> Optional[CoatsimError]:
    """The error a sweep exits with: a failed point or gate (exit 1), else None."""
    from coatsim.core.errors import GateFailure

    failed_points = result.failed_points
    if not failed_points and not result.gate_failures:
        return None
    parts = []
    if failed_points:
        parts.append(f"{len(failed_points)} of {len(result.points)} point(s) failed")
    if result.gate_failures:
        parts.append(f"{len(result.gate_failures)} point(s) failed a gate")
    return GateFailure(f"{'; '.join(parts)} (see {result.outdir / 'sweep.html'})")
