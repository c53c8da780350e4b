"""Exact two-sided Hausdorff distance between an input polyline and a polysegment.

Distances are computed point-to-primitive in closed form (no sampling of either curve), at
every point where the distance can have a local maximum:

- polyline -> polysegment: every input vertex; inside an edge, only where the edge can
  still beat the maximum (its end distances and length allow it: the distance is
  1-Lipschitz along the edge), there the feet of nearby arc centres (a chord deepest inside
  an arc), the points equidistant from an arc's ends, and the points where the nearest
  segment switches (a corner passing over the edge), found by a vectorised bisection;
- polysegment -> polyline: every segment end, points along every segment, the foot of every
  input vertex, the points of every arc whose tangent is parallel to a nearby input edge and
  the crossings of every vertex's angle bisector (where its two edges are equally near).

Nearest features come from KD-tree indices (coatsim.geometry.nearest) with a proof: a point
is measured exactly only while its upper bound can still set the maximum, so the cost is
N log N and the result the exact maximum over the candidates.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from coatsim.geometry.certify import certify
from coatsim.geometry.nearest import (
    PolylineIndex,
    PolysegmentIndex,
    distance_per_point,
    edge_distance,
    expand_ranges,
    max_distance,
)
from coatsim.geometry.polysegment import Polysegment
from coatsim.geometry.segment_table import SegmentTable

SEGMENT_SAMPLES = 17  # points along each output segment checked besides the analytic candidates
SWITCH_STEPS = 40  # bisection steps for a switch point on an edge (2^-40 of a grid step)
CERTIFY_SLACK = 1e-9  # the polysegment -> polyline part is certified to this fraction of (1 + its value)


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
    return distance_per_point(PolysegmentIndex(SegmentTable.of(poly)), np.asarray(points, dtype=float).reshape(-1, 2))


def hausdorff(polyline: np.ndarray, poly: Polysegment) -> Deviation:
    """Exact two-sided Hausdorff distance between ``polyline`` (n, 2), n >= 2, and ``poly``."""
    verts = np.asarray(polyline, dtype=float)
    if verts.ndim != 2 or verts.shape[1] != 2 or len(verts) < 2:
        raise ValueError(f"hausdorff needs a polyline of at least two points, got shape {verts.shape}")
    table = SegmentTable.of(poly)
    segments = PolysegmentIndex(table)
    d_vert, seg_of, foot, where = segments.nearest(verts)
    edges = PolylineIndex(verts)
    d_in = max_distance(segments, verts, d_vert, bounded=True)
    d_in = _edge_interiors(edges, d_vert, d_in, segments)
    d_out = _to_polyline(edges, table, d_vert, seg_of, foot, where)
    return Deviation(d_in, d_out)


# ---------------------------------------------------------------- polyline -> polysegment


class _Envelope:
    """Distance to the polysegment for points on a set of edges, over the segments that can
    be nearest anywhere on each edge (a superset, so the minimum is exact)."""

    def __init__(self, segments: PolysegmentIndex, centre: np.ndarray, radius: np.ndarray):
        self.table = segments.table
        m = len(self.table)
        row, seg = segments.samples.within(centre, radius)
        key = np.unique(row * m + seg)
        self.row, self.seg = key // m, key % m
        self.ptr = np.searchsorted(self.row, np.arange(len(centre) + 1))

    def __call__(self, points: np.ndarray, row: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(distance, nearest segment) of points[i] lying on edge ``row[i]``."""
        which, pair = expand_ranges(self.ptr[row], self.ptr[row + 1])
        seg = self.seg[pair]
        d = self.table.distance(points[which], seg)[0]
        order = np.lexsort((d, which))
        first = order[np.searchsorted(which[order], np.arange(len(points)))]
        return d[first], seg[first]


def _edge_interiors(edges: PolylineIndex, upper: np.ndarray, best: float, segments: PolysegmentIndex) -> float:
    """Largest distance inside the edges that can still exceed ``best``."""
    reach = (upper[:-1] + upper[1:] + edges.length) / 2
    edge = np.flatnonzero(reach > best)
    if not len(edge):
        return best
    verts = edges.vertices
    a, ab, length, reach = verts[edge], verts[edge + 1] - verts[edge], edges.length[edge], reach[edge]
    envelope = _Envelope(segments, a + ab / 2, reach + length / 2)
    table = envelope.table

    def at(row: np.ndarray, u: np.ndarray) -> np.ndarray:
        return a[row] + u[:, None] * ab[row]

    # a grid along every edge (finer along long edges) locates the switches of the nearest segment
    n_grid = np.clip(np.ceil(length / max(edges.median, 1e-300)).astype(np.int64) + 1, 9, 200)
    row, k = expand_ranges(np.zeros(len(edge), dtype=np.int64), n_grid)
    u = k / (n_grid[row] - 1)
    d_grid, nearest = envelope(at(row, u), row)
    best = max(best, float(d_grid.max()))
    cand_row, cand_u = [], []
    switch = np.flatnonzero((row[1:] == row[:-1]) & (nearest[1:] != nearest[:-1]))
    if len(switch):
        r, j1, j2 = row[switch], nearest[switch], nearest[switch + 1]
        lo, hi = u[switch], u[switch + 1]
        for _ in range(SWITCH_STEPS):  # d1 - d2 goes from <= 0 at lo to >= 0 at hi
            mid = (lo + hi) / 2
            x = at(r, mid)
            right = table.distance(x, j1)[0] > table.distance(x, j2)[0]
            hi, lo = np.where(right, mid, hi), np.where(right, lo, mid)
        cand_row.append(r)
        cand_u.append((lo + hi) / 2)
    # maxima of the distance to one arc: under its centre, and where its two ends are equally far
    arc = table.kappa[envelope.seg] != 0
    r, j = envelope.row[arc], envelope.seg[arc]
    den = np.einsum("ij,ij->i", ab[r], ab[r])
    cand_row.append(r)
    cand_u.append(np.einsum("ij,ij->i", table.centre(j) - a[r], ab[r]) / den)
    chord = table.end[j] - table.start[j]
    along = np.einsum("ij,ij->i", ab[r], chord)
    cand_row.append(r)
    with np.errstate(divide="ignore", invalid="ignore"):
        cand_u.append(np.einsum("ij,ij->i", (table.start[j] + table.end[j]) / 2 - a[r], chord) / along)
    r, u = np.concatenate(cand_row), np.concatenate(cand_u)
    inside = (u > 0) & (u < 1)
    if inside.any():
        best = max(best, float(envelope(at(r[inside], u[inside]), r[inside])[0].max()))
    return best


# ---------------------------------------------------------------- polysegment -> polyline


def _to_polyline(edges: PolylineIndex, table: SegmentTable, d_vert: np.ndarray, seg_of: np.ndarray,
                 foot: np.ndarray, where: np.ndarray) -> float:
    """Largest distance from the polysegment to the polyline: exact at the candidate points,
    then certified along the polysegment between them (coatsim.geometry.certify)."""
    verts, m = edges.vertices, len(table)
    offset = np.concatenate(([0.0], np.cumsum(table.length)))
    # segment ends and points along every segment (more along one no vertex is nearest to)
    owned = np.bincount(seg_of, minlength=m) > 0
    count = np.where(owned, SEGMENT_SAMPLES, 4 * SEGMENT_SAMPLES)
    seg, k = expand_ranges(np.zeros(m, dtype=np.int64), count)
    s = k / (count[seg] - 1) * table.length[seg]
    fixed = np.vstack((table.start, table.end[-1:], table.point_at(seg, s)))
    fixed_at = np.concatenate((offset, offset[seg] + s))
    fixed_up = edges.bound(fixed)[0]
    best = max_distance(edges, fixed, fixed_up, bounded=True)
    # the foot of every vertex: within the vertex's own distance of the polyline
    best = max_distance(edges, foot, d_vert, best)
    position = offset[seg_of] + table.along(foot, seg_of)
    points, upper = _tangent_points(edges, table, seg_of, position, d_vert)
    best = max_distance(edges, points, upper, best)
    points, upper = _bisector_points(verts, table, seg_of, where, _stretch_bound(position, d_vert) > best)
    best = max_distance(edges, points, upper, best)
    return certify(table, edges, np.concatenate((fixed_at, position)), np.concatenate((fixed_up, d_vert)),
                   best, CERTIFY_SLACK * (1 + best))


def _stretch_bound(position: np.ndarray, d_vert: np.ndarray) -> np.ndarray:
    """Per vertex, a bound on the distance to the polyline of the polysegment between the
    feet of the vertex's neighbours (at arc lengths ``position`` along the polysegment; the
    distance is 1-Lipschitz along it and the feet are within the vertices' distances of the
    polyline). Large where the polyline does not follow the polysegment in order, so those
    vertices are never left out."""
    pair = (d_vert[:-1] + d_vert[1:] + np.abs(np.diff(position))) / 2
    return np.maximum(np.r_[pair[:1], pair], np.r_[pair, pair[-1:]])


def _tangent_points(edges: PolylineIndex, table: SegmentTable, seg_of: np.ndarray, position: np.ndarray,
                    d_vert: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Points of the arcs nearest to an edge's ends whose tangent is parallel (or opposite)
    to the edge and that lie across from it (where the distance to the edge's interior can
    peak), with their distance to that edge as a bound."""
    verts = edges.vertices
    ab = np.diff(verts, axis=0)
    heading = np.arctan2(ab[:, 1], ab[:, 0])
    edge = np.arange(len(ab))
    first, second = seg_of[:-1], seg_of[1:]
    e = np.concatenate((edge, edge[second != first]))
    j = np.concatenate((first, second[second != first]))
    arc = table.kappa[j] != 0
    e, j = e[arc], j[arc]
    offset = np.concatenate(([0.0], np.cumsum(table.length)))[j]
    # across from the edge: near the feet of its ends (give or take its length and distance)
    slack = edges.length[e] + np.abs(position[e + 1] - position[e]) + d_vert[e] + d_vert[e + 1]
    lo = np.minimum(position[e], position[e + 1]) - offset - slack
    hi = np.maximum(position[e], position[e + 1]) - offset + slack
    kappa = table.kappa[j]
    pts, upper = [], []
    for flip in (0.0, np.pi):
        s = np.mod(np.sign(kappa) * (heading[e] + flip - table.heading[j]), 2 * np.pi) / np.abs(kappa)
        near = np.flatnonzero((s <= table.length[j]) & (s >= lo) & (s <= hi))
        y = table.point_at(j[near], s[near])
        a, d = verts[e[near]], ab[e[near]]
        u = np.einsum("ij,ij->i", y - a, d) / np.einsum("ij,ij->i", d, d)
        ok = (u >= 0) & (u <= 1)
        pts.append(y[ok])
        upper.append(edge_distance(y[ok], verts, e[near][ok]))
    return np.vstack(pts), np.concatenate(upper)


def _bisector_points(verts: np.ndarray, table: SegmentTable, seg_of: np.ndarray, where: np.ndarray,
                     wanted: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Where the angle bisector of every ``wanted`` inner vertex crosses the vertex's nearest
    segment (and the neighbouring one where that nearest point is a segment end): the points
    equally near to the vertex's two edges, bounded by their distance to the first edge."""
    closed = len(verts) > 3 and np.array_equal(verts[0], verts[-1])
    v = np.arange(len(verts) - 1) if closed else np.arange(1, len(verts) - 1)
    v = v[wanted[v] | (where[v] != 0)]
    prev = np.where(v == 0, len(verts) - 2, v - 1)
    u1, u2 = verts[prev] - verts[v], verts[v + 1] - verts[v]
    n1, n2 = np.hypot(u1[:, 0], u1[:, 1]), np.hypot(u2[:, 0], u2[:, 1])
    turning = (n1 > 0) & (n2 > 0)  # a repeated vertex has no bisector
    if not turning.any():
        return np.zeros((0, 2)), np.zeros(0)
    v, prev = v[turning], prev[turning]
    u1, u2 = u1[turning] / n1[turning, None], u2[turning] / n2[turning, None]
    plus, minus = u1 + u2, u2 - u1
    across = np.column_stack((-minus[:, 1], minus[:, 0]))
    direction = np.where((np.hypot(*plus.T) > np.hypot(*across.T))[:, None], plus, across)
    direction /= np.hypot(direction[:, 0], direction[:, 1])[:, None]
    j = seg_of[v]
    rows = [np.arange(len(v))]
    segs = [j]
    at_end = where[v] != 0
    for step in (-1, 1):
        other = table.neighbour(j[at_end], step)
        ok = other >= 0
        rows.append(np.flatnonzero(at_end)[ok])
        segs.append(other[ok])
    r, j = np.concatenate(rows), np.concatenate(segs)
    pts, valid = table.line_crossings(verts[v[r]], direction[r], j)
    pts, j2 = pts[valid], np.concatenate((j, j))[valid]
    on = table.distance(pts, j2)[1]
    edge_before = np.concatenate((prev[r], prev[r]))[valid]
    return on, edge_distance(on, verts, edge_before)
