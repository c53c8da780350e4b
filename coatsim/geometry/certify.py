"""Certify the largest distance from a polysegment to a polyline between sample points.

Between two points of one segment at arc lengths a < b, the distance to the polyline is at
most (Ua + Ub + b − a) / 2 (it is 1-Lipschitz along the segment; Ua, Ub bound it at the
ends), and at most the largest distance over the stretch to the polyline edge nearest to
either end; that one is found in closed form: the distance to a fixed edge peaks along a
segment only at the stretch's ends, where the segment runs parallel to the edge, or on the
line through an edge end and the arc's centre. Stretches whose bound exceeds the maximum
found by more than ``slack`` are halved and their middle point measured, until none is left.
The maximum is then exact at the points measured and no point of the polysegment is farther
from the polyline than maximum + slack.
"""

from __future__ import annotations

import numpy as np

from coatsim.geometry.nearest import PolylineIndex, edge_distance
from coatsim.geometry.segment_table import SegmentTable

MAX_HALVINGS = 64


class Stretches:
    """Stretches [a, b] of arc length along the polysegment, each within one segment, with
    upper bounds and nearest polyline edges (-1 if unknown) at both ends."""

    def __init__(self, table: SegmentTable, edges: PolylineIndex):
        self.table, self.edges = table, edges
        self.offset = np.concatenate(([0.0], np.cumsum(table.length)))

    def locate(self, position: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(segment, arc length along it) of global arc lengths."""
        t = self.table
        seg = np.clip(np.searchsorted(self.offset, position, side="right") - 1, 0, len(t) - 1)
        return seg, np.clip(position - self.offset[seg], 0.0, t.length[seg])

    def edge_bound(self, seg: np.ndarray, s_a: np.ndarray, s_b: np.ndarray, edge: np.ndarray) -> np.ndarray:
        """Largest distance to polyline edge ``edge`` over [s_a, s_b] of segment ``seg``."""
        t, verts = self.table, self.edges.vertices
        out = np.full(len(seg), np.inf)
        known = np.flatnonzero(edge >= 0)
        if not len(known):
            return out
        j, a, b, e = seg[known], s_a[known], s_b[known], edge[known]
        where = [a, b]
        arc = t.kappa[j] != 0
        k = np.where(arc, t.kappa[j], 1.0)
        p0, p1 = verts[e], verts[e + 1]
        along_e = np.arctan2(p1[:, 1] - p0[:, 1], p1[:, 0] - p0[:, 0])
        centre = t.start[j] + (1.0 / k)[:, None] * np.column_stack((-np.sin(t.heading[j]), np.cos(t.heading[j])))
        for heading in (along_e, along_e + np.pi):  # tangent parallel to the edge
            where.append(np.mod(np.sign(k) * (heading - t.heading[j]), 2 * np.pi) / np.abs(k))
        for p in (p0, p1):  # on the line through an edge end and the centre
            polar = np.arctan2(p[:, 1] - centre[:, 1], p[:, 0] - centre[:, 0])
            turn = np.mod(np.sign(k) * (polar + np.sign(k) * np.pi / 2 - t.heading[j]), 2 * np.pi)
            where += [turn / np.abs(k), np.mod(turn + np.pi, 2 * np.pi) / np.abs(k)]
        best = np.zeros(len(j))
        for n, s in enumerate(where):
            inside = (s >= a) & (s <= b) & (arc | (n < 2))  # a line: the ends only (its distance is convex)
            if inside.any():
                y = t.point_at(j[inside], s[inside])
                best[inside] = np.maximum(best[inside], edge_distance(y, verts, e[inside]))
        out[known] = best
        return out

    def bound(self, a_pos, b_pos, a_up, b_up, a_edge, b_edge) -> np.ndarray:
        seg, _ = self.locate((a_pos + b_pos) / 2)
        s_a, s_b = a_pos - self.offset[seg], b_pos - self.offset[seg]
        lipschitz = (a_up + b_up + (b_pos - a_pos)) / 2
        return np.minimum(lipschitz, np.minimum(self.edge_bound(seg, s_a, s_b, a_edge),
                                                self.edge_bound(seg, s_a, s_b, b_edge)))

    def points(self, position: np.ndarray) -> np.ndarray:
        seg, s = self.locate(position)
        return self.table.point_at(seg, s)


def certify(table: SegmentTable, edges: PolylineIndex, position: np.ndarray, upper: np.ndarray,
            best: float, slack: float) -> float:
    """Largest distance from the polysegment to the polyline, given points at arc lengths
    ``position`` (any order; every segment start and the end included) with upper bounds
    ``upper`` on their distances and the largest exact distance ``best`` found so far."""
    st = Stretches(table, edges)
    order = np.argsort(position, kind="stable")
    pos, up = position[order], upper[order]
    edge = np.full(len(pos), -1)
    if table.closed:  # the stretch across the seam ends at the start, one length on
        pos, up, edge = np.r_[pos, st.offset[-1]], np.r_[up, up[0]], np.r_[edge, -1]

    def measure(points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Bounds and nearest edges of points, exact where the bound is in doubt."""
        nonlocal best
        d, e, _ = edges.bound(points)
        doubt = np.flatnonzero(d > best + slack)
        if len(doubt):
            d[doubt], e[doubt], _ = edges.exact(points[doubt], d[doubt])
            best = max(best, float(d[doubt].max()))
        return d, e

    # first tighter bounds and nearest edges at the ends of the stretches in doubt
    live = np.flatnonzero((up[:-1] + up[1:] + np.diff(pos)) / 2 > best + slack)
    ends = np.unique(np.r_[live, live + 1])
    d, e = measure(st.points(np.mod(pos[ends], st.offset[-1]) if table.closed else pos[ends]))
    up[ends], edge[ends] = np.minimum(up[ends], d), e
    a_pos, b_pos, a_up, b_up, a_edge, b_edge = pos[live], pos[live + 1], up[live], up[live + 1], edge[live], edge[live + 1]
    limit = 4 * len(pos) + 10_000
    for _ in range(MAX_HALVINGS):
        keep = np.flatnonzero(st.bound(a_pos, b_pos, a_up, b_up, a_edge, b_edge) > best + slack)
        if not len(keep) or len(keep) > limit:
            break
        a_pos, b_pos, a_up, b_up, a_edge, b_edge = (x[keep] for x in (a_pos, b_pos, a_up, b_up, a_edge, b_edge))
        m_pos = (a_pos + b_pos) / 2
        m_up, m_edge = measure(st.points(np.mod(m_pos, st.offset[-1]) if table.closed else m_pos))
        a_pos, b_pos = np.r_[a_pos, m_pos], np.r_[m_pos, b_pos]
        a_up, b_up = np.r_[a_up, m_up], np.r_[m_up, b_up]
        a_edge, b_edge = np.r_[a_edge, m_edge], np.r_[m_edge, b_edge]
    return best
