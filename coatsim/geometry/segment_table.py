"""The segments of a polysegment as arrays, for vectorised exact geometry on many points.

Every segment is described by its start point, start heading, signed curvature and length
(a line has curvature 0), never by its centre: the formulas below stay exact for nearly
straight arcs of huge radius, where ``|p - centre| - radius`` loses every digit.

For a point p, q = p - start, t the unit start tangent and n the unit normal towards the
centre (the left normal of a line), the circle through the start is
w(p) = |κ|·|q|² − 2 q·n = 0; the distance to it is |w| / (1 + sqrt(1 + |κ| w)), which tends
to the line distance |q·n| as κ -> 0.

Queries take one segment index per point. Points come mostly in runs on one segment (a
polyline in order), so a query is evaluated run by run with the segment's numbers as scalars
when the runs are few, and with gathered per-point numbers otherwise.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from coatsim.geometry.polysegment import Polysegment
from coatsim.geometry.primitives import Arc

RUNS_PER_POINT = 1 / 256  # evaluate run by run when there are at most this many runs per point


class _Numbers(NamedTuple):
    """One segment's numbers (floats), or one per point (arrays)."""

    ax: np.ndarray  # start
    ay: np.ndarray
    bx: np.ndarray  # end
    by: np.ndarray
    tx: np.ndarray  # unit start tangent
    ty: np.ndarray
    nx: np.ndarray  # unit normal towards the centre (left normal of a line)
    ny: np.ndarray
    ex: np.ndarray  # unit end tangent
    ey: np.ndarray
    kappa: np.ndarray  # signed curvature, 1/mm
    ak: np.ndarray  # |kappa|
    heading: np.ndarray  # start heading, rad
    length: np.ndarray
    wide: np.ndarray  # turns by more than half a circle


def _distance(n: _Numbers, px: np.ndarray, py: np.ndarray):
    qx, qy = px - n.ax, py - n.ay
    w = n.ak * (qx * qx + qy * qy) - 2 * (qx * n.nx + qy * n.ny)
    root = np.sqrt(np.maximum(1 + n.ak * w, 0.0))
    signed = w / (1 + root)
    after_start = qx * n.tx + qy * n.ty >= 0
    before_end = (px - n.bx) * n.ex + (py - n.by) * n.ey <= 0
    inside = np.where(n.wide, after_start | before_end, after_start & before_end)
    centred = root > 1e-12
    scale = signed / np.where(centred, root, 1.0)
    fx = np.where(centred, px - scale * (n.ak * qx - n.nx), n.ax)
    fy = np.where(centred, py - scale * (n.ak * qy - n.ny), n.ay)
    da, db = np.hypot(qx, qy), np.hypot(px - n.bx, py - n.by)
    at_start = da <= db
    d = np.where(inside, np.abs(signed), np.minimum(da, db))
    fx = np.where(inside, fx, np.where(at_start, n.ax, n.bx))
    fy = np.where(inside, fy, np.where(at_start, n.ay, n.by))
    near = d * (1 + 1e-9) + 1e-12  # an inside foot on an end counts as that end
    where = np.where(inside & (da > near) & (db > near), 0, np.where(at_start, -1, 1))
    return d, fx, fy, where


def _point_at(n: _Numbers, s: np.ndarray):
    half = n.kappa * s / 2
    r = s * np.sinc(half / math.pi)
    return n.ax + r * np.cos(n.heading + half), n.ay + r * np.sin(n.heading + half)


def _along(n: _Numbers, px: np.ndarray, py: np.ndarray):
    dx, dy = px - n.ax, py - n.ay
    half = np.where(n.kappa == 0, 0.0, np.arctan2(np.sign(n.kappa) * (n.tx * dy - n.ty * dx), n.tx * dx + n.ty * dy))
    return (np.minimum(np.hypot(dx, dy) / np.sinc(half / np.pi), n.length),)


def _contains(n: _Numbers, px: np.ndarray, py: np.ndarray):
    after_start = (px - n.ax) * n.tx + (py - n.ay) * n.ty >= 0
    before_end = (px - n.bx) * n.ex + (py - n.by) * n.ey <= 0
    return (np.where(n.wide, after_start | before_end, after_start & before_end),)


def _crossings(n: _Numbers, ox: np.ndarray, oy: np.ndarray, dx: np.ndarray, dy: np.ndarray):
    # on the circle |κ|τ² + 2βτ + γ = 0, β = |κ| q0·d − d·n, γ = |κ||q0|² − 2 q0·n (|d| = 1)
    qx, qy = ox - n.ax, oy - n.ay
    beta = n.ak * (qx * dx + qy * dy) - (dx * n.nx + dy * n.ny)
    gamma = n.ak * (qx * qx + qy * qy) - 2 * (qx * n.nx + qy * n.ny)
    disc = beta * beta - n.ak * gamma
    big = -(beta + np.copysign(np.sqrt(np.maximum(disc, 0.0)), beta))
    with np.errstate(divide="ignore", invalid="ignore"):
        tau1 = np.where((disc >= 0) & (big != 0), gamma / np.where(big != 0, big, 1.0), np.nan)
        tau2 = np.where((disc >= 0) & (n.ak > 0), big / np.where(n.ak > 0, n.ak, 1.0), np.nan)
    return tau1, tau2


@dataclass(frozen=True, eq=False)
class SegmentTable:
    """m segments: start and end (m, 2) mm, start heading (m,) rad, signed curvature (m,)
    1/mm, length (m,) mm; ``closed`` when the last segment ends where the first starts."""

    start: np.ndarray
    end: np.ndarray
    heading: np.ndarray
    kappa: np.ndarray
    length: np.ndarray
    closed: bool

    @classmethod
    def of(cls, poly: Polysegment) -> SegmentTable:
        segs = poly.segments
        start = np.array([s.start for s in segs], dtype=float)
        end = np.array([s.end for s in segs], dtype=float)
        chord = end - start
        heading = np.array([s.start_heading if isinstance(s, Arc) else math.atan2(c[1], c[0])
                            for s, c in zip(segs, chord)])
        kappa = np.array([s.curvature for s in segs], dtype=float)
        length = np.array([s.length for s in segs], dtype=float)
        return cls(start, end, heading, kappa, length, poly.closed)

    def __post_init__(self) -> None:
        side = np.where(self.kappa < 0, -1.0, 1.0)
        t = np.column_stack((np.cos(self.heading), np.sin(self.heading)))
        turn = self.heading + self.kappa * self.length
        cols = _Numbers(self.start[:, 0], self.start[:, 1], self.end[:, 0], self.end[:, 1], t[:, 0], t[:, 1],
                        -side * t[:, 1], side * t[:, 0], np.cos(turn), np.sin(turn), self.kappa,
                        np.abs(self.kappa), self.heading, self.length, np.abs(self.kappa * self.length) > math.pi)
        object.__setattr__(self, "_cols", cols)
        object.__setattr__(self, "_rows", [_Numbers(*row) for row in zip(*(c.tolist() for c in cols))])

    def __len__(self) -> int:
        return len(self.length)

    def _apply(self, kernel: Callable, seg: np.ndarray, *values: np.ndarray) -> tuple[np.ndarray, ...]:
        """``kernel(numbers, *values)`` with the numbers of segment seg[i] for values[...][i]."""
        seg = np.asarray(seg, dtype=np.int64)
        cut = np.flatnonzero(seg[1:] != seg[:-1]) + 1
        if len(seg) == 0 or len(cut) + 1 > max(16, len(seg) * RUNS_PER_POINT):
            return kernel(_Numbers(*(c[seg] for c in self._cols)), *values)
        edges = np.r_[0, cut, len(seg)]
        parts = [kernel(self._rows[seg[a]], *(v[a:b] for v in values)) for a, b in zip(edges[:-1], edges[1:])]
        if len(parts) == 1:
            return tuple(np.broadcast_to(x, (len(seg),)) if np.ndim(x) == 0 else x for x in parts[0])
        return tuple(np.concatenate([np.broadcast_to(x, (b - a,)) for x, a, b in zip(col, edges[:-1], edges[1:])])
                     for col in zip(*parts))

    def neighbour(self, seg: np.ndarray, step: int) -> np.ndarray:
        """Index of the segment ``step`` (±1) along the chain; -1 past an open end."""
        nxt = seg + step
        if self.closed:
            return nxt % len(self)
        return np.where((nxt >= 0) & (nxt < len(self)), nxt, -1)

    def distance(self, points: np.ndarray, seg: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Exact distance from ``points[i]`` to segment ``seg[i]``.

        Returns (distance (n,), nearest point (n, 2), where (n,): -1 at (or within rounding
        of) the start, +1 at the end, 0 inside)."""
        p = np.asarray(points, dtype=float)
        d, fx, fy, where = self._apply(_distance, seg, p[:, 0], p[:, 1])
        return d, np.column_stack((fx, fy)), where

    def point_at(self, seg: np.ndarray, s: np.ndarray) -> np.ndarray:
        """Points at arc lengths ``s`` (mm) along segments ``seg``, shape (n, 2)."""
        return np.column_stack(self._apply(_point_at, seg, np.asarray(s, dtype=float)))

    def along(self, points: np.ndarray, seg: np.ndarray) -> np.ndarray:
        """Arc length (mm) from the start of segment ``seg[i]`` to ``points[i]`` on it: the
        chord from the start makes half the turn with the start tangent."""
        p = np.asarray(points, dtype=float)
        return self._apply(_along, seg, p[:, 0], p[:, 1])[0]

    def contains(self, points: np.ndarray, seg: np.ndarray) -> np.ndarray:
        """Whether each point's radial projection falls inside its segment (for points on
        the segment's circle or line: whether the point lies on the segment)."""
        p = np.asarray(points, dtype=float)
        return self._apply(_contains, seg, p[:, 0], p[:, 1])[0]

    def centre(self, seg: np.ndarray) -> np.ndarray:
        """Centres of arcs ``seg`` (curvature must be non-zero)."""
        c = self._cols
        return self.start[seg] + (1.0 / self.kappa[seg])[:, None] * np.column_stack((-c.ty[seg], c.tx[seg]))

    def line_crossings(self, origin: np.ndarray, direction: np.ndarray, seg: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Where the lines ``origin + τ·direction`` (unit directions) cross segments ``seg``:
        up to two points per row. Returns (points (2n, 2), valid (2n,)), the first roots of
        every row, then the second ones."""
        tau1, tau2 = self._apply(_crossings, seg, origin[:, 0], origin[:, 1], direction[:, 0], direction[:, 1])
        taus = np.concatenate((tau1, tau2))
        rows = np.concatenate((seg, seg))
        pts = np.concatenate((origin, origin)) + np.nan_to_num(taus)[:, None] * np.concatenate((direction, direction))
        return pts, np.isfinite(taus) & self.contains(pts, rows)
