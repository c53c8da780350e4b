"""segment_drawing: a DXF or SVG drawing and a tolerance in, one verified polysegment per
contour out."""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Optional, Sequence

import numpy as np

from coatsim.core import defaults
from coatsim.core.errors import CoatsimError, InputError
from coatsim.geometry.cad.chaining import chain_pieces
from coatsim.geometry.cad.contour_fit import fit_contour
from coatsim.geometry.cad.read import read_drawing
from coatsim.geometry.curves import Curve
from coatsim.geometry.dynamics import curvature_limit, speed_limited
from coatsim.geometry.segment import Segmentation
from coatsim.geometry.theta import theta_of_polyline

FLATTEN_FRACTION = 0.05  # free-form curves are sampled within this fraction of σ
JOIN_FRACTION = 0.01  # default join tolerance, as a fraction of σ
SUMMARY_CONTOURS = 30  # contours listed one per line in the summary


@dataclass(frozen=True, eq=False)
class ContourSegmentation(Segmentation):
    """One contour of a drawing: a Segmentation whose input curve is the drawn contour
    sampled densely, and the number of drawn pieces it was chained from."""

    n_pieces: int = 0
    origin: str = ""

    def stats(self) -> dict:
        return {**super().stats(), "input_primitives": self.n_pieces}


@dataclass(frozen=True, eq=False)
class PartSegmentation:
    """Every contour of a drawing, in drawing order, with what reading it noted; ``seconds``
    is the wall time (reported on request, never written to a file)."""

    source: str
    contours: tuple[ContourSegmentation, ...]
    units: str
    tolerance_mm: float
    join_tolerance_mm: float
    notes: tuple[str, ...]
    seconds: float

    def stats(self) -> dict:
        polys = [c.polysegment for c in self.contours]
        return {
            "n_contours": len(self.contours),
            "n_closed": sum(p.closed for p in polys),
            "n_segments": sum(p.n_segments for p in polys),
            "n_arcs": sum(p.n_arcs for p in polys),
            "n_lines": sum(p.n_lines for p in polys),
            "n_corners": sum(len(p.corners) for p in polys),
            "input_primitives": sum(c.n_pieces for c in self.contours),
            "max_deviation_mm": max(c.max_deviation_mm for c in self.contours),
            "max_tangent_break_deg": max(math.degrees(p.max_tangent_break()) for p in polys),
        }

    def summary(self) -> str:
        st = self.stats()
        lines = [
            f"{self.source}: {st['n_contours']} contour{'s' if st['n_contours'] != 1 else ''} ({st['n_closed']} "
            f"closed) from {st['input_primitives']} pieces; units {self.units}",
            f"tolerance {self.tolerance_mm:g} mm, join tolerance {self.join_tolerance_mm:g} mm",
            f"segments {st['n_segments']} ({st['n_arcs']} arcs, {st['n_lines']} lines), corners {st['n_corners']}",
            f"max deviation {st['max_deviation_mm']:.6f} mm, max tangent break {st['max_tangent_break_deg']:.3g} deg "
            f"(outside corners)",
        ]
        for k, c in enumerate(self.contours[:SUMMARY_CONTOURS]):
            p = c.polysegment
            lines.append(f"  contour {k + 1}: {'closed' if p.closed else 'open'}, {c.n_pieces} pieces -> "
                         f"{p.n_segments} segments ({p.n_arcs} arcs, {p.n_lines} lines), {len(p.corners)} corners, "
                         f"length {p.length:.3f} mm, deviation {c.max_deviation_mm:.4g} mm; starts at {c.origin}")
        if len(self.contours) > SUMMARY_CONTOURS:
            lines.append(f"  ... and {len(self.contours) - SUMMARY_CONTOURS} more contours")
        lines += [f"note: {n}" for n in self.notes]
        return "\n".join(lines)


def default_join_tolerance(tolerance_mm: float) -> float:
    """The join tolerance used when none is given: far below σ."""
    return JOIN_FRACTION * tolerance_mm


def segment_drawing(
    path: str | Path,
    tolerance_mm: float,
    layers: Optional[Sequence[str]] = None,
    join_tolerance_mm: Optional[float] = None,
    rotation: Optional[np.ndarray] = None,
    scale: float = 1.0,
    corner_deg: float = defaults.CORNER_DEG,
    speed_mm_s: Optional[float] = None,
    tool_accel_mm_s2: Optional[float] = None,
) -> PartSegmentation:
    """Read, chain and fit a drawing within ``tolerance_mm``.

    ``layers`` selects layers (default: every visible one); ``join_tolerance_mm`` defaults
    to σ/100; the drawing is scaled by ``scale`` and turned by ``rotation`` (2 x 2) about
    its origin before it is chained and fitted; ``corner_deg`` is the corner rule inside
    free-form stretches (as for point curves). With ``speed_mm_s`` and ``tool_accel_mm_s2``
    (both or neither) fitted arcs are no tighter than v² / a where the drawing allows that
    speed, and each polysegment lists its speed-limited stretches (as segment_curve does).
    """
    if not (isinstance(tolerance_mm, (int, float)) and math.isfinite(tolerance_mm) and tolerance_mm > 0):
        raise InputError(f"tolerance_mm: must be a positive number of mm, got {tolerance_mm}", parameters=("tolerance_mm",))
    join = default_join_tolerance(tolerance_mm) if join_tolerance_mm is None else join_tolerance_mm
    if not (math.isfinite(corner_deg) and 0 < corner_deg < 180):
        raise InputError(f"corner_deg: must be between 0 and 180 degrees, got {corner_deg}", parameters=("corner_deg",))
    if not (math.isfinite(join) and 0 < join < tolerance_mm):
        raise InputError(f"join_tolerance_mm {join:g}: must be > 0 and below the tolerance {tolerance_mm:g} mm",
                         parameters=("join_tolerance_mm",))
    if (speed_mm_s is None) != (tool_accel_mm_s2 is None):
        raise InputError("speed_mm_s and tool_accel_mm_s2 go together: give both or neither",
                         parameters=("speed_mm_s", "tool_accel_mm_s2"))
    speed_kappa = curvature_limit(speed_mm_s, tool_accel_mm_s2)
    started = time.perf_counter()
    flatten_mm = FLATTEN_FRACTION * tolerance_mm / max(scale, 1e-300)
    drawing = read_drawing(path, layers, flatten_mm)
    pieces = drawing.pieces
    if rotation is not None or scale != 1.0:
        matrix = np.eye(2) if rotation is None else np.asarray(rotation, float)
        pieces = tuple(p.transformed(matrix, np.zeros(2), scale) for p in pieces)
    chaining = chain_pieces(pieces, join, drawing.source, near_mm=tolerance_mm)
    contours, skipped = [], []
    cache: dict = {}  # translated copies of a free-form stretch share one fit
    for contour in chaining.contours:
        t0 = time.perf_counter()
        # joins that moved the drawing leave the fit what remains of the tolerance
        fit_tol = tolerance_mm - contour.moved_mm
        try:
            fit = fit_contour(contour, fit_tol, FLATTEN_FRACTION * tolerance_mm, corner_deg, speed_kappa, cache)
        except CoatsimError as exc:
            skipped.append(f"{contour.name}: {exc}")
            continue
        poly = fit.polysegment
        if speed_mm_s is not None:
            poly = replace(poly, speed_limited=speed_limited(poly, speed_mm_s, tool_accel_mm_s2))
        name = f"{drawing.source} contour {len(contours) + 1} ({contour.name})"
        curve = Curve(_distinct(fit.points), contour.closed, name)
        contours.append(ContourSegmentation(curve, poly, "drawing", tolerance_mm, fit.deviation_mm + contour.moved_mm,
                                            time.perf_counter() - t0, theta_of_polyline(curve.points),
                                            speed_mm_s=speed_mm_s, tool_accel_mm_s2=tool_accel_mm_s2,
                                            n_pieces=len(contour.pieces), origin=contour.name))
    if not contours:
        raise InputError(f"{drawing.source}: no contour could be segmented ({skipped[0]})")
    notes = drawing.notes + chaining.notes
    if skipped:
        notes += (f"{len(skipped)} contours left out, the others segmented (first: {skipped[0]})",)
    return PartSegmentation(drawing.source, tuple(contours), drawing.units, tolerance_mm, join,
                            notes, time.perf_counter() - started)


def _distinct(points: np.ndarray) -> np.ndarray:
    """Samples without consecutive repeats (a Curve's invariant)."""
    keep = np.ones(len(points), dtype=bool)
    keep[1:] = np.any(np.diff(points, axis=0) != 0.0, axis=1)
    return points[keep]
