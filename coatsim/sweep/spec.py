"""Sweep files: the strict schema of a sweep and its YAML loading.

A sweep names a base scenario (relative to the sweep file), whether to run it in fast mode, and
its axes: ``grid`` (dotted scenario keys -> lists of values, full product) and/or ``points`` (a
list of explicit overrides, each a point of its own). ``metrics`` chooses what ``sweep.html``
plots against each axis. Loading is strict: an unknown key, a wrong type or an unknown metric is
an InputError naming the file, the line and the key.
"""

from __future__ import annotations

import difflib
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Mapping

from pydantic import BaseModel, ConfigDict, Field, ValidationError, field_validator, model_validator

from coatsim.core.errors import InputError
from coatsim.report.catalogue import METRICS
from coatsim.report.summary import HEADLINE
from coatsim.core.yamlsource import Loc, format_validation_error, load_yaml_with_lines, where_in

# a dotted scenario key: names (letters, digits, _) and list indices, e.g. gates.0.threshold
_KEY = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*(\.(?:[A-Za-z_][A-Za-z0-9_]*|[0-9]+))*$")
DEFAULT_METRICS = HEADLINE


def parse_key(key: str) -> tuple[str | int, ...]:
    """``"gates.0.threshold"`` -> ``("gates", 0, "threshold")``."""
    return tuple(int(part) if part.isdigit() else part for part in key.split("."))


def _check_key(key: str) -> str:
    if not _KEY.match(key):
        raise ValueError(f"{key!r} is not a dotted scenario key (e.g. motion.speed_mm_s or gates.0.threshold)")
    return key


class SweepSpec(BaseModel):
    """One sweep, as written in a sweep YAML file."""

    model_config = ConfigDict(extra="forbid", strict=True, frozen=True)

    base: str = Field(description="the base scenario YAML, relative to the sweep file")
    description: str = ""
    fast: bool = Field(False, description="run every point with the scenario's fast settings")
    grid: dict[str, list[Any]] = Field(default_factory=dict, description="dotted scenario key -> values (full product)")
    points: list[dict[str, Any]] = Field(default_factory=list, description="explicit points: dotted key -> value")
    metrics: list[str] = Field(default_factory=lambda: list(DEFAULT_METRICS),
                               description="metrics sweep.html plots against each axis (group.name)")

    @field_validator("grid")
    @classmethod
    def _grid(cls, grid: dict[str, list[Any]]) -> dict[str, list[Any]]:
        for key, values in grid.items():
            _check_key(key)
            if not values:
                raise ValueError(f"{key}: give at least one value")
        return grid

    @field_validator("points")
    @classmethod
    def _points(cls, points: list[dict[str, Any]]) -> list[dict[str, Any]]:
        for i, point in enumerate(points):
            if not point:
                raise ValueError(f"points[{i}] sets no key")
            for key in point:
                _check_key(key)
        return points

    @model_validator(mode="after")
    def _some_axis(self) -> SweepSpec:
        if not self.grid and not self.points:
            raise ValueError("a sweep needs 'grid' (key -> list of values) or 'points' (list of overrides)")
        return self


@dataclass(frozen=True)
class SweepFile:
    """A validated sweep with its source file and the line of every key path."""

    spec: SweepSpec
    path: Path
    lines: Mapping[Loc, int]

    def where(self, *loc: str | int) -> str:
        """``file:line`` of the deepest prefix of ``loc`` that the file spells out."""
        return where_in(self.path, self.lines, loc)

    @property
    def base_path(self) -> Path:
        p = Path(self.spec.base).expanduser()
        return p if p.is_absolute() else self.path.parent / p


def load_sweep(path: str | Path) -> SweepFile:
    """Read and validate a sweep YAML file; any defect is an InputError with its line."""
    path = Path(path)
    data, lines = load_yaml_with_lines(path, expected="a sweep (base, grid and/or points)")
    if not isinstance(data, dict):
        raise InputError(f"{path}:1: a sweep is a mapping of keys (base, fast, grid, points, metrics)")
    try:
        spec = SweepSpec.model_validate(data)
    except ValidationError as exc:
        raise InputError(format_validation_error(exc, path, data, lines, SweepSpec)) from None
    loaded = SweepFile(spec, path, lines)
    for i, metric in enumerate(spec.metrics):
        if metric not in METRICS:
            close = difflib.get_close_matches(metric, list(METRICS), n=1)
            hint = f"did you mean {close[0]!r}?" if close else "see the metrics reference (docs/reference/metrics.md)"
            raise InputError(f"{loaded.where('metrics', i)}: metrics[{i}]: unknown metric {metric!r}; {hint}")
    return loaded
