"""Drawn primitives in the workpiece plane (mm): native lines and arcs, and free-form pieces.

A *native* piece is a line or circular arc of the drawing, kept exactly. A *free-form* piece
(spline, ellipse, Bézier, elliptical arc) is a dense polyline within a flattening distance of
the drawn curve, with the drawn curve's exact end tangents (from its derivatives), so a join
with a neighbour can be judged tangent or not. Every piece names the entity it came from,
and a piece of a drawn path (a polyline, an SVG path) names that path too: where more than two
ends meet, a path's own pieces are followed in the order it was drawn.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Callable, Union

import numpy as np

from coatsim.geometry.primitives import Arc, Line, Point, Segment

NATIVE_MIN_FLATTENINGS = 100  # free-form pieces shorter than this stay free-form (5 σ at the default flattening)
_ROUND_OFF = 1e-9  # relative: end moves this small are round-off, not geometry


def _xy(p: np.ndarray | Point) -> Point:
    return (float(p[0]), float(p[1]))


def heading_of(vector: np.ndarray) -> float:
    return math.atan2(float(vector[1]), float(vector[0]))


@dataclass(frozen=True, eq=False)
class NativePiece:
    """A line or arc of the drawing, exactly; ``path`` names the drawn path it is part of
    ("" for an entity of its own)."""

    segment: Segment
    source: str
    path: str = ""

    @property
    def start(self) -> Point:
        return self.segment.start

    @property
    def end(self) -> Point:
        return self.segment.end

    @property
    def start_heading(self) -> float:
        return self.segment.start_heading

    @property
    def end_heading(self) -> float:
        return self.segment.end_heading

    @property
    def length(self) -> float:
        return self.segment.length

    def midpoint(self) -> np.ndarray:
        return self.segment.points(np.array([self.length / 2]))[0]

    def reversed(self) -> NativePiece:
        return replace(self, segment=self.segment.reversed())

    def transformed(self, matrix: np.ndarray, offset: np.ndarray, scale: float) -> NativePiece:
        return replace(self, segment=self.segment.transformed(np.asarray(matrix, float), np.asarray(offset, float),
                                                              scale))

    def with_ends(self, start: Point, end: Point) -> NativePiece:
        """The piece moved to end exactly at ``start`` and ``end`` (each at most the join
        tolerance away); an arc keeps its radius and sense and gets the centre that fits."""
        seg = self.segment
        if isinstance(seg, Line):
            return replace(self, segment=Line(_xy(start), _xy(end)))
        return replace(self, segment=refit_arc(seg, start, end))

    def samples(self, flatten_mm: float) -> np.ndarray:
        """Points (n, 2) from start to end, chords within ``flatten_mm`` of the piece."""
        seg = self.segment
        if isinstance(seg, Line):
            return np.array([seg.start, seg.end], dtype=float)
        step = 2.0 * math.sqrt(max(flatten_mm * (2.0 * seg.radius - flatten_mm), 1e-300)) if flatten_mm < seg.radius else seg.radius
        n = max(2, int(math.ceil(seg.length / step)), int(math.ceil(abs(seg.sweep) / (math.pi / 8))))
        pts = seg.points(np.linspace(0.0, seg.length, n + 1))
        pts[0], pts[-1] = seg.start, seg.end
        return pts


def refit_arc(arc: Arc, start: Point, end: Point) -> Arc:
    """The arc of ``arc``'s sense from ``start`` to ``end`` (ends moved by round-off or within
    the join tolerance, or a near miss closed) that moves least: of its radius (its centre on
    the side of the old one) or of its sweep (a half circle whose end moves along its chord
    keeps its shape), the one whose centre and radius change least."""
    scale = max(1.0, arc.radius)
    if math.dist(start, arc.start) <= _ROUND_OFF * scale and math.dist(end, arc.end) <= _ROUND_OFF * scale:
        return Arc(_xy(start), _xy(end), arc.center, arc.radius, arc.sweep)
    a, b = np.asarray(start, float), np.asarray(end, float)
    chord = b - a
    d = float(np.linalg.norm(chord))
    if d <= _ROUND_OFF * scale:  # a full circle: move it with its start point
        shift = a - np.asarray(arc.start, float)
        return Arc(_xy(a), _xy(a), _xy(np.asarray(arc.center) + shift), arc.radius, arc.sweep)
    mid = (a + b) / 2
    normal = np.array([-chord[1], chord[0]]) / d
    side = 1.0 if float(np.dot(np.asarray(arc.center) - mid, normal)) >= 0 else -1.0
    candidates = [max(arc.radius, d / 2)]
    if 1e-6 < abs(arc.sweep) < 2 * math.pi - 1e-6:
        candidates.append(d / (2 * abs(math.sin(arc.sweep / 2))))
    best = None
    for radius in candidates:
        center = mid + side * math.sqrt(max(radius * radius - d * d / 4, 0.0)) * normal
        change = math.dist(center, arc.center) + abs(radius - arc.radius)
        if best is None or change < best[0]:
            best = (change, center, radius)
    _, center, radius = best
    turn = math.atan2(b[1] - center[1], b[0] - center[0]) - math.atan2(a[1] - center[1], a[0] - center[0])
    turn += 2 * math.pi * round((arc.sweep - turn) / (2 * math.pi))  # the sweep nearest the old one
    return Arc(_xy(a), _xy(b), _xy(center), radius, turn)


@dataclass(frozen=True, eq=False)
class FreePiece:
    """A free-form curve: ``points`` (n, 2) within the flattening distance of it, start and
    end exactly on it, and its exact end headings (rad); ``path`` as for a native piece."""

    points: np.ndarray
    start_heading: float
    end_heading: float
    source: str
    path: str = ""

    @property
    def start(self) -> Point:
        return _xy(self.points[0])

    @property
    def end(self) -> Point:
        return _xy(self.points[-1])

    @property
    def length(self) -> float:
        return float(np.linalg.norm(np.diff(self.points, axis=0), axis=1).sum())

    def midpoint(self) -> np.ndarray:
        cum = np.concatenate(([0.0], np.cumsum(np.linalg.norm(np.diff(self.points, axis=0), axis=1))))
        half = cum[-1] / 2
        k = int(np.clip(np.searchsorted(cum, half), 1, len(cum) - 1))
        u = (half - cum[k - 1]) / max(cum[k] - cum[k - 1], 1e-300)
        return self.points[k - 1] + u * (self.points[k] - self.points[k - 1])

    def reversed(self) -> FreePiece:
        return replace(self, points=self.points[::-1].copy(), start_heading=self.end_heading + math.pi,
                       end_heading=self.start_heading + math.pi)

    def transformed(self, matrix: np.ndarray, offset: np.ndarray, scale: float) -> FreePiece:
        m = np.asarray(matrix, float)
        pts = scale * self.points @ m.T + np.asarray(offset, float)
        turn = lambda h: heading_of(m @ np.array([math.cos(h), math.sin(h)]))  # noqa: E731
        return replace(self, points=pts, start_heading=turn(self.start_heading), end_heading=turn(self.end_heading))

    def with_ends(self, start: Point, end: Point) -> FreePiece:
        pts = self.points.copy()
        pts[0], pts[-1] = start, end
        return replace(self, points=pts)

    def samples(self, flatten_mm: float) -> np.ndarray:
        return self.points


Piece = Union[NativePiece, FreePiece]


def line_piece(start: np.ndarray, end: np.ndarray, source: str, path: str = "") -> NativePiece:
    return NativePiece(Line(_xy(start), _xy(end)), source, path)


def arc_piece(center: np.ndarray, radius: float, start: np.ndarray, end: np.ndarray, sweep: float,
              source: str, path: str = "") -> NativePiece:
    """A circular arc from its centre, radius, end points and signed sweep (rad)."""
    return NativePiece(Arc(_xy(start), _xy(end), _xy(center), float(radius), float(sweep)), source, path)


def flatten(point_at: Callable[[np.ndarray], np.ndarray], flatten_mm: float, min_pieces: int = 8,
            max_points: int = 200_000) -> np.ndarray:
    """Samples (n, 2) of a parametric curve on [0, 1] whose chords stay within ``flatten_mm``.

    ``point_at`` maps parameters (m,) to points (m, 2). Starts from ``min_pieces`` equal
    intervals and halves every interval whose middle (and quarter points) lie farther than
    ``flatten_mm`` from its chord.
    """
    t = np.linspace(0.0, 1.0, min_pieces + 1)
    for _ in range(40):
        a, b = t[:-1], t[1:]
        probe = np.concatenate((a + (b - a) / 4, (a + b) / 2, a + 3 * (b - a) / 4))
        pa, pb, pp = point_at(a), point_at(b), point_at(probe).reshape(3, len(a), 2)
        chord = pb - pa
        norm = np.linalg.norm(chord, axis=1)
        rel = pp - pa
        off = np.where(norm > 0, np.abs(rel[..., 0] * chord[:, 1] - rel[..., 1] * chord[:, 0]) / np.maximum(norm, 1e-300),
                       np.linalg.norm(rel, axis=2))
        bad = off.max(axis=0) > flatten_mm
        if not bad.any() or len(t) > max_points:
            break
        t = np.sort(np.concatenate((t, ((a + b) / 2)[bad])))
    return point_at(t)


def tangent_heading(point_at: Callable[[np.ndarray], np.ndarray], at_end: bool) -> float:
    """Heading of the tangent at t = 0 (or 1) of a parametric curve, by a short forward (or
    backward) difference that also finds the direction where the derivative vanishes."""
    for eps in (1e-7, 1e-5, 1e-3):
        t = np.array([1.0 - eps, 1.0]) if at_end else np.array([0.0, eps])
        p = point_at(t)
        d = p[1] - p[0]
        if np.linalg.norm(d) > 1e-12 * max(1.0, float(np.abs(p).max())):
            return heading_of(d)
    p = point_at(np.array([0.0, 1.0]))
    return heading_of(p[1] - p[0])


def free_or_native(point_at: Callable[[np.ndarray], np.ndarray], flatten_mm: float, source: str,
                   path: str = "") -> Piece:
    """A parametric curve on [0, 1] as a free-form piece, or as the native line or arc it
    exactly is (a Bézier with its handles on the chord, a NURBS circle): every sample and
    every point half way between samples on that line or circle to round-off, running along
    it without turning back. A curve of low degree meeting a line or circle at that many
    points lies on it. Pieces shorter than ``NATIVE_MIN_FLATTENINGS`` flattening distances
    stay free-form, to be fitted with their neighbours rather than cut a stretch in two."""
    pts = flatten(point_at, flatten_mm)
    if float(np.linalg.norm(np.diff(pts, axis=0), axis=1).sum()) < NATIVE_MIN_FLATTENINGS * flatten_mm:
        return FreePiece(pts, tangent_heading(point_at, False), tangent_heading(point_at, True), source, path)
    t = np.linspace(0.0, 1.0, len(pts))  # not the samples' parameters: probes between and beyond them
    probe = np.vstack((pts, point_at(t), point_at((t[:-1] + t[1:]) / 2)))
    exact = _exact_line(pts, probe) or _exact_arc(pts, probe)
    if exact is not None:
        return NativePiece(exact, source, path)
    return FreePiece(pts, tangent_heading(point_at, False), tangent_heading(point_at, True), source, path)


def _exact_line(pts: np.ndarray, probe: np.ndarray) -> Line | None:
    a, b = pts[0], pts[-1]
    chord = b - a
    norm = float(np.linalg.norm(chord))
    scale = _ROUND_OFF * max(1.0, float(np.abs(probe).max()))
    if norm <= scale:
        return None
    along = (pts - a) @ chord / norm
    off = np.abs((probe - a) @ np.array([-chord[1], chord[0]])) / norm
    if off.max() > scale or np.diff(along).min() < -scale:
        return None
    return Line(_xy(a), _xy(b))


def _exact_arc(pts: np.ndarray, probe: np.ndarray) -> Arc | None:
    if len(pts) < 3:
        return None
    a, m, b = pts[0], pts[len(pts) // 2], pts[-1]
    d = 2.0 * ((m[0] - a[0]) * (b[1] - a[1]) - (m[1] - a[1]) * (b[0] - a[0]))
    if abs(d) <= 1e-300:
        return None
    am, ab = float(np.dot(m - a, m - a)), float(np.dot(b - a, b - a))
    ux = ((b[1] - a[1]) * am - (m[1] - a[1]) * ab) / d
    uy = ((m[0] - a[0]) * ab - (b[0] - a[0]) * am) / d
    center = a + np.array([ux, uy])
    radius = float(np.linalg.norm(a - center))
    scale = _ROUND_OFF * max(1.0, float(np.abs(probe).max()), radius)
    if np.abs(np.linalg.norm(probe - center, axis=1) - radius).max() > scale * 10:
        return None
    phi = np.unwrap(np.arctan2(pts[:, 1] - center[1], pts[:, 0] - center[0]))
    step = np.diff(phi)
    if not (np.all(step > 0) or np.all(step < 0)) or abs(phi[-1] - phi[0]) > 2 * math.pi + 1e-9:
        return None
    return Arc(_xy(a), _xy(b), _xy(center), radius, float(phi[-1] - phi[0]))
