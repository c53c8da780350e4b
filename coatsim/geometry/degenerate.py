"""Fits that have an obvious answer, and the guards every fitted chain passes.

A tolerance at least the curve's extent (the diagonal of its bounding box) is met by the
simplest chain there is: the line from the start to the end point of an open curve, or for a
closed one a circle through the start point, tangent to the first edge, turning the way the
curve does (as two half arcs for an open curve that ends where it starts). Every input
point is within the extent of the start point, and every point of these chains within the
extent of an input point, so both are within the tolerance.
"""

from __future__ import annotations

import math

import numpy as np

from coatsim.core.errors import InputError
from coatsim.geometry.deviation import hausdorff
from coatsim.geometry.polysegment import Polysegment
from coatsim.geometry.primitives import Arc, Line, Segment

LONGEST_SWEEP = 1.5 * math.pi  # arcs of a chain turning more are cut into equal parts (all within (-2π, 2π))
CIRCLE_SHARE = 0.1  # a closed chain of arcs whose centres and radii agree within this share of σ is one circle
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
    if closed:
        return full_circle(center, radius, heading + math.pi, turn, start)
    far = (2 * center[0] - start[0], 2 * center[1] - start[1])
    return Polysegment((Arc(start, far, center, radius, turn * math.pi), Arc(far, start, center, radius, turn * math.pi)))


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


def full_circle(center: tuple[float, float], radius: float, start_angle: float, turn: float,
                start: tuple[float, float] | None = None) -> Polysegment:
    """The closed chain of one arc turning a whole circle (``turn`` +1 counter-clockwise, -1
    clockwise) from the point at ``start_angle`` (rad) about ``center`` (``start`` if given:
    that point exactly)."""
    if start is None:
        start = (center[0] + radius * math.cos(start_angle), center[1] + radius * math.sin(start_angle))
    return Polysegment((Arc(start, start, center, radius, turn * 2 * math.pi),), closed=True)


def one_circle(points: np.ndarray, poly: Polysegment, tolerance: float) -> tuple[Polysegment, float] | None:
    """A closed chain of arcs of one circle (centres and radii within CIRCLE_SHARE σ, all
    turning one way, no corner) as that circle in one arc, with its verified deviation, if it
    keeps the points within ``tolerance``; else None. The fit splits long arcs and starts a loop at its seam, so a
    circle comes out as a few arcs of itself; the user asked for a circle."""
    segs = poly.segments
    if not poly.closed or poly.corners or len(segs) < 2 or not all(isinstance(s, Arc) for s in segs):
        return None
    centers = np.array([s.center for s in segs])
    radii = np.array([s.radius for s in segs])
    turns = {math.copysign(1.0, s.sweep) for s in segs}
    spread = max(float(np.ptp(centers, axis=0).max()), float(np.ptp(radii)))
    if len(turns) != 1 or spread > CIRCLE_SHARE * tolerance:
        return None
    weights = np.array([s.length for s in segs])
    center = tuple(float(v) for v in weights @ centers / weights.sum())
    first = segs[0]
    angle = math.atan2(first.start[1] - center[1], first.start[0] - center[0])
    circle = full_circle(center, float(weights @ radii / weights.sum()), angle, turns.pop())
    dev = hausdorff(points, circle).hausdorff
    return (circle, dev) if dev <= tolerance else None


def check_chain(poly: Polysegment, extent: float) -> None:
    """Raise InputError if a chain has an arc below the numerical floor of its size (centre
    and radius lost in round-off) or one turning more than a full circle."""
    floor = 1e-9 * max(extent, 1.0)
    for k, seg in enumerate(poly.segments):
        if isinstance(seg, Arc) and (seg.radius < floor or not abs(seg.sweep) <= 2 * math.pi * (1 + 1e-12)):
            raise InputError(f"the fit produced an unusable arc (segment {k}: radius {seg.radius:.3g} mm, sweep "
                             f"{seg.sweep:.3g} rad); try a smaller tolerance")
