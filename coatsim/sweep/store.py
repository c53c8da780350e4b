"""The sweep's output folder: one folder per point, the manifest, the lock, and resuming.

The folder is held like every output folder (coatsim.core.outputs_guard: one process at a time,
only files coatsim wrote there replaced). ``OUTDIR/points/<id>/`` holds ``point.json`` (written last: the point is finished once it is
there), the run's ``metrics.json``, the resolved ``scenario.yaml`` (``coatsim run`` reproduces
the point from it) and, with ``--keep-outputs``, every output of the run. A rerun reuses a
point whose ``point.json`` has the same cache key (resolved scenario, input file contents,
fast mode, coatsim version) and a reusable outcome; everything else runs again.
"""

from __future__ import annotations

import json
import os
import shutil
from pathlib import Path
from typing import Any, Mapping, Optional

import yaml

from coatsim.core.errors import InputError
from coatsim.core.fileio import os_problem, read_input, write_bytes, write_text
from coatsim.core.jsonfile import read_json
from coatsim.sweep.task import PointOutcome

MANIFEST = "sweep.json"
POINT_FORMAT = "coatsim.sweep-point/1"


#: What a sweep writes into its folder (held with coatsim.core.outputs_guard: one lock, one manifest)
OUTPUTS = (MANIFEST, "results.parquet", "results.csv", "sweep.html", "points/")


def point_dir(outdir: Path, point: str) -> Path:
    return outdir / "points" / point


def _clear(folder: Path) -> None:
    """An empty new ``points/<id>`` folder: whatever is there is removed, a symbolic link itself
    and never what it points to (``points/`` is the sweep's own folder, see OUTPUTS)."""
    if folder.is_symlink() or folder.exists() and not folder.is_dir():
        folder.unlink()
    elif folder.exists():
        shutil.rmtree(folder)
    try:
        folder.mkdir(parents=True)
    except OSError as exc:
        raise InputError(f"{folder}: cannot create the point's folder ({os_problem(exc)})") from None


def _json(value: Any) -> str:
    return json.dumps(value, indent=2, ensure_ascii=False, allow_nan=False) + "\n"


def save_point(outdir: Path, outcome: PointOutcome, params: Mapping[str, Any],
               scenario: Optional[Mapping[str, Any]]) -> None:
    """Replace the point's folder with this outcome (its metrics, scenario and outputs)."""
    folder = point_dir(outdir, outcome.point)
    _clear(folder)
    for name, data in outcome.files.items():
        write_bytes(folder / name, data)
    if outcome.metrics is not None:
        write_text(folder / "metrics.json", outcome.metrics)
    if scenario is not None:
        write_text(folder / "scenario.yaml", yaml.safe_dump(dict(scenario), sort_keys=False))
    record = {
        "format": POINT_FORMAT,
        "point": outcome.point,
        "key": outcome.key,
        "parameters": dict(params),
        "status": outcome.status,
        "variants": {v: {"status": "ok" if e is None else "failed", "error": e} for v, e in outcome.variants.items()},
        "error": outcome.error,
        "exit_code": outcome.exit_code,
        "reusable": outcome.reusable,
        "outputs": bool(outcome.files),
        "coatsim": outcome.version,
        "host": outcome.host,
        "seconds": round(outcome.seconds, 3),
        "cpu_seconds": round(outcome.cpu_seconds, 3),
    }
    if outcome.traceback:
        record["traceback"] = outcome.traceback
    write_text(folder / "point.json", _json(record))


def load_point(outdir: Path, point: str, key: str, keep_outputs: bool) -> Optional[PointOutcome]:
    """The stored outcome of ``point`` if a rerun may reuse it (same key, reusable, outputs kept
    when asked for), else None."""
    folder = point_dir(outdir, point)
    try:
        record = read_json(folder / "point.json", "point record")
        metrics_path = folder / "metrics.json"
        metrics = read_input(metrics_path, "metrics").decode("utf-8") if os.path.lexists(metrics_path) else None
    except (InputError, ValueError):  # missing, unreadable or not a file coatsim wrote: run the point again
        return None
    if not isinstance(record, dict) or record.get("format") != POINT_FORMAT or record.get("key") != key:
        return None
    if not record.get("reusable") or (keep_outputs and metrics is not None and not record.get("outputs")):
        return None
    try:
        variants = {v: item["error"] for v, item in record["variants"].items()}
    except (KeyError, TypeError, AttributeError):
        return None
    if metrics is None and record.get("error") is None:
        return None
    return PointOutcome(point, key, variants, error=record.get("error"), exit_code=record.get("exit_code"),
                        reusable=True, metrics=metrics, seconds=float(record.get("seconds") or 0.0),
                        cpu_seconds=float(record.get("cpu_seconds") or 0.0),
                        host=str(record.get("host", "")), version=str(record.get("coatsim", "")))


def write_manifest(outdir: Path, manifest: Mapping[str, Any]) -> None:
    write_text(outdir / MANIFEST, _json(dict(manifest)))

