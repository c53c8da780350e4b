"""Exact distances from many points to many 3-D primitives (chain segments, polyline edges).

Every primitive is sampled so that each of its points lies within h/2 of one of its own
samples; a KD-tree over the samples gives, for a query point x, an upper bound d (the exact
distance to the owners of its nearest samples), and every primitive that can be nearer than d
has a sample within d + h/2 of x. Measuring those exactly gives the exact minimum, in
N log N (the same proof idea as the planar coatsim.geometry.nearest).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

from coatsim.geometry.space.chain import SpaceChain
from coatsim.geometry.space.primitives import Arc3

NEIGHBOURS = 12  # samples asked of the KD-tree per point before a ball query is needed
MAX_SAMPLES = 2_000_000  # samples per index, at most (the spacing grows past it)

Distance = Callable[[np.ndarray, np.ndarray], np.ndarray]


@dataclass(frozen=True, eq=False)
class SegmentTable:
    """A chain's segments as arrays, for vectorised distances and points (lines have
    radius inf and sweep 0)."""

    is_arc: np.ndarray
    start: np.ndarray
    end: np.ndarray
    center: np.ndarray
    normal: np.ndarray
    radius: np.ndarray
    sweep: np.ndarray
    length: np.ndarray

    @classmethod
    def of(cls, chain: SpaceChain) -> SegmentTable:
        segs = chain.segments
        arc = np.array([isinstance(s, Arc3) for s in segs])
        get = lambda name, default: np.array([getattr(s, name) if a else default for s, a in zip(segs, arc)], dtype=float)  # noqa: E731
        return cls(arc, np.array([s.start for s in segs]), np.array([s.end for s in segs]),
                   get("center", np.zeros(3)), get("normal", np.zeros(3)), get("radius", math.inf),
                   get("sweep", 0.0), np.array([s.length for s in segs]))

    def distance(self, points: np.ndarray, seg: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Exact distance from points[i] to segment seg[i], and the arc length of the nearest point."""
        d, s = np.empty(len(seg)), np.empty(len(seg))
        line = ~self.is_arc[seg]
        if line.any():
            d[line], s[line] = _segment_distance(points[line], self.start[seg[line]], self.end[seg[line]])
        arc = ~line
        if arc.any():
            j, p = seg[arc], points[arc]
            rel = p - self.center[j]
            u = (self.start[j] - self.center[j]) / self.radius[j, None]
            v = np.cross(self.normal[j], u)
            a, b = np.einsum("ij,ij->i", rel, u), np.einsum("ij,ij->i", rel, v)
            phi = np.mod(np.arctan2(b, a), 2 * math.pi)
            inside = phi <= self.sweep[j]
            height = np.einsum("ij,ij->i", rel, self.normal[j])
            d_circle = np.hypot(height, np.hypot(a, b) - self.radius[j])
            d0 = np.linalg.norm(p - self.start[j], axis=1)
            d1 = np.linalg.norm(p - self.end[j], axis=1)
            d[arc] = np.where(inside, d_circle, np.minimum(d0, d1))
            s[arc] = np.where(inside, phi * self.radius[j], np.where(d1 < d0, self.length[j], 0.0))
        return d, s

    def point_at(self, seg: np.ndarray, s: np.ndarray) -> np.ndarray:
        """Points at arc lengths s[i] along segments seg[i]."""
        out = np.empty((len(seg), 3))
        line = ~self.is_arc[seg]
        if line.any():
            j = seg[line]
            frac = np.where(self.length[j] > 0, s[line] / np.where(self.length[j] > 0, self.length[j], 1.0), 0.0)
            out[line] = self.start[j] + frac[:, None] * (self.end[j] - self.start[j])
        arc = ~line
        if arc.any():
            j = seg[arc]
            radial = self.start[j] - self.center[j]
            angle = s[arc] / self.radius[j]
            axv = np.cross(self.normal[j], radial)
            out[arc] = (self.start[j] + np.sin(angle)[:, None] * axv
                        + (2 * np.sin(angle / 2) ** 2)[:, None] * np.cross(self.normal[j], axv))
        return out


def _segment_distance(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Distance from points p[i] to segments a[i]->b[i], and the distance along it of the foot."""
    ab = b - a
    length = np.linalg.norm(ab, axis=1)
    safe = np.where(length > 0, length, 1.0)
    t = np.clip(np.einsum("ij,ij->i", p - a, ab) / safe, 0.0, length)
    return np.linalg.norm(p - a - (t / safe)[:, None] * ab, axis=1), t


class SampledIndex:
    """Exact nearest-primitive distance for points, over primitives sampled every ``h`` mm
    or closer (``samples`` (N, 3), ``owner`` (N,) the primitive of each sample)."""

    def __init__(self, samples: np.ndarray, owner: np.ndarray, h: float, distance: Distance):
        from scipy.spatial import cKDTree

        self.tree, self.owner, self.h, self.measure = cKDTree(samples), owner, h, distance

    def distance(self, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(exact distance (n,), nearest primitive (n,)) of points (n, 3)."""
        points = np.asarray(points, dtype=float).reshape(-1, 3)
        k = min(NEIGHBOURS, self.tree.n)
        dk, ik = self.tree.query(points, k=k)
        dk, ik = dk.reshape(len(points), k), ik.reshape(len(points), k)
        owners = self.owner[ik]
        rows = np.repeat(np.arange(len(points)), k)
        d = self.measure(points[rows], owners.ravel()).reshape(len(points), k)
        pick = np.argmin(d, axis=1)
        best, who = d[np.arange(len(points)), pick], owners[np.arange(len(points)), pick]
        unsure = np.flatnonzero((dk[:, -1] <= best + self.h / 2) & (k < self.tree.n))
        for i in unsure:  # the k samples may not hold every candidate: ask for all of them
            near = np.unique(self.owner[self.tree.query_ball_point(points[i], best[i] + self.h / 2)])
            dd = self.measure(np.repeat(points[i : i + 1], len(near), axis=0), near)
            j = int(np.argmin(dd))
            if dd[j] < best[i]:
                best[i], who[i] = dd[j], near[j]
        return best, who


def chain_index(table: SegmentTable, h: float) -> SampledIndex:
    """A SampledIndex over a chain's segments, sampled every ``h`` mm or closer."""
    h = max(h, float(table.length.sum()) / MAX_SAMPLES)
    count = np.maximum(1, np.ceil(table.length / h).astype(np.int64)) + 1
    seg = np.repeat(np.arange(len(count)), count)
    first = np.repeat(np.cumsum(count) - count, count)
    s = (np.arange(len(seg)) - first) / (count[seg] - 1) * table.length[seg]
    return SampledIndex(table.point_at(seg, s), seg, h, lambda p, j: table.distance(p, j)[0])


def polyline_index(vertices: np.ndarray) -> tuple[SampledIndex, float]:
    """A SampledIndex over a polyline's edges (sampled at about the median edge length),
    and that spacing."""
    a, b = vertices[:-1], vertices[1:]
    length = np.linalg.norm(b - a, axis=1)
    h = max(float(np.median(length)), float(length.sum()) / MAX_SAMPLES, 1e-12)
    count = np.maximum(1, np.ceil(length / h).astype(np.int64)) + 1
    edge = np.repeat(np.arange(len(count)), count)
    first = np.repeat(np.cumsum(count) - count, count)
    u = (np.arange(len(edge)) - first) / (count[edge] - 1)
    samples = a[edge] + u[:, None] * (b[edge] - a[edge])
    return SampledIndex(samples, edge, h, lambda p, e: _segment_distance(p, a[e], b[e])[0]), h


def edge_distance(points: np.ndarray, vertices: np.ndarray, edge: np.ndarray) -> np.ndarray:
    """Distance from points[i] to polyline edge edge[i]."""
    return _segment_distance(points, vertices[edge], vertices[edge + 1])[0]
