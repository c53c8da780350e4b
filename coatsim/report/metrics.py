"""metrics.json: the one file every figure of a run comes from.

``{"format": "coatsim.metrics/1", "mode": "full" | "fast", "scenario": {...}, "variants": {V: {"segmentation": {...},
"motion": {...}, "coating": {...}}}, "warnings": [{"variant": V, "message": ...}], "gates": [...], "passed": bool}``;
the metric names are those of :mod:`coatsim.report.catalogue`, values are plain numbers (null where undefined);
``warnings`` lists what the simulated run warned about (TOOL mismatch, joint-limit approach, singularity,
small tracking or joint-limit excesses), each naming its program line. A part of several
contours adds "contours": one entry per contour with its segmentation and motion groups per
variant (the variant groups sum or take the extremes over the part).
"""

from __future__ import annotations

import json
import math
from typing import Any, Mapping, Sequence

import numpy as np

from coatsim.geometry.deviation import hausdorff
from coatsim.geometry.polysegment import Polysegment
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


def segmentation_group(points: np.ndarray, programmed: Polysegment, tolerance_mm: float, corner_deg: float,
                       deviation_mm: float | None = None) -> dict[str, Any]:
    """The programmed curve (polysegment, or polyline as lines) against the input points.

    A junction whose heading changes by more than ``corner_deg`` counts as a corner; the
    tangent break is the largest change among the other junctions. ``deviation_mm`` is the
    Hausdorff distance when already known (it is computed otherwise).
    """
    breaks = np.degrees(programmed.junction_breaks())
    corner = breaks > corner_deg
    smooth = breaks[~corner]
    kappa = np.array([s.curvature for s in programmed.segments])
    jumps = np.abs(np.roll(kappa, -1) - kappa)[: len(breaks)][~corner]
    return {
        "n_segments": programmed.n_segments,
        "n_arcs": programmed.n_arcs,
        "n_lines": programmed.n_lines,
        "n_corners": int(np.count_nonzero(corner)),
        "max_deviation_mm": hausdorff(points, programmed).hausdorff if deviation_mm is None else deviation_mm,
        "tolerance_mm": tolerance_mm,
        "max_tangent_break_deg": float(smooth.max()) if len(smooth) else 0.0,
        "curve_length_mm": programmed.length,
        "max_curvature_jump_per_mm": float(jumps.max()) if len(jumps) else 0.0,
    }


_SUMMED = ("n_segments", "n_arcs", "n_lines", "n_corners", "curve_length_mm")


def combine_segmentation(groups: Sequence[Mapping[str, Any]]) -> dict[str, Any]:
    """The segmentation group of a part from its contours' groups: counts and the curve
    length add up, the tolerance is the one they share, every other figure (deviation,
    tangent break, curvature jump) is the largest."""
    if len(groups) == 1:
        return dict(groups[0])
    out: dict[str, Any] = {}
    for name in groups[0]:
        values = [g[name] for g in groups]
        if name in _SUMMED:
            out[name] = sum(values)
        elif name == "tolerance_mm":
            out[name] = values[0]
        else:
            known = [v for v in values if v is not None]
            out[name] = max(known) if known else None
    return out


def contours_section(contours: Sequence[Any], order: Sequence[int],
                     per_variant: Mapping[str, Sequence[Mapping[str, Mapping[str, Any]]]]) -> list[dict[str, Any]]:
    """``metrics.json`` "contours" of a part: for every contour in drawing order its number,
    its place in the spray order, whether it is closed, where the drawing starts it, and per
    variant its segmentation and motion groups (the catalogue's names)."""
    place = {k: i for i, k in enumerate(order)}
    rows = []
    for k, c in enumerate(contours):
        rows.append({
            "contour": k + 1,
            "spray_order": place[k] + 1,
            "closed": bool(c.curve.closed),
            "source": getattr(c, "origin", "") or c.curve.name,
            "variants": {v: {g: {n: plain(groups[k][g][n]) for n in names(g)} for g in ("segmentation", "motion")}
                         for v, groups in per_variant.items()},
        })
    return rows


def coating_group(coating: Mapping[str, float]) -> dict[str, Any]:
    """The catalogue's coating metrics from the coating stage's metrics."""
    group = {name: coating[name] for name in names("coating") if name in coating}
    group["mass_balance_error"] = abs(coating["deposited_volume_mm3"] / coating["sprayed_volume_mm3"] - 1.0)
    return group


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
    mode: str = "full",
    warnings: Sequence[Mapping[str, str]] = (),
) -> dict[str, Any]:
    """The metrics document; groups are ordered as in the catalogue; ``mode`` says whether
    the run used the scenario's full or fast settings; ``warnings`` are ``{"variant", "message"}``."""
    ordered = {}
    for variant, groups in variants.items():
        check_groups(variant, groups)
        ordered[variant] = {g: {n: plain(groups[g][n]) for n in names(g)} for g in GROUPS}
    gate_rows = [dict(plain(g.to_dict()), label=g.label) for g in gates]
    return {
        "format": FORMAT,
        "mode": mode,
        "scenario": plain(scenario),
        "variants": ordered,
        "warnings": [{"variant": str(w["variant"]), "message": str(w["message"])} for w in warnings],
        "gates": gate_rows,
        "passed": all(g.passed for g in gates),
    }


def to_json(document: Mapping[str, Any]) -> str:
    """Indented JSON text, keys in document order, no NaN."""
    return json.dumps(document, indent=2, allow_nan=False, ensure_ascii=False) + "\n"
