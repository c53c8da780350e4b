"""Exact two-sided Hausdorff distance between an input polyline and a polysegment.

Distances are computed point-to-primitive in closed form (no sampling of either curve).
Both directions are evaluated at every point where the distance can have a local maximum:

- polyline -> polysegment: every input vertex, plus on every input edge the foot of the
  centre of a nearby arc (where a chord is deepest inside an arc, the sagitta case);
- polysegment -> polyline: every segment end, the foot on the polysegment of every input
  vertex, and on every arc the points whose tangent is parallel to a nearby input edge.

Nearest input edges are found with a KD-tree among the edges at the nearest vertices; where
that search cannot prove no farther edge is closer (very dense input), the value is the
distance to the nearest edge found, an upper bound, so the check never under-reports.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

from coatsim.geometry.polysegment import Polysegment
from coatsim.geometry.primitives import Arc


@dataclass(frozen=True)
class Deviation:
    """Hausdorff distance (mm) and its two directed parts."""

    input_to_output: float
    output_to_input: float

    @property
    def hausdorff(self) -> float:
        return max(self.input_to_output, self.output_to_input)


def distance_to_polysegment(points: np.ndarray, poly: Polysegment) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Exact distance from each point (m, 2) to the polysegment.

    Returns (distance (m,), index of the nearest segment (m,), nearest point (m, 2)).
    """
    pts = np.asarray(points, dtype=float)
    best = np.full(len(pts), np.inf)
    index = np.zeros(len(pts), dtype=int)
    foot = np.zeros_like(pts)
    for j, seg in enumerate(poly.segments):
        # Every point of a segment lies within half its length of its middle point: points
        # farther than that from the middle plus their best distance so far cannot improve.
        middle = seg.points(np.array([seg.length / 2]))[0]
        cand = np.flatnonzero(np.linalg.norm(pts - middle, axis=1) - seg.length / 2 < best)
        if not len(cand):
            continue
        d, f = _distance_to_segment(pts[cand], seg)
        better = d < best[cand]
        upd = cand[better]
        best[upd], index[upd], foot[upd] = d[better], j, f[better]
    return best, index, foot


def _distance_to_segment(pts: np.ndarray, seg) -> tuple[np.ndarray, np.ndarray]:
    a, b = np.asarray(seg.start), np.asarray(seg.end)
    if not isinstance(seg, Arc):
        ab = b - a
        denom = float(ab @ ab)
        u = np.clip((pts - a) @ ab / denom, 0.0, 1.0) if denom > 0 else np.zeros(len(pts))
        f = a + u[:, None] * ab
        return np.linalg.norm(pts - f, axis=1), f
    c = np.asarray(seg.center)
    rel = pts - c
    r = np.linalg.norm(rel, axis=1)
    ang = np.arctan2(rel[:, 1], rel[:, 0])
    direction = 1.0 if seg.sweep > 0 else -1.0
    phi = np.mod(direction * (ang - seg.start_angle), 2 * np.pi)
    inside = phi <= abs(seg.sweep)
    on_circle = c + seg.radius * np.column_stack((np.cos(ang), np.sin(ang)))
    da, db = np.linalg.norm(pts - a, axis=1), np.linalg.norm(pts - b, axis=1)
    end_foot = np.where((da <= db)[:, None], a, b)
    d = np.where(inside, np.abs(r - seg.radius), np.minimum(da, db))
    f = np.where(inside[:, None], on_circle, end_foot)
    return d, f


class PolylineDistance:
    """Exact distance from query points to a fixed polyline (KD-tree accelerated)."""

    def __init__(self, vertices: np.ndarray) -> None:
        self.vertices = np.asarray(vertices, dtype=float)
        self.tree = cKDTree(self.vertices)
        edges = np.diff(self.vertices, axis=0)
        self.max_edge = float(np.linalg.norm(edges, axis=1).max()) if len(edges) else 0.0

    def _edge_distance(self, pts: np.ndarray, edge: np.ndarray) -> np.ndarray:
        a, b = self.vertices[edge], self.vertices[edge + 1]
        ab = b - a
        denom = np.einsum("ij,ij->i", ab, ab)
        u = np.clip(np.einsum("ij,ij->i", pts - a, ab) / np.where(denom > 0, denom, 1.0), 0.0, 1.0)
        return np.linalg.norm(pts - (a + u[:, None] * ab), axis=1)

    def _nearest(self, pts: np.ndarray, k: int) -> tuple[np.ndarray, np.ndarray]:
        """Distance to the polyline using the edges at the k nearest vertices, and whether
        that is provably exact (no farther vertex can start a closer edge)."""
        n_vert = len(self.vertices)
        k = min(k, n_vert)
        dist_v, idx = self.tree.query(pts, k=k)
        dist_v, idx = dist_v.reshape(len(pts), k), idx.reshape(len(pts), k)
        best = dist_v[:, 0].copy()
        for col in range(k):
            for edge in (idx[:, col] - 1, idx[:, col]):
                valid = (edge >= 0) & (edge < n_vert - 1)
                best[valid] = np.minimum(best[valid], self._edge_distance(pts[valid], edge[valid]))
        # An edge closer than `best` has an end point within best + max_edge / 2.
        exact = (dist_v[:, -1] > best + self.max_edge / 2) | (k == n_vert)
        return best, exact

    def near(self, points: np.ndarray, anchors: np.ndarray, window: int = 6) -> np.ndarray:
        """Distance from each point to the edges within ``window`` edges of its anchor
        vertex: an upper bound on the distance to the polyline, tight when the anchor is
        where the point's nearest approach lies."""
        pts = np.asarray(points, dtype=float)
        best = np.full(len(pts), np.inf)
        for off in range(-window, window):
            edge = np.clip(anchors + off, 0, len(self.vertices) - 2)
            best = np.minimum(best, self._edge_distance(pts, edge))
        return best

    def __call__(self, points: np.ndarray) -> np.ndarray:
        """Distance from each point to the polyline: exact where the neighbourhood search
        proves it, otherwise the distance to the nearest of the 64 closest vertices' edges,
        which can only be larger than the true one (a safe bound for a tolerance check)."""
        pts = np.asarray(points, dtype=float)
        best = np.empty(len(pts))
        todo = np.arange(len(pts))
        for k in (8, 64):
            if not len(todo):
                break
            d, exact = self._nearest(pts[todo], k)
            best[todo] = d
            todo = todo[~exact]
        return best


SEGMENT_SAMPLES = 17  # points along each output segment checked besides the analytic candidates


def _switch_candidates(a: np.ndarray, ab: np.ndarray, seg_of: np.ndarray, poly: Polysegment,
                       is_arc: np.ndarray, centers: np.ndarray) -> list[np.ndarray]:
    """Extra points on input edges whose two ends are nearest to different segments: where
    the distances to the two segments are equal (a maximum of their minimum can sit there,
    e.g. an edge passing under a corner), the feet of the centres of the arcs between them,
    and points along such edges when they are long (sparse input)."""
    edges = np.flatnonzero(seg_of[:-1] != seg_of[1:])
    if not len(edges):
        return []
    out = []
    lo, hi = np.zeros(len(edges)), np.ones(len(edges))
    j1, j2 = seg_of[edges], seg_of[edges + 1]

    def gap(u: np.ndarray) -> np.ndarray:
        x = a[edges] + u[:, None] * ab[edges]
        d1 = np.array([_distance_to_segment(x[i : i + 1], poly.segments[j])[0][0] for i, j in enumerate(j1)])
        d2 = np.array([_distance_to_segment(x[i : i + 1], poly.segments[j])[0][0] for i, j in enumerate(j2)])
        return d1 - d2

    for _ in range(40):  # bisection: d1 - d2 goes from <= 0 at the edge's start to >= 0 at its end
        mid = (lo + hi) / 2
        right = gap(mid) > 0
        hi, lo = np.where(right, mid, hi), np.where(right, lo, mid)
    out.append(a[edges] + ((lo + hi) / 2)[:, None] * ab[edges])
    length = np.linalg.norm(ab, axis=1)
    step = float(np.median(length))
    for e, first, last in zip(edges, np.minimum(j1, j2), np.maximum(j1, j2)):
        between = np.arange(first, last + 1)
        arcs = between[is_arc[between]]
        if len(arcs):
            u = np.clip((centers[arcs] - a[e]) @ ab[e] / (ab[e] @ ab[e]), 0.0, 1.0)
            out.append(a[e] + u[:, None] * ab[e])
        if length[e] > 4 * step:
            u = np.linspace(0.0, 1.0, min(int(length[e] / step) + 1, 200))
            out.append(a[e] + u[:, None] * ab[e])
    return out


def hausdorff(polyline: np.ndarray, poly: Polysegment) -> Deviation:
    """Exact two-sided Hausdorff distance between ``polyline`` (n, 2) and ``poly``."""
    verts = np.asarray(polyline, dtype=float)
    d_vert, seg_of, foot = distance_to_polysegment(verts, poly)

    # polyline -> polysegment: edge interiors deepest inside a nearby arc.
    a, b = verts[:-1], verts[1:]
    ab = b - a
    denom = np.einsum("ij,ij->i", ab, ab)
    is_arc = np.array([isinstance(seg, Arc) for seg in poly.segments])
    centers = np.array([seg.center if isinstance(seg, Arc) else (0.0, 0.0) for seg in poly.segments])
    extra = []
    for owner in (seg_of[:-1], seg_of[1:]):
        u = np.einsum("ij,ij->i", centers[owner] - a, ab) / np.where(denom > 0, denom, 1.0)
        interior = is_arc[owner] & (u > 0) & (u < 1)
        extra.append(a[interior] + u[interior, None] * ab[interior])
    extra += _switch_candidates(a, ab, seg_of, poly, is_arc, centers)
    d_in = float(d_vert.max())
    cand = np.vstack(extra)
    if len(cand):
        d_in = max(d_in, float(distance_to_polysegment(cand, poly)[0].max()))

    # polysegment -> polyline: candidates anchored at the input vertex or edge they come from.
    measure = PolylineDistance(verts)
    cand, anchor = [foot], [np.arange(len(verts))]
    headings = np.arctan2(ab[:, 1], ab[:, 0])
    for j, seg in enumerate(poly.segments):
        if not isinstance(seg, Arc):
            continue
        near = np.flatnonzero((seg_of[:-1] == j) | (seg_of[1:] == j))
        ang = headings[near] - np.sign(seg.sweep) * np.pi / 2
        phi = np.mod(np.sign(seg.sweep) * (ang - seg.start_angle), 2 * np.pi)
        ok = phi <= abs(seg.sweep)
        cand.append(np.asarray(seg.center) + seg.radius * np.column_stack((np.cos(ang[ok]), np.sin(ang[ok]))))
        anchor.append(near[ok])
    # a few points along every segment, more along one no input vertex is nearest to
    owned = np.bincount(seg_of, minlength=len(poly.segments)) > 0
    for j, seg in enumerate(poly.segments):
        along = seg.points(np.linspace(0.0, seg.length, SEGMENT_SAMPLES if owned[j] else 4 * SEGMENT_SAMPLES))
        cand.append(along)
        anchor.append(np.full(len(along), int(np.argmin(np.linalg.norm(verts - along[len(along) // 2], axis=1)))))
    points, quick = np.vstack(cand), measure.near(np.vstack(cand), np.concatenate(anchor))
    # The windowed distance is an upper bound; where it would set a new maximum, measure
    # against the whole polyline instead (the anchor may not be where the point is closest).
    doubt = quick > max(d_in, float(np.median(quick)))
    if doubt.any():
        quick[doubt] = np.minimum(quick[doubt], measure(points[doubt]))
    d_out = float(quick.max())
    ends = np.array([s.start for s in poly.segments] + [poly.end])
    d_out = max(d_out, float(measure(ends).max()))
    return Deviation(d_in, d_out)
