"""The one set of 3-D path primitives: ``Line3`` and ``Arc3`` (mm, radians).

An arc is built in a plane and then placed (as ezdxf does): ``place(planar_segment, pose)``
maps a planar ``Line``/``Arc`` of coatsim.geometry.primitives, drawn in the XY plane of a
frame, into space. ``arc_through`` gives the arc of a three-point move (C1MOVE/C2MOVE,
MoveC, CIRC); ``arc_from_tangent`` and ``arc_from_corner`` the arcs a G1 chain is made of.

``Arc3.sweep`` is positive (more than 2π where a chain loops): the arc turns counter-clockwise about its unit
``normal`` (right-handed), so a planar clockwise arc is placed with the frame's −z as normal.
Points on an arc are computed as offsets from the start (never ``centre + r·...``), so arcs
of huge radius keep their precision.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar, Union

import numpy as np

from coatsim.geometry.primitives import Arc, Line
from coatsim.geometry.space.pose import Pose

# Three points define a circle only if they are distinct and not collinear; these limits
# are far below the 1e-4 mm a written pose carries (the interpreter's choice, kept).
MIN_POINT_GAP_MM = 1e-6
MIN_SIN_ANGLE = 1e-10
UNIT_TOL = 1e-9  # a normal this far from unit length is refused


class DegenerateArc(ValueError):
    """The given points or tangent do not define a circular arc."""


def _vec(p) -> np.ndarray:
    out = np.array(p, dtype=float).reshape(3)
    out.flags.writeable = False
    return out


def _points_in(points: np.ndarray) -> tuple[np.ndarray, bool]:
    p = np.asarray(points, dtype=float)
    return p.reshape(-1, 3), p.ndim == 1


def rotate_about(vectors: np.ndarray, axis: np.ndarray, angles: np.ndarray) -> np.ndarray:
    """Displacements (n, 3) of the tip of ``vectors`` (3,) when turned about the unit ``axis``
    by each of ``angles`` (n,) (Rodrigues, written as offsets: sin·(a×v) + versine·a×(a×v))."""
    angles = np.asarray(angles, dtype=float)
    s, versine = np.sin(angles)[:, None], (2.0 * np.sin(angles / 2.0) ** 2)[:, None]
    axv = np.cross(axis, vectors)
    return s * axv + versine * np.cross(axis, axv)


@dataclass(frozen=True, eq=False)
class Line3:
    """Straight segment from ``start`` to ``end`` (mm)."""

    start: np.ndarray
    end: np.ndarray
    kind: ClassVar[str] = "line"

    def __post_init__(self) -> None:
        object.__setattr__(self, "start", _vec(self.start))
        object.__setattr__(self, "end", _vec(self.end))

    @property
    def length(self) -> float:
        return float(np.linalg.norm(self.end - self.start))

    @property
    def curvature(self) -> float:
        return 0.0

    @property
    def direction(self) -> np.ndarray:
        """Unit direction (zero for a zero-length line)."""
        d = self.end - self.start
        n = float(np.linalg.norm(d))
        return d / n if n > 0 else np.zeros(3)

    @property
    def start_tangent(self) -> np.ndarray:
        return self.direction

    @property
    def end_tangent(self) -> np.ndarray:
        return self.direction

    @property
    def via(self) -> np.ndarray:
        """The midpoint."""
        return (self.start + self.end) / 2

    def points(self, s: np.ndarray) -> np.ndarray:
        """Points (n, 3) at arc lengths ``s`` (n,) from the start."""
        s = np.atleast_1d(np.asarray(s, dtype=float))
        return self.start + s[:, None] * self.direction

    def tangents(self, s: np.ndarray) -> np.ndarray:
        """Unit tangents (n, 3) at arc lengths ``s``."""
        return np.tile(self.direction, (len(np.atleast_1d(s)), 1))

    def nearest(self, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Exact distance (n,) from points (n, 3) to the segment and the arc length (n,) of
        the nearest point on it."""
        p, _ = _points_in(points)
        length = self.length
        if length == 0.0:
            return np.linalg.norm(p - self.start, axis=1), np.zeros(len(p))
        s = np.clip((p - self.start) @ self.direction, 0.0, length)
        return np.linalg.norm(p - self.start - s[:, None] * self.direction, axis=1), s

    def distance(self, points: np.ndarray) -> np.ndarray | float:
        """Exact distance from a point (3,) or points (n, 3) to the segment."""
        p, single = _points_in(points)
        d = self.nearest(p)[0]
        return float(d[0]) if single else d

    def transformed(self, pose: Pose) -> Line3:
        return Line3(pose.apply(self.start), pose.apply(self.end))

    def reversed(self) -> Line3:
        return Line3(self.end, self.start)

    def halves(self) -> tuple[Line3, Line3]:
        """The line split at its middle: the same path, one more point to give a pose at."""
        return Line3(self.start, self.via), Line3(self.via, self.end)


@dataclass(frozen=True, eq=False)
class Arc3:
    """Circular arc from ``start`` turning ``sweep`` rad (> 0; more than a full turn where a
    chain loops) counter-clockwise about the unit ``normal`` around ``center``; ``end`` is where
    it arrives."""

    start: np.ndarray
    end: np.ndarray
    center: np.ndarray
    normal: np.ndarray
    radius: float
    sweep: float
    kind: ClassVar[str] = "arc"

    def __post_init__(self) -> None:
        for name in ("start", "end", "center", "normal"):
            object.__setattr__(self, name, _vec(getattr(self, name)))
        if abs(float(np.linalg.norm(self.normal)) - 1.0) > UNIT_TOL:
            raise ValueError("an arc's normal must be a unit vector")
        if not (self.radius > 0 and math.isfinite(self.radius) and 0 < self.sweep and math.isfinite(self.sweep)):
            raise ValueError(f"an arc needs radius > 0 and a finite sweep > 0, got r={self.radius}, sweep={self.sweep}")
        object.__setattr__(self, "radius", float(self.radius))
        object.__setattr__(self, "sweep", float(self.sweep))

    @property
    def length(self) -> float:
        return self.radius * self.sweep

    @property
    def curvature(self) -> float:
        return 1.0 / self.radius

    @property
    def radial(self) -> np.ndarray:
        """start − center."""
        return self.start - self.center

    @property
    def start_tangent(self) -> np.ndarray:
        return np.cross(self.normal, self.radial) / self.radius

    @property
    def end_tangent(self) -> np.ndarray:
        return self.tangents(np.array([self.length]))[0]

    @property
    def via(self) -> np.ndarray:
        """The point halfway along the arc (a C1MOVE's via point)."""
        return self.points(np.array([self.length / 2]))[0]

    def points(self, s: np.ndarray) -> np.ndarray:
        """Points (n, 3) at arc lengths ``s`` (n,) from the start."""
        return self.at_angles(np.atleast_1d(np.asarray(s, dtype=float)) / self.radius)

    def at_angles(self, angles: np.ndarray) -> np.ndarray:
        """Points (n, 3) turned by ``angles`` (n,) rad from the start about the normal (written
        as offsets from the start, so huge radii keep their precision)."""
        return self.start + rotate_about(self.radial, self.normal, np.atleast_1d(np.asarray(angles, dtype=float)))

    def tangents(self, s: np.ndarray) -> np.ndarray:
        """Unit tangents (n, 3) at arc lengths ``s``."""
        return self.tangents_at_angles(np.atleast_1d(np.asarray(s, dtype=float)) / self.radius)

    def tangents_at_angles(self, angles: np.ndarray) -> np.ndarray:
        """Unit tangents (n, 3) turned by ``angles`` (n,) rad from the start."""
        radial = self.radial + rotate_about(self.radial, self.normal, np.atleast_1d(np.asarray(angles, dtype=float)))
        return np.cross(self.normal, radial) / self.radius

    def nearest(self, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Exact distance (n,) from points (n, 3) to the arc and the arc length (n,) of the
        nearest point: project onto the arc's plane, take the nearest point of the circle,
        keep it if it lies within the sweep, else the nearer end. (A point on the axis is
        equally far from the whole circle; its nearest point is reported as the start.)"""
        p, _ = _points_in(points)
        rel = p - self.center
        u = self.radial / self.radius
        v = np.cross(self.normal, u)
        phi = np.mod(np.arctan2(rel @ v, rel @ u), 2 * math.pi)
        inside = phi <= self.sweep
        height = rel @ self.normal
        in_plane = np.hypot(rel @ u, rel @ v)
        d_circle = np.hypot(height, in_plane - self.radius)
        d_start = np.linalg.norm(p - self.start, axis=1)
        d_end = np.linalg.norm(p - self.end, axis=1)
        end_nearer = d_end < d_start
        d = np.where(inside, d_circle, np.where(end_nearer, d_end, d_start))
        s = np.where(inside, phi * self.radius, np.where(end_nearer, self.length, 0.0))
        return d, s

    def distance(self, points: np.ndarray) -> np.ndarray | float:
        """Exact distance from a point (3,) or points (n, 3) to the arc."""
        p, single = _points_in(points)
        d = self.nearest(p)[0]
        return float(d[0]) if single else d

    def transformed(self, pose: Pose) -> Arc3:
        return Arc3(pose.apply(self.start), pose.apply(self.end), pose.apply(self.center),
                    pose.apply_vectors(self.normal), self.radius, self.sweep)

    def reversed(self) -> Arc3:
        return Arc3(self.end, self.start, self.center, -self.normal, self.radius, self.sweep)

    def halves(self) -> tuple[Arc3, Arc3]:
        """The arc split at its middle into two arcs of its circle: the same path and tangents."""
        mid, half = self.via, self.sweep / 2
        return (Arc3(self.start, mid, self.center, self.normal, self.radius, half),
                Arc3(mid, self.end, self.center, self.normal, self.radius, half))


Segment3 = Union[Line3, Arc3]


def place(segment: Line | Arc, pose: Pose) -> Segment3:
    """A planar segment drawn in the XY plane of the frame ``pose`` (its pose in the parent
    frame), placed in the parent frame: "build in a plane, then place it"."""
    lift = lambda p: pose.apply(np.array([p[0], p[1], 0.0]))  # noqa: E731
    if isinstance(segment, Line):
        return Line3(lift(segment.start), lift(segment.end))
    normal = pose.rotation[:, 2] * math.copysign(1.0, segment.sweep)
    return Arc3(lift(segment.start), lift(segment.end), lift(segment.center), normal, segment.radius, abs(segment.sweep))


def _arc_from(start: np.ndarray, tangent: np.ndarray, end: np.ndarray, sweep_hint: float | None = None) -> Arc3:
    """The arc leaving ``start`` along the unit ``tangent`` and arriving at ``end``."""
    chord = end - start
    c2 = float(chord @ chord)
    along = float(chord @ tangent)
    normal = np.cross(tangent, chord)
    sin_len = float(np.linalg.norm(normal))
    if c2 < MIN_POINT_GAP_MM**2:
        raise DegenerateArc("the arc's start and end points coincide")
    if not sin_len > MIN_SIN_ANGLE * math.sqrt(c2):
        raise DegenerateArc("the end point lies on the start tangent's line: no arc, a line")
    normal = normal / sin_len
    radius = c2 / (2.0 * sin_len)  # chord = 2 r sin(sweep/2), sin_len = |chord| sin(angle to tangent)
    centre = start + radius * np.cross(normal, tangent)
    half = math.atan2(sin_len, along)  # the angle between tangent and chord is half the sweep
    return Arc3(start, end, centre, normal, radius, 2.0 * half)


def arc_from_tangent(start: np.ndarray, tangent: np.ndarray, end: np.ndarray) -> Arc3:
    """The arc that leaves ``start`` along ``tangent`` (any length) and arrives at ``end``;
    DegenerateArc when ``end`` lies on the tangent's line (a line, not an arc)."""
    t = np.asarray(tangent, dtype=float)
    n = float(np.linalg.norm(t))
    if not n > 0:
        raise DegenerateArc("the start tangent is zero")
    return _arc_from(np.asarray(start, float), t / n, np.asarray(end, float))


def arc_from_corner(start: np.ndarray, corner: np.ndarray, end: np.ndarray) -> Arc3:
    """The arc tangent to start->corner at ``start`` and to corner->end at ``end`` (the two legs
    must be equally long: the arc's tangent triangle); DegenerateArc when the legs are collinear."""
    start, corner, end = (np.asarray(p, dtype=float) for p in (start, corner, end))
    return arc_from_tangent(start, corner - start, end)


def arc_through(start: np.ndarray, via: np.ndarray, end: np.ndarray) -> Arc3:
    """The arc from ``start`` through ``via`` to ``end`` (a three-point circular move);
    DegenerateArc if the points coincide or lie on one line."""
    p0, p1, p2 = (np.asarray(p, dtype=float).reshape(3) for p in (start, via, end))
    a, b = p0 - p2, p1 - p2
    gaps = (float(np.linalg.norm(a)), float(np.linalg.norm(b)), float(np.linalg.norm(p1 - p0)))
    if min(gaps) < MIN_POINT_GAP_MM:
        raise DegenerateArc("start, via and end points of the arc are not distinct")
    axb = np.cross(a, b)
    area = float(np.linalg.norm(axb))
    if not area > MIN_SIN_ANGLE * gaps[0] * gaps[1]:
        raise DegenerateArc("start, via and end points of the arc lie on one line")
    center = p2 + np.cross(float(a @ a) * b - float(b @ b) * a, axb) / (2.0 * area * area)
    normal = np.cross(p1 - p0, p2 - p1)
    normal = normal / np.linalg.norm(normal)
    u0, u2 = p0 - center, p2 - center
    radius = float(np.linalg.norm(u0))
    sweep = math.atan2(float(normal @ np.cross(u0, u2)), float(u0 @ u2))
    if sweep <= 0.0:
        sweep += 2.0 * math.pi
    return Arc3(p0, p2, center, normal, radius, sweep)
