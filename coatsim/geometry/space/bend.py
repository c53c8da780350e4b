"""A bend between two straight stretches as one arc tangent to both: a pipe's bend, a
programmed line–arc–line.

The two lines (coatsim.geometry.space.straight) end where the input leaves them, a little
into the bend, so an arc spline between them with both end tangents pinned needs two or
three arcs where the input has one. Where the lines lie in one plane (they meet within
COPLANAR_SHARE σ), the arc tangent to both whose radius fits the bend's input best (least
squares of the distances to its centre) stands for the bend, the line before ending at its first
tangent point and the line after leaving its last one for its own far end (so that each line's
direction is the arc's tangent exactly and the chain stays G1); it is taken where the lines and
the arc keep the input of the whole stretch within σ both ways, else None (the caller fits the
bend as a free arc spline). An arc tighter than the speed allows is listed as speed-limited, as
any arc the curve itself forces.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
from scipy.optimize import minimize_scalar

from coatsim.geometry.space.chain import SpaceChain
from coatsim.geometry.space.deviation import hausdorff3
from coatsim.geometry.space.primitives import Arc3, DegenerateArc, Line3, arc_from_tangent
from coatsim.geometry.space.straight import Straight

COPLANAR_SHARE = 0.1  # two lines this close (in σ) lie in one plane
MIN_TURN_RAD = 1e-3  # lines turning less than this meet in no useful point
MIN_POINTS = 3  # input points inside the bend that the radius is fitted to, at least


def bend_arc(before: Straight, after: Straight, points: np.ndarray, tol: float) -> tuple[Straight, Arc3, Straight] | None:
    """The two lines moved to the tangent points and the arc between them, or None (see the
    module text); ``points`` is the run the lines index."""
    u1, u2 = before.direction, after.direction
    normal = np.cross(u1, u2)
    sin_turn = float(np.linalg.norm(normal))
    turn = float(np.arctan2(sin_turn, u1 @ u2))
    inner = points[before.last + 1 : after.first]
    if turn < MIN_TURN_RAD or turn > np.pi - MIN_TURN_RAD or len(inner) < MIN_POINTS:
        return None
    normal /= sin_turn
    if abs(float((after.start - before.end) @ normal)) > COPLANAR_SHARE * tol:
        return None
    corner = _meeting(before.end, u1, after.start, u2)
    room = min(float((corner - before.start) @ u1), float((after.end - corner) @ u2))  # how far a tangent point may go
    if not room > 0:
        return None
    inward = u2 - (u2 @ u1) * u1
    inward /= np.linalg.norm(inward)
    half = np.tan(turn / 2)

    def centre(radius: float) -> np.ndarray:
        return corner - u1 * radius * half + inward * radius

    def misfit(radius: float) -> float:
        return float(np.square(np.linalg.norm(inner - centre(radius), axis=1) - radius).sum())

    radius = float(minimize_scalar(misfit, bounds=(1e-6 * room / half, room / half), method="bounded").x)
    t1 = before.start + u1 * float((corner - u1 * radius * half - before.start) @ u1)  # on the line before, exactly
    t2 = _tangent_point(t1, u1, radius, after.end)
    if t2 is None:
        return None
    try:
        arc = arc_from_tangent(t1, u1, t2)
    except DegenerateArc:
        return None
    first, second = replace(before, end=t1), replace(after, start=t2)
    v2 = second.direction
    # the stretch from the first input point of the line before to the last of the line after,
    # against the lines from those points' feet to the tangent points and the arc
    q1 = t1 - u1 * float((t1 - points[before.first]) @ u1)
    q2 = t2 + v2 * float((points[after.last] - t2) @ v2)
    if not ((t1 - q1) @ u1 > 0 and (q2 - t2) @ v2 > 0 and (t1 - before.start) @ u1 > 0):
        return None  # the arc would take a whole line
    local = SpaceChain((Line3(q1, t1), arc, Line3(t2, q2)))
    if hausdorff3(points[before.first : after.last + 1], local, tol).hausdorff > tol:
        return None
    return first, arc, second


def _tangent_point(t1: np.ndarray, u1: np.ndarray, radius: float, end: np.ndarray) -> np.ndarray | None:
    """Where the circle of ``radius`` tangent to ``u1`` at ``t1``, turning towards ``end``, has
    a tangent through ``end`` that leaves it forwards (the line after the arc then points at
    ``end`` exactly: the line after keeps its far end, so the chain stays G1 and joined)."""
    off = (end - t1) - ((end - t1) @ u1) * u1
    if not np.linalg.norm(off) > 0:
        return None
    m = off / np.linalg.norm(off)
    centre, normal = t1 + radius * m, np.cross(u1, m)
    w = end - centre
    dist = float(np.linalg.norm(w))
    if not dist > radius:
        return None
    a = w / dist
    b = np.cross(normal, a)
    alpha = float(np.arccos(radius / dist))
    for sign in (1.0, -1.0):
        radial = np.cos(alpha) * a + sign * np.sin(alpha) * b
        if (end - (centre + radius * radial)) @ np.cross(normal, radial) > 0:
            return centre + radius * radial
    return None


def _meeting(p1: np.ndarray, u1: np.ndarray, p2: np.ndarray, u2: np.ndarray) -> np.ndarray:
    """The middle of the closest points of two lines (p + t u) that are not parallel."""
    w = p1 - p2
    b, d, e = u1 @ u2, u1 @ w, u2 @ w
    den = 1.0 - b * b
    t1, t2 = (b * e - d) / den, (e - b * d) / den
    return (p1 + t1 * u1 + p2 + t2 * u2) / 2
