"""Where a closed loop without corners is fitted from, and where its chain then starts.

A closed chain is fitted from a calm point of the loop (its flattest stretch), where closing
the chain tangentially is easy, and then started again at the point nearest the input's first
point: the segment there is cut in two, so the program's seam lies inside an arc, with no
turn and no curvature jump at all (or at the junction next to it, if the cut would leave a
piece shorter than the minimum segment length).
"""

from __future__ import annotations

import math

import numpy as np

from coatsim.geometry.deviation import distance_to_polysegment
from coatsim.geometry.envelope import curvature_profile
from coatsim.geometry.polysegment import Polysegment
from coatsim.geometry.primitives import Arc, Line, Segment

CALM_SHARE = 0.05  # the flattest stretch is judged over this share of the loop's length


def calm_start(points: np.ndarray) -> int:
    """Index of the vertex of a closed loop (last point = first) where the input is flattest
    over a stretch around it (its curvature at the input's own resolution, not the
    tolerance's: a large tolerance smooths a tight dip into a flat one)."""
    profile = curvature_profile(points, True, 0.0)
    envelope = profile.envelope(CALM_SHARE * profile.length)
    s = np.concatenate(([0.0], np.cumsum(np.linalg.norm(np.diff(points, axis=0), axis=1))))[:-1]
    return int(np.argmin(profile.at(envelope, s)))


def rotated_loop(points: np.ndarray, first: int) -> np.ndarray:
    """The closed loop's points starting (and ending) at vertex ``first``."""
    body = points[:-1]
    return np.vstack((body[first:], body[:first], body[first:first + 1]))


def _cut(seg: Segment, at: float) -> tuple[Segment, Segment]:
    """The segment as two pieces meeting ``at`` mm from its start (same circle or line)."""
    point = tuple(float(v) for v in seg.points(np.array([at]))[0])
    if isinstance(seg, Line):
        return Line(seg.start, point), Line(point, seg.end)
    sign = math.copysign(1.0, seg.sweep)
    return (Arc(seg.start, point, seg.center, seg.radius, sign * at / seg.radius),
            Arc(point, seg.end, seg.center, seg.radius, seg.sweep - sign * at / seg.radius))


def _along(seg: Segment, foot: np.ndarray) -> float:
    """Arc length from the segment's start to ``foot``, a point on it."""
    if isinstance(seg, Line):
        return float(np.linalg.norm(foot - np.asarray(seg.start)))
    angle = math.atan2(foot[1] - seg.center[1], foot[0] - seg.center[0])
    turned = (math.copysign(1.0, seg.sweep) * (angle - seg.start_angle)) % (2 * math.pi)
    return min(turned, abs(seg.sweep)) * seg.radius


def reseat(segments: tuple[Segment, ...], point: np.ndarray, min_length: float) -> tuple[Segment, ...]:
    """The closed chain started at the point of it nearest ``point``."""
    poly = Polysegment(segments, closed=True)
    _, index, foot = distance_to_polysegment(np.asarray(point, float)[None], poly)
    j = int(index[0])
    seg = segments[j]
    along = _along(seg, foot[0])
    if along < min_length or seg.length - along < min_length:
        first = j if along < seg.length - along else (j + 1) % len(segments)
        return segments[first:] + segments[:first]
    head, tail = _cut(seg, along)
    return (tail,) + segments[j + 1:] + segments[:j] + (head,)
