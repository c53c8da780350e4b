"""metrics.json: the one file every figure of a run comes from.

``{"format": "coatsim.metrics/1", "scenario": {...}, "variants": {V: {"segmentation": {...},
"motion": {...}, "coating": {...}}}, "gates": [...], "passed": bool}``; the metric names are
those of :mod:`coatsim.report.catalogue`, values are plain numbers (null where undefined).
"""

from __future__ import annotations

import json
import math
from typing import Any, Mapping, Sequence

import numpy as np

from coatsim.report.catalogue import GROUPS, names
from coatsim.report.gates import GateResult

FORMAT = "coatsim.metrics/1"


def plain(value: Any) -> Any:
    """A JSON-ready copy: numpy scalars to Python numbers, NaN and inf to None."""
    if isinstance(value, Mapping):
        return {str(k): plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [plain(v) for v in value]
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, (int, np.integer)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        return float(value) if math.isfinite(value) else None
    return value


def check_groups(variant: str, groups: Mapping[str, Mapping[str, Any]]) -> None:
    """Every variant carries exactly the catalogue's metric names (a programming error if not)."""
    for group in GROUPS:
        got, want = list(groups.get(group, {})), names(group)
        if sorted(got) != sorted(want):
            missing, extra = sorted(set(want) - set(got)), sorted(set(got) - set(want))
            raise ValueError(f"{variant}.{group}: metrics do not match the catalogue (missing {missing}, extra {extra})")


def assemble(
    scenario: Mapping[str, Any],
    variants: Mapping[str, Mapping[str, Mapping[str, Any]]],
    gates: Sequence[GateResult],
) -> dict[str, Any]:
    """The metrics document; groups are ordered as in the catalogue."""
    ordered = {}
    for variant, groups in variants.items():
        check_groups(variant, groups)
        ordered[variant] = {g: {n: plain(groups[g][n]) for n in names(g)} for g in GROUPS}
    gate_rows = [dict(plain(g.to_dict()), label=g.label) for g in gates]
    return {
        "format": FORMAT,
        "scenario": plain(scenario),
        "variants": ordered,
        "gates": gate_rows,
        "passed": all(g.passed for g in gates),
    }


def to_json(document: Mapping[str, Any]) -> str:
    """Indented JSON text, keys in document order, no NaN."""
    return json.dumps(document, indent=2, allow_nan=False, ensure_ascii=False) + "\n"
