"""Shared helpers for the geometry tests: benchmark curves (coatsim.geometry.benchmark), cached segmentations, independent
geometric checks (computed here from the primitives, not with coatsim's own helpers) and
brute-force distances."""

from __future__ import annotations

import functools
import math

import numpy as np
from scipy.spatial import cKDTree

from coatsim.geometry import Arc, Polysegment, load_curve, segment_curve
from coatsim.geometry.benchmark import CURVES, NAMES, REFERENCE_COUNTS, TOLERANCES_MM, bench_curve

BENCH_NAMES = NAMES
BENCH_CLOSED = {name: closed for name, (_, closed) in CURVES.items()}
TOLERANCES = TOLERANCES_MM


def bench_spec(name: str) -> str:
    """The curve spec of a benchmark curve (``bench:NAME``, read by ``curve``)."""
    return f"bench:{name}"


def reference_counts() -> dict[str, dict[str, dict[float, int]]]:
    """Reference segment counts: ``{"greedy": {curve: {σ: n}}, "paper": {curve: {σ: n}}}``."""
    return {kind: {name: dict(zip(TOLERANCES, counts)) for name, counts in table.items()}
            for kind, table in REFERENCE_COUNTS.items()}


@functools.lru_cache(maxsize=None)
def curve(spec: str, closed: str = "auto"):
    """A curve spec as ``coatsim segment`` reads it, or ``bench:NAME`` for a benchmark curve."""
    if spec.startswith("bench:"):
        return bench_curve(spec.removeprefix("bench:"))
    return load_curve(spec, closed)


@functools.lru_cache(maxsize=None)
def segmented(spec: str, tol: float, method: str = "optimal"):
    """segment_curve on a curve spec, computed once per test session."""
    return segment_curve(curve(spec), tol, method=method)


# ---------------------------------------------------------------- independent geometry


def end_tangent(seg) -> np.ndarray:
    """Unit tangent at the end of a segment, from its end points (and centre)."""
    if isinstance(seg, Arc):
        r = np.subtract(seg.end, seg.center)
        t = np.array([-r[1], r[0]]) * math.copysign(1.0, seg.sweep)
    else:
        t = np.subtract(seg.end, seg.start)
    return t / np.linalg.norm(t)


def start_tangent(seg) -> np.ndarray:
    if isinstance(seg, Arc):
        r = np.subtract(seg.start, seg.center)
        t = np.array([-r[1], r[0]]) * math.copysign(1.0, seg.sweep)
    else:
        t = np.subtract(seg.end, seg.start)
    return t / np.linalg.norm(t)


def tangent_breaks(poly: Polysegment) -> list[tuple[int, float]]:
    """(junction index, turn in rad) for every junction; the seam last for a closed chain."""
    segs = poly.segments
    pairs = list(zip(segs[:-1], segs[1:]))
    if poly.closed:
        pairs.append((segs[-1], segs[0]))
    out = []
    for k, (a, b) in enumerate(pairs):
        ta, tb = end_tangent(a), start_tangent(b)
        out.append((k, abs(math.atan2(ta[0] * tb[1] - ta[1] * tb[0], ta @ tb))))
    return out


def junction_gaps(poly: Polysegment) -> list[tuple[int, tuple, tuple]]:
    """Junctions whose end and start points differ (exact comparison)."""
    segs = poly.segments
    return [(k, a.end, b.start) for k, (a, b) in enumerate(zip(segs[:-1], segs[1:])) if tuple(a.end) != tuple(b.start)]


def arc_defects(poly: Polysegment, rel: float = 1e-9) -> list[str]:
    """Arcs whose end points are off their circle or whose sweep disagrees with the end points."""
    bad = []
    for k, seg in enumerate(poly.segments):
        if not isinstance(seg, Arc):
            continue
        for name, p in (("start", seg.start), ("end", seg.end)):
            off = abs(math.dist(p, seg.center) - seg.radius)
            if off > rel * max(1.0, seg.radius):
                bad.append(f"segment {k}: {name} {off:.3g} mm off its circle")
        a0 = math.atan2(seg.start[1] - seg.center[1], seg.start[0] - seg.center[0])
        a1 = math.atan2(seg.end[1] - seg.center[1], seg.end[0] - seg.center[0])
        miss = abs(math.remainder(a0 + seg.sweep - a1, 2 * math.pi))
        if miss * seg.radius > rel * max(1.0, seg.radius) * 10:
            bad.append(f"segment {k}: sweep misses the end point by {miss:.3g} rad")
    return bad


def junction_points(poly: Polysegment) -> np.ndarray:
    return np.array([s.start for s in poly.segments] + [poly.end], dtype=float)


# ---------------------------------------------------------------- brute force


def point_at(seg, s: np.ndarray) -> np.ndarray:
    """Points at arc lengths ``s`` along a primitive, from its own definition."""
    s = np.asarray(s, dtype=float)
    if isinstance(seg, Arc):
        a0 = math.atan2(seg.start[1] - seg.center[1], seg.start[0] - seg.center[0])
        phi = a0 + math.copysign(1.0, seg.sweep) * s / seg.radius
        return np.asarray(seg.center) + seg.radius * np.column_stack((np.cos(phi), np.sin(phi)))
    a, b = np.asarray(seg.start, float), np.asarray(seg.end, float)
    return a + (s / seg.length)[:, None] * (b - a)


def dense_polysegment(poly: Polysegment, step: float) -> np.ndarray:
    """Points on the polysegment no farther than ``step`` apart along it (ends included)."""
    out = []
    for seg in poly.segments:
        n = max(1, int(math.ceil(seg.length / step)))
        out.append(point_at(seg, np.linspace(0.0, seg.length, n + 1)))
    return np.vstack(out)


def dense_polyline(points: np.ndarray, step: float) -> np.ndarray:
    """Points on a polyline no farther than ``step`` apart (vertices included)."""
    pts = np.asarray(points, dtype=float)
    d = np.diff(pts, axis=0)
    n = np.maximum(1, np.ceil(np.linalg.norm(d, axis=1) / step).astype(np.int64))
    edge = np.repeat(np.arange(len(d)), n)
    k = np.arange(len(edge)) - np.repeat(np.cumsum(n) - n, n) + 1  # 1..n along each edge
    return np.vstack((pts[:1], pts[edge] + (k / n[edge])[:, None] * d[edge]))


def distance_to_polyline(points: np.ndarray, vertices: np.ndarray, chunk: int = 4000) -> np.ndarray:
    """Exact distance from every point to a (small) polyline, all edges tried."""
    a, b = vertices[:-1], vertices[1:]
    ab = b - a
    den = np.where((ab * ab).sum(axis=1) > 0, (ab * ab).sum(axis=1), 1.0)
    out = np.empty(len(points))
    for i in range(0, len(points), chunk):
        q = points[i : i + chunk, None, :]
        u = np.clip(((q - a) * ab).sum(axis=2) / den, 0.0, 1.0)
        out[i : i + chunk] = np.linalg.norm(q - (a + u[..., None] * ab), axis=2).min(axis=1)
    return out


def brute_hausdorff(polyline: np.ndarray, poly: Polysegment, step: float) -> float:
    """Two-sided Hausdorff distance by dense sampling of both curves with a KD-tree.

    Within ``step`` of the true value: every point of either curve is within step / 2 of a
    sample of that curve."""
    a = dense_polyline(polyline, step)
    b = dense_polysegment(poly, step)
    d_ab = cKDTree(b).query(a)[0].max()
    d_ba = cKDTree(a).query(b)[0].max()
    return float(max(d_ab, d_ba))


G1_RAD = 1e-9  # a junction turning less than this is tangent-continuous


def assert_contract(seg, tol: float, points: np.ndarray | None = None) -> None:
    """The fitter's contract on ``points`` (default: the segmented curve's): tolerance (the exact
    check, and brute force to within its step), G1 everywhere but at listed corners, shared end
    points, a closed chain ending where it starts."""
    from coatsim.geometry.deviation import hausdorff

    poly = seg.polysegment
    pts = seg.curve.points if points is None else points
    assert seg.max_deviation_mm <= tol
    assert hausdorff(pts, poly).hausdorff <= tol
    assert brute_hausdorff(pts, poly, tol / 10) <= tol * 1.05
    for k, turn in tangent_breaks(poly):
        assert k in poly.corners or turn <= G1_RAD, f"junction {k} breaks the tangent by {turn:.3g} rad"
    segs = poly.segments
    assert all(a.end == b.start for a, b in zip(segs[:-1], segs[1:]))
    if poly.closed:
        assert poly.end == poly.start
