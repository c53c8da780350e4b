"""The sweep's results table: one row per point x variant, written as Parquet and CSV.

Columns (docs/formats.md, "Sweep results"): ``point``, one per axis (its dotted scenario key; ``axis.KEY``
when the key is also a metric's name, as ``segmentation.tolerance_mm`` is), ``variant``, ``status``
(``ok`` / ``failed``), ``error`` (one line), then every metric of the catalogue in its order (null
on a failed row). Count metrics are integers, the others floats; an axis column is
numeric, boolean or text as its values are (lists and mappings as JSON text).
"""

from __future__ import annotations

import csv
import io
import json
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Mapping, Optional, Sequence

from coatsim.core.fileio import atomic_open, write_text
from coatsim.report.catalogue import METRICS
from coatsim.sweep.points import Point
from coatsim.sweep.task import PointOutcome

FIXED = ("point", "variant", "status", "error")


def axis_column(key: str) -> str:
    """The column of an axis: its dotted key, prefixed with ``axis.`` when a metric has that name."""
    return f"axis.{key}" if key in METRICS or key in FIXED else key


@dataclass(frozen=True)
class Table:
    """Column names and rows (plain Python values, None for null), with each column's kind:
    ``int``, ``float``, ``bool`` or ``str``."""

    columns: tuple[str, ...]
    kinds: tuple[str, ...]
    rows: tuple[tuple[Any, ...], ...]

    def column(self, name: str) -> list[Any]:
        k = self.columns.index(name)
        return [r[k] for r in self.rows]


def _axis_kind(values: Sequence[Any]) -> str:
    present = [v for v in values if v is not None]
    if present and all(isinstance(v, bool) for v in present):
        return "bool"
    if present and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in present):
        return "float" if any(isinstance(v, float) for v in present) else "int"
    if all(isinstance(v, str) for v in present):
        return "str"
    return "json"


def _cast(value: Any, kind: str) -> Any:
    if value is None:
        return None
    if kind == "json":
        return json.dumps(value, sort_keys=True, separators=(",", ":"))
    if kind == "float":
        return float(value)
    return value


def _metric(document: Optional[Mapping[str, Any]], variant: str, key: str) -> Any:
    if document is None:
        return None
    group, name = key.split(".", 1)
    return document.get("variants", {}).get(variant, {}).get(group, {}).get(name)


def build_table(axes: Sequence[str], points: Sequence[Point], outcomes: Mapping[str, PointOutcome],
                variants_of: Mapping[str, Sequence[str]]) -> Table:
    """The rows of every point (in sweep order) and variant (in the scenario's order)."""
    kinds = {a: _axis_kind([p.axes[a] for p in points]) for a in axes}
    metric_kinds = ["int" if info.unit == "count" else "float" for info in METRICS.values()]
    rows = []
    for point in points:
        outcome = outcomes[point.id]
        document = json.loads(outcome.metrics) if outcome.metrics else None
        for variant in variants_of[point.id]:
            error = outcome.variants.get(variant, outcome.error)
            values = [_metric(document, variant, key) if error is None else None for key in METRICS]
            values = [None if v is None else (int(v) if k == "int" else float(v)) for v, k in zip(values, metric_kinds)]
            rows.append((point.id, *(_cast(point.axes[a], kinds[a]) for a in axes), variant,
                         "ok" if error is None else "failed", error, *values))
    columns = ("point", *(axis_column(a) for a in axes), "variant", "status", "error", *METRICS)
    axis_kinds = tuple("str" if kinds[a] == "json" else kinds[a] for a in axes)
    return Table(columns, ("str", *axis_kinds, "str", "str", "str", *metric_kinds), tuple(rows))


def write_parquet(path: Path, table: Table) -> None:
    """``results.parquet`` with typed columns (int64, float64, bool, string; nulls kept)."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    types = {"int": pa.int64(), "float": pa.float64(), "bool": pa.bool_(), "str": pa.string()}
    arrays = [pa.array(table.column(c), type=types[k]) for c, k in zip(table.columns, table.kinds)]
    schema = pa.schema([pa.field(c, types[k]) for c, k in zip(table.columns, table.kinds)])
    with atomic_open(path, "wb") as handle:
        pq.write_table(pa.Table.from_arrays(arrays, schema=schema), handle)


def _csv_text(value: Any) -> str:
    if value is None:
        return ""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return repr(value) if math.isfinite(value) else ""
    return str(value)


def write_csv(path: Path, table: Table) -> None:
    """``results.csv``: a header row, then the rows; null is an empty field, floats round-trip."""
    buf = io.StringIO()
    writer = csv.writer(buf, lineterminator="\n")
    writer.writerow(table.columns)
    writer.writerows([_csv_text(v) for v in row] for row in table.rows)
    write_text(path, buf.getvalue())
