"""Polysegment primitives: straight lines and circular arcs in the plane (mm, radians).

A polysegment is a chain of lines and arcs; consecutive segments share end points exactly.
Headings are angles of the unit tangent, measured counter-clockwise from +x.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar, Union

import numpy as np

Point = tuple[float, float]


def _unit(angle: float) -> np.ndarray:
    return np.array([math.cos(angle), math.sin(angle)])


@dataclass(frozen=True)
class Line:
    """Straight segment from ``start`` to ``end``."""

    start: Point
    end: Point
    kind: ClassVar[str] = "line"

    @property
    def length(self) -> float:
        return math.hypot(self.end[0] - self.start[0], self.end[1] - self.start[1])

    @property
    def curvature(self) -> float:
        return 0.0

    @property
    def start_heading(self) -> float:
        return math.atan2(self.end[1] - self.start[1], self.end[0] - self.start[0])

    @property
    def end_heading(self) -> float:
        return self.start_heading

    def points(self, s: np.ndarray) -> np.ndarray:
        """Points at arc lengths ``s`` (n,) from the start, shape (n, 2)."""
        s = np.asarray(s, dtype=float)
        a, b = np.asarray(self.start), np.asarray(self.end)
        frac = s / self.length if self.length > 0 else np.zeros_like(s)
        return a + frac[:, None] * (b - a)

    def tangents(self, s: np.ndarray) -> np.ndarray:
        """Unit tangents at arc lengths ``s``, shape (n, 2)."""
        return np.tile(_unit(self.start_heading), (len(np.atleast_1d(s)), 1))

    def transformed(self, matrix: np.ndarray, offset: np.ndarray, scale: float) -> Line:
        """Image under p -> scale * matrix @ p + offset (matrix a rotation)."""
        f = lambda p: tuple(float(v) for v in scale * matrix @ np.asarray(p) + offset)  # noqa: E731
        return Line(f(self.start), f(self.end))

    def reversed(self) -> Line:
        return Line(self.end, self.start)


@dataclass(frozen=True)
class Arc:
    """Circular arc; ``sweep`` is signed (positive = counter-clockwise)."""

    start: Point
    end: Point
    center: Point
    radius: float
    sweep: float
    kind: ClassVar[str] = "arc"

    @property
    def length(self) -> float:
        return self.radius * abs(self.sweep)

    @property
    def curvature(self) -> float:
        return math.copysign(1.0 / self.radius, self.sweep)

    @property
    def start_angle(self) -> float:
        """Polar angle of ``start`` about ``center``."""
        return math.atan2(self.start[1] - self.center[1], self.start[0] - self.center[0])

    @property
    def start_heading(self) -> float:
        return self.start_angle + math.copysign(math.pi / 2, self.sweep)

    @property
    def end_heading(self) -> float:
        return self.start_heading + self.sweep

    def points(self, s: np.ndarray) -> np.ndarray:
        """Points at arc lengths ``s`` from the start, from the chord (length · sinc of half
        the turn), which stays exact for nearly straight arcs of huge radius."""
        s = np.asarray(s, dtype=float)
        half = np.sign(self.sweep) * s / (2 * self.radius)
        chord = s * np.sinc(half / math.pi)
        heading = self.start_heading + half
        return np.asarray(self.start) + chord[:, None] * np.column_stack((np.cos(heading), np.sin(heading)))

    def tangents(self, s: np.ndarray) -> np.ndarray:
        s = np.asarray(s, dtype=float)
        h = self.start_heading + np.sign(self.sweep) * s / self.radius
        return np.column_stack((np.cos(h), np.sin(h)))

    def transformed(self, matrix: np.ndarray, offset: np.ndarray, scale: float) -> Arc:
        """Image under p -> scale * matrix @ p + offset; a reflection flips the sweep."""
        f = lambda p: tuple(float(v) for v in scale * matrix @ np.asarray(p) + offset)  # noqa: E731
        sign = 1.0 if np.linalg.det(matrix) > 0 else -1.0
        return Arc(f(self.start), f(self.end), f(self.center), scale * self.radius, sign * self.sweep)

    def reversed(self) -> Arc:
        return Arc(self.end, self.start, self.center, self.radius, -self.sweep)


Segment = Union[Line, Arc]


def make_segment(start: Point, heading: float, curvature: float, length: float) -> Segment:
    """The line or arc that leaves ``start`` at ``heading`` with ``curvature`` for ``length``.

    A turn below 1e-12 rad over the length gives a line (no arc is measurably different);
    otherwise the arc's centre lies on the left normal for positive curvature. The end point
    comes from the chord (length · sinc), which stays accurate for nearly straight arcs.
    """
    p = np.asarray(start, dtype=float)
    sweep = curvature * length
    if abs(sweep) < 1e-12:
        end = p + length * _unit(heading)
        return Line(tuple(map(float, p)), (float(end[0]), float(end[1])))
    radius = 1.0 / abs(curvature)
    center = p + radius * _unit(heading + math.copysign(math.pi / 2, curvature))
    end = p + length * math.sin(sweep / 2) / (sweep / 2) * _unit(heading + sweep / 2)
    return Arc(
        tuple(map(float, p)),
        (float(end[0]), float(end[1])),
        (float(center[0]), float(center[1])),
        radius,
        sweep,
    )


def snap_end(segments: tuple[Segment, ...], end: Point) -> tuple[Segment, ...]:
    """The chain with its last end point set exactly to ``end`` (a round-off correction:
    callers only pass points the chain already ends at within a tiny distance)."""
    last = segments[-1]
    tip = (float(end[0]), float(end[1]))
    if isinstance(last, Arc):
        moved = Arc(last.start, tip, last.center, last.radius, last.sweep)
    else:
        moved = Line(last.start, tip)
    return segments[:-1] + (moved,)
