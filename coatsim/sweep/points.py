"""Sweep points: the grid product and the explicit points, each applied to the base scenario,
validated, and given a stable id.

A point is a set of overrides (dotted scenario key -> value). Its id is a hash of those
parameters after validation (so ``200`` and ``200.0`` are the same point), independent of the
order of the sweep file. A key the scenario schema does not know, a value of the wrong type or
an override that makes the scenario malformed is an InputError naming the sweep file's line and
the key; a value that is merely out of range (a negative speed) makes the point ``invalid``: it
becomes a failed row and the sweep goes on.
"""

from __future__ import annotations

import copy
import difflib
import hashlib
import itertools
import json
import math
from dataclasses import dataclass
from typing import Any, Mapping, Optional

from pydantic import ValidationError

from coatsim.core.budgets import check_budget
from coatsim.core.errors import CoatsimError, InputError
from coatsim.run.scenario import Scenario, ScenarioFile, check_gate_metrics, check_references, load_scenario
from coatsim.sweep.spec import SweepFile, parse_key
from coatsim.core.yamlsource import allowed_keys, data_path

# pydantic error types that say "a value out of range", not "a wrong key or type"
_OUT_OF_RANGE = {"greater_than", "greater_than_equal", "less_than", "less_than_equal", "finite_number"}
_MISSING = object()


@dataclass(frozen=True)
class Point:
    """One scenario run of the sweep.

    ``params`` are the point's own overrides (dotted key -> validated value); ``axes`` the value
    of every sweep axis for this point (the base scenario's where the point sets none, None where
    the base does not spell it out either); ``scenario`` the resolved scenario (validated, defaults
    filled, JSON-ready), None when ``invalid`` holds the reason it cannot run.
    """

    id: str
    label: str
    params: Mapping[str, Any]
    axes: Mapping[str, Any]
    scenario: Optional[dict[str, Any]]
    invalid: Optional[str] = None


def canonical_json(value: Any) -> str:
    """Sorted, compact JSON: the text every hash in a sweep is taken of."""
    return json.dumps(value, sort_keys=True, separators=(",", ":"), ensure_ascii=True, allow_nan=False)


def _number_neutral(value: Any) -> Any:
    """Integral floats as ints, so 200 and 200.0 name the same value (also in values that did
    not validate, whose type the schema has not settled)."""
    if isinstance(value, float) and value.is_integer():
        return int(value)
    if isinstance(value, dict):
        return {k: _number_neutral(v) for k, v in value.items()}
    if isinstance(value, list):
        return [_number_neutral(v) for v in value]
    return value


def point_id(params: Mapping[str, Any]) -> str:
    """A stable id of a point's parameters: the whole SHA-256 (64 hex digits), so that two
    different points never share an id (a 40-bit prefix collides within a million points)."""
    return hashlib.sha256(canonical_json(_number_neutral(dict(params))).encode()).hexdigest()


def lookup(data: Any, path: tuple[str | int, ...]) -> Any:
    """The value at ``path`` in nested dicts and lists, or ``_MISSING``."""
    for part in path:
        if isinstance(data, dict) and part in data:
            data = data[part]
        elif isinstance(data, list) and isinstance(part, int) and 0 <= part < len(data):
            data = data[part]
        else:
            return _MISSING
    return data


def _apply(data: dict[str, Any], key: str, value: Any) -> str | None:
    """Set ``key`` (dotted) in ``data`` in place; the reason when it cannot be set."""
    path = parse_key(key)
    node: Any = data
    for depth, part in enumerate(path[:-1]):
        nxt = path[depth + 1]
        here = ".".join(str(p) for p in path[:depth + 1])
        if isinstance(part, int):
            if not isinstance(node, list) or part >= len(node):
                return f"{here}: no list item {part} in the base scenario"
            node = node[part]
            continue
        if not isinstance(node, dict):
            return f"{here}: {'.'.join(str(p) for p in path[:depth]) or 'the scenario'} is not a mapping"
        if part not in node:
            if isinstance(nxt, int):
                return f"{here}: the base scenario writes out no list here to index"
            node[part] = {}
        node = node[part]
    last = path[-1]
    if isinstance(last, int):
        if not isinstance(node, list) or last >= len(node):
            return f"{key}: no list item {last} in the base scenario"
    elif not isinstance(node, dict):
        return f"{key}: {'.'.join(str(p) for p in path[:-1])} is not a mapping"
    node[last] = copy.deepcopy(value)
    return None


def _dotted(loc: tuple) -> str:
    return ".".join(str(p) for p in loc)


def _describe(err: Mapping[str, Any], data: Any) -> str:
    loc = data_path(tuple(err["loc"]), data)
    if err["type"] == "extra_forbidden":
        allowed = allowed_keys(Scenario, loc[:-1], data)
        close = difflib.get_close_matches(str(loc[-1]), allowed, n=1)
        hint = f"; did you mean {close[0]!r}?" if close else (f"; allowed: {', '.join(allowed)}" if allowed else "")
        return "unknown scenario key" + hint
    if err["type"] == "missing":
        return "required key is missing"
    got = err.get("input")
    text = err["msg"].removeprefix("Value error, ")
    return text if isinstance(got, (dict, list)) else f"{text} (got {got!r})"


def _name(where: tuple) -> str:
    """``("grid", key)`` -> ``grid.key``; ``("points", 2, key)`` -> ``points[2].key``."""
    return f"grid.{where[1]}" if where[0] == "grid" else f"points[{where[1]}].{where[2]}"


def _owner(loc: tuple, keys: list[tuple]) -> Optional[tuple]:
    """The override key whose path contains ``loc`` or is contained in it."""
    for key in keys:
        n = min(len(key), len(loc))
        if tuple(loc[:n]) == tuple(key[:n]):
            return key
    return None


class _Resolver:
    """Applies overrides to the base scenario and validates the result."""

    def __init__(self, sweep: SweepFile, base: ScenarioFile, raw: dict[str, Any]):
        self.sweep, self.base, self.raw = sweep, base, raw
        self.base_dump = base.spec.model_dump(mode="json")

    def resolve(self, overrides: Mapping[str, Any], where: Mapping[str, tuple]) -> tuple[dict, Optional[dict], Optional[str]]:
        """(validated params, resolved scenario or None, reason the point cannot run or None)."""
        data = copy.deepcopy(self.raw)
        for key, value in overrides.items():
            problem = _apply(data, key, value)
            if problem is not None:
                raise InputError(f"{self.sweep.where(*where[key])}: {_name(where[key])}: {problem.split(': ', 1)[1]}")
        paths = [parse_key(k) for k in overrides]
        try:
            spec = Scenario.model_validate(data)
        except ValidationError as exc:
            errors = exc.errors()
            for err in errors:
                loc = data_path(tuple(err["loc"]), data)
                owner = _owner(loc, paths)
                if owner is None or err["type"] not in _OUT_OF_RANGE:
                    key = _dotted(owner) if owner is not None else next(iter(overrides))
                    at = where[key]
                    detail = _dotted(loc)
                    culprit = _name(at) if detail == key else f"{_name(at)}: {detail}"
                    raise InputError(f"{self.sweep.where(*at)}: {culprit}: {_describe(err, data)}") from None
            first = errors[0]
            return dict(overrides), None, f"{_dotted(data_path(tuple(first['loc']), data))}: {_describe(first, data)}"
        loaded = ScenarioFile(spec, self.base.path, {})
        # gate checks: blame an override of the gates, else of the variants, else the first
        key0 = next((k for k in overrides if k.startswith("gates")),
                    next((k for k in overrides if k.startswith("variants")), next(iter(overrides))))
        try:
            check_references(spec, loaded)
            check_gate_metrics(loaded)
        except CoatsimError as exc:
            message = str(exc).split(": ", 1)[-1]
            raise InputError(f"{self.sweep.where(*where[key0])}: {_name(where[key0])}: makes the scenario invalid: "
                             f"{message}") from None
        dump = spec.model_dump(mode="json")
        params = {k: lookup(dump, parse_key(k)) for k in overrides}
        return params, dump, None

    def base_value(self, key: str) -> Any:
        value = lookup(self.base_dump, parse_key(key))
        return None if value is _MISSING else value


def _label(params: Mapping[str, Any]) -> str:
    return ", ".join(f"{k}={canonical_json(_number_neutral(v))}" for k, v in params.items())


def expand(sweep: SweepFile) -> tuple[tuple[str, ...], tuple[Point, ...]]:
    """The sweep's axes (dotted keys, grid first, in file order) and its points (grid product in
    file order, the first key varying slowest, then the explicit points)."""
    spec = sweep.spec
    keys = list(spec.grid)
    count = math.prod(len(spec.grid[k]) for k in keys) if keys else 0
    check_budget(f"{sweep.where('grid' if keys else 'points')}: sweep points (the grid's product "
                 f"{' x '.join(str(len(spec.grid[k])) for k in keys) or '0'} and {len(spec.points)} explicit points)",
                 count + len(spec.points), "sweep_points", "sweep fewer values (each point is a run)")
    base = load_scenario(sweep.base_path)
    check_gate_metrics(base)
    raw = _raw_data(base)
    resolver = _Resolver(sweep, base, raw)
    wanted: list[tuple[dict[str, Any], dict[str, tuple], str]] = []
    for combo in itertools.product(*(spec.grid[k] for k in keys)) if keys else ():
        where = {k: ("grid", k) for k in keys}
        wanted.append((dict(zip(keys, combo)), where, "grid point"))
    for i, point in enumerate(spec.points):
        wanted.append((dict(point), {k: ("points", i, k) for k in point}, f"points[{i}]"))
    axes = list(keys) + [k for p in spec.points for k in p if k not in keys]
    axes = list(dict.fromkeys(axes))
    points: list[Point] = []
    seen: dict[str, str] = {}
    for overrides, where, name in wanted:
        params, scenario, invalid = resolver.resolve(overrides, where)
        pid = point_id(params)
        if pid in seen:
            first = next(iter(where.values()))
            raise InputError(f"{sweep.where(*first)}: {name} repeats {seen[pid]} ({_label(params)})")
        seen[pid] = name if name != "grid point" else f"the grid point {_label(params)}"
        values = {a: params[a] if a in params else resolver.base_value(a) for a in axes}
        points.append(Point(pid, _label(params), params, values, scenario, invalid))
    return tuple(axes), tuple(points)


def _raw_data(base: ScenarioFile) -> dict[str, Any]:
    """The base scenario as its file writes it (overrides go into this, so that the scenario's own
    validation decides as it does for a file)."""
    from coatsim.core.yamlsource import load_yaml_with_lines

    data, _ = load_yaml_with_lines(base.path)
    return data
