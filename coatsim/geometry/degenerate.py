"""Fits that have an obvious answer, and the guards every fitted chain passes.

A tolerance at least the curve's extent (the diagonal of its bounding box) is met by the
simplest chain there is: the line from the start to the end point of an open curve, or for a
closed one (or an open one that ends where it starts) a circle through the start point,
tangent to the first edge, turning the way the curve does, as two half arcs. Every input
point is within the extent of the start point, and every point of these chains within the
extent of an input point, so both are within the tolerance.
"""

from __future__ import annotations

import math

import numpy as np

from coatsim.core.errors import InputError
from coatsim.geometry.polysegment import Polysegment
from coatsim.geometry.primitives import Arc, Line, Segment

LONGEST_SWEEP = 1.5 * math.pi  # arcs turning more are cut into equal parts (all within (-2π, 2π))
RESOLVED = 1e-11  # the finest tolerance, relative to the coordinates (float64 resolves 2.2e-16 of them;
#                   arc centres, sincs and running sums of lengths lose the rest)


def extent_mm(points: np.ndarray) -> float:
    """Diagonal of the points' bounding box (mm)."""
    return float(np.linalg.norm(np.ptp(points, axis=0)))


def check_resolvable(points: np.ndarray, tolerance: float) -> None:
    """Raise InputError if ``tolerance`` is finer than float64 arithmetic can resolve at
    the points' coordinates (the fit could not be verified, only fail after a long search)."""
    pts = np.asarray(points, dtype=float)
    scale = max(float(np.abs(pts).max()), extent_mm(pts))
    floor = RESOLVED * scale
    if tolerance < floor:
        raise InputError(f"tolerance_mm {tolerance:g} is below what float64 resolves at these coordinates "
                         f"(up to {scale:.3g} mm from the origin or across): give at least {floor:.3g} mm",
                         parameters=("tolerance_mm",))


def obvious_answer(points: np.ndarray, closed: bool, tolerance: float) -> Polysegment | None:
    """The one-line or one-circle chain when ``tolerance`` is at least the curve's extent,
    else None."""
    pts = np.asarray(points, dtype=float)
    extent = extent_mm(pts)
    if tolerance < extent:
        return None
    start, end = (float(pts[0][0]), float(pts[0][1])), (float(pts[-1][0]), float(pts[-1][1]))
    if not closed and math.dist(start, end) > 1e-9 * extent:
        return Polysegment((Line(start, end),))
    edges = np.diff(pts, axis=0)
    length = float(np.linalg.norm(edges, axis=1).sum())
    radius = min(extent / 2, length / (2 * math.pi))
    area = float(np.sum(pts[:-1, 0] * pts[1:, 1] - pts[1:, 0] * pts[:-1, 1]))
    turn = 1.0 if area >= 0 else -1.0  # counter-clockwise: the centre on the left of the first edge
    heading = math.atan2(edges[0][1], edges[0][0]) + turn * math.pi / 2
    center = (start[0] + radius * math.cos(heading), start[1] + radius * math.sin(heading))
    far = (2 * center[0] - start[0], 2 * center[1] - start[1])
    arcs = (Arc(start, far, center, radius, turn * math.pi), Arc(far, start, center, radius, turn * math.pi))
    return Polysegment(arcs, closed=closed)


def split_long_arcs(segments: tuple[Segment, ...]) -> tuple[Segment, ...]:
    """The chain with every arc turning more than LONGEST_SWEEP cut into equal arcs."""
    out: list[Segment] = []
    for seg in segments:
        if not isinstance(seg, Arc) or abs(seg.sweep) <= LONGEST_SWEEP:
            out.append(seg)
            continue
        parts = math.ceil(abs(seg.sweep) / LONGEST_SWEEP)
        step = seg.sweep / parts
        a0 = seg.start_angle
        point = seg.start
        for i in range(1, parts + 1):
            angle = a0 + step * i
            nxt = seg.end if i == parts else (seg.center[0] + seg.radius * math.cos(angle),
                                               seg.center[1] + seg.radius * math.sin(angle))
            out.append(Arc(point, nxt, seg.center, seg.radius, step))
            point = nxt
    return tuple(out)


def check_chain(poly: Polysegment, extent: float) -> None:
    """Raise InputError if a chain has an arc below the numerical floor of its size (centre
    and radius lost in round-off) or one turning a full circle or more."""
    floor = 1e-9 * max(extent, 1.0)
    for k, seg in enumerate(poly.segments):
        if isinstance(seg, Arc) and (seg.radius < floor or not abs(seg.sweep) < 2 * math.pi):
            raise InputError(f"the fit produced an unusable arc (segment {k}: radius {seg.radius:.3g} mm, sweep "
                             f"{seg.sweep:.3g} rad); try a smaller tolerance")
