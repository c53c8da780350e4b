"""What ``coatsim program`` reads: a curve (file or ``builtin:NAME``, segmented here) or a
polysegment JSON written by ``coatsim segment``."""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Optional

import numpy as np

from coatsim.core import defaults
from coatsim.core.errors import InputError
from coatsim.geometry.polysegment import Polysegment


@dataclass(frozen=True, eq=False)
class ProgramInput:
    """The curve to program: its polysegment, the input points if any (n, 2), the tolerance."""

    polysegment: Polysegment
    points: Optional[np.ndarray]
    tolerance_mm: float
    source: str
    builtin: bool


def _json_tolerance(doc: object) -> Optional[float]:
    value = doc.get("tolerance_mm") if isinstance(doc, dict) else None
    return float(value) if isinstance(value, (int, float)) and math.isfinite(value) and value > 0 else None


def _check_tolerance(tol: Optional[float]) -> None:
    if tol is not None and not (math.isfinite(tol) and tol > 0.0):
        raise InputError(f"tolerance_mm {tol}: must be a finite number > 0 (mm)", parameters=("tolerance_mm",))


def load_program_input(spec: str, tol: Optional[float], corner_deg: float = defaults.CORNER_DEG, speed_mm_s: Optional[float] = None,
                       tool_accel_mm_s2: Optional[float] = None) -> ProgramInput:
    """Read ``spec``; a curve is segmented within ``tol`` mm (required), a polysegment JSON is
    taken as is (``tol`` defaults to the file's ``tolerance_mm``). With the programmed speed and
    the tool acceleration limit, a curve is segmented for them (no arc tighter than v² / a where
    the curve allows v), and the speed-limited stretches of a JSON are listed again for them."""
    _check_tolerance(tol)
    if spec.lower().endswith(".json"):
        from coatsim.geometry.polysegment_json import polysegment_from_document, read_json_document

        doc = read_json_document(Path(spec))
        poly = polysegment_from_document(doc, spec)
        if speed_mm_s is not None and tool_accel_mm_s2 is not None:
            from coatsim.geometry.dynamics import speed_limited

            poly = replace(poly, speed_limited=speed_limited(poly, speed_mm_s, tool_accel_mm_s2))
        tolerance = tol if tol is not None else _json_tolerance(doc)
        if tolerance is None:
            raise InputError(f"{spec}: no tolerance_mm in the file; give --tol MM")
        return ProgramInput(poly, None, tolerance, spec, False)
    if tol is None:
        raise InputError(f"{spec}: --tol MM is required to segment a curve")
    from coatsim.geometry import load_curve, segment_curve

    curve = load_curve(spec)
    seg = segment_curve(curve, tol, corner_deg=corner_deg, speed_mm_s=speed_mm_s, tool_accel_mm_s2=tool_accel_mm_s2)
    return ProgramInput(seg.polysegment, curve.points, tol, spec, spec.startswith("builtin:"))


@dataclass(frozen=True, eq=False)
class PartInput:
    """The contours to program (one for a curve), their input points where known, the
    tolerance, and notes from reading a drawing."""

    contours: tuple[Polysegment, ...]
    points: tuple[Optional[np.ndarray], ...]
    tolerance_mm: float
    source: str
    builtin: bool
    notes: tuple[str, ...] = ()


def load_part_input(spec: str, tol: Optional[float], layers: Optional[list[str]] = None,
                    join_tol: Optional[float] = None, corner_deg: float = defaults.CORNER_DEG, speed_mm_s: Optional[float] = None,
                    tool_accel_mm_s2: Optional[float] = None) -> PartInput:
    """Read ``spec``: a drawing (DXF/SVG, segmented here within ``tol``), a part or
    polysegment JSON, or a curve (as :func:`load_program_input`, also for the speed)."""
    from coatsim.geometry.cad.drawing import is_drawing

    drawing = is_drawing(spec)
    if (layers or join_tol is not None) and not drawing:
        raise InputError(f"{spec}: --layer and --join-tol apply to drawings (DXF, SVG)")
    if drawing:
        if tol is None:
            raise InputError(f"{spec}: --tol MM is required to segment a drawing")
        from coatsim.geometry.cad.segment_drawing import segment_drawing

        part = segment_drawing(spec, tol, layers=layers or None, join_tolerance_mm=join_tol, corner_deg=corner_deg,
                               speed_mm_s=speed_mm_s, tool_accel_mm_s2=tool_accel_mm_s2)
        return PartInput(tuple(c.polysegment for c in part.contours), tuple(c.curve.points for c in part.contours),
                         tol, spec, False, part.notes)
    if spec.lower().endswith(".json"):
        _check_tolerance(tol)
        from coatsim.geometry.part_json import read_part_json

        part_file = read_part_json(spec)
        tolerance = tol if tol is not None else part_file.tolerance_mm
        if tolerance is None:
            raise InputError(f"{spec}: no tolerance_mm in the file; give --tol MM")
        contours = part_file.contours
        if speed_mm_s is not None and tool_accel_mm_s2 is not None:
            from coatsim.geometry.dynamics import speed_limited

            contours = tuple(replace(c, speed_limited=speed_limited(c, speed_mm_s, tool_accel_mm_s2)) for c in contours)
        return PartInput(contours, (None,) * len(contours), tolerance, spec, False)
    single = load_program_input(spec, tol, corner_deg, speed_mm_s=speed_mm_s, tool_accel_mm_s2=tool_accel_mm_s2)
    return PartInput((single.polysegment,), (single.points,), single.tolerance_mm, spec, single.builtin)
