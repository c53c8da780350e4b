"""Level sets of a scalar field on a triangle mesh (marching triangles), as curves on the surface.

A field given at the vertices is linear on each triangle, so its level set crosses a triangle in
one straight segment between two edge points. A vertex exactly at the level counts as above it.
On a consistently oriented mesh every segment is directed with the higher values on its left
(seen from the side the normals point to), so the segments chain into polylines with one
successor per point; a polyline that returns to its start is a closed loop. Where a mesh is
non-manifold or not orientable a point may get two successors: the segment of the lower face id
is kept, and the polyline breaks there.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from coatsim.geometry.surface.topology import unique_pairs

#: consecutive points of a level curve closer than this fraction of its extent are one point
DUPLICATE_FRACTION = 1e-8


@dataclass(frozen=True, eq=False)
class SurfaceCurve:
    """A polyline on a mesh: points (n, 3) mm, the face each point lies in (n,) with its
    barycentric weights there (n, 3); a closed loop does not repeat its first point."""

    points: np.ndarray
    faces: np.ndarray
    bary: np.ndarray
    closed: bool

    @property
    def length_mm(self) -> float:
        pts = np.vstack([self.points, self.points[:1]]) if self.closed else self.points
        return float(np.linalg.norm(np.diff(pts, axis=0), axis=1).sum())

    def sample(self, mesh_faces: np.ndarray, values: np.ndarray) -> np.ndarray:
        """Per-vertex ``values`` (n_vertices, ...) interpolated at the points (a corner of zero
        weight does not count, even where its value is infinite)."""
        corner = values[mesh_faces[self.faces]]  # (n, 3, ...)
        weights = self.bary.reshape(self.bary.shape + (1,) * (corner.ndim - 2))
        weighted = np.zeros(np.broadcast_shapes(weights.shape, corner.shape))
        np.multiply(weights, corner, out=weighted, where=weights != 0)
        return weighted.sum(axis=1)

    def take(self, index: np.ndarray, closed: bool | None = None) -> SurfaceCurve:
        """The points ``index`` (in that order) as a new curve."""
        return SurfaceCurve(self.points[index], self.faces[index], self.bary[index],
                            self.closed if closed is None else closed)

    def reversed(self) -> SurfaceCurve:
        return self.take(np.arange(len(self.points))[::-1])

    def rolled(self, start: int) -> SurfaceCurve:
        """A closed loop starting at point ``start``."""
        return self.take(np.roll(np.arange(len(self.points)), -start))


def crossings(faces: np.ndarray, field: np.ndarray, level: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Directed segments of the level set: (faces crossed, from-edge (S, 2), to-edge (S, 2))."""
    above = field >= level
    corner = above[faces]
    n_above = corner.sum(axis=1)
    crossed = np.flatnonzero((n_above == 1) | (n_above == 2))
    corner = corner[crossed]
    lonely_above = n_above[crossed] == 1
    k = np.where(lonely_above, np.argmax(corner, axis=1), np.argmin(corner, axis=1))
    tri = faces[crossed]
    rows = np.arange(len(crossed))
    lone, nxt, prv = tri[rows, k], tri[rows, (k + 1) % 3], tri[rows, (k + 2) % 3]
    edge_lp = np.column_stack([lone, nxt])
    edge_ql = np.column_stack([prv, lone])
    # higher values on the left: from L-P to Q-L when L is above, the other way round otherwise
    start = np.where(lonely_above[:, None], edge_lp, edge_ql)
    end = np.where(lonely_above[:, None], edge_ql, edge_lp)
    return crossed, start, end


def edge_points(vertices: np.ndarray, field: np.ndarray, level: float,
                edges: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Where the level crosses each edge (E, 2) sorted: (points (E, 3), parameter t from the
    first vertex)."""
    s0, s1 = field[edges[:, 0]] - level, field[edges[:, 1]] - level
    t = np.clip(s0 / (s0 - s1), 0.0, 1.0)
    return vertices[edges[:, 0]] + t[:, None] * (vertices[edges[:, 1]] - vertices[edges[:, 0]]), t


def crossing_edges(faces: np.ndarray, field: np.ndarray, level: float) -> np.ndarray:
    """Every edge the level set crosses, unordered (E, 2) sorted: for quick criteria."""
    _, start, end = crossings(faces, field, level)
    return unique_pairs(np.concatenate([start, end]))[0]


def level_curves(vertices: np.ndarray, faces: np.ndarray, field: np.ndarray, level: float) -> list[SurfaceCurve]:
    """The level set ``field == level`` as polylines, each with the higher values on its left."""
    crossed, start, end = crossings(faces, field, level)
    if not len(crossed):
        return []
    n_seg = len(crossed)
    keys, node = unique_pairs(np.concatenate([start, end]))
    a, b = node[:n_seg], node[n_seg:]
    succ = np.full(len(keys), -1)
    seg = np.full(len(keys), -1)
    _, first = np.unique(a, return_index=True)  # segments come in face order: the lowest face wins
    succ[a[first]], seg[a[first]] = b[first], first
    pred = np.full(len(keys), -1)
    linked = np.flatnonzero(succ >= 0)
    _, first_in = np.unique(succ[linked], return_index=True)
    pred[succ[linked[first_in]]] = linked[first_in]
    points, t = edge_points(vertices, field, level, keys)
    curves = []
    for chain, closed in _chains(succ.tolist(), pred.tolist()):
        chain = np.asarray(chain)
        seg_face = crossed[seg[chain[:-1]]] if not closed else crossed[seg[chain]]
        point_face = seg_face if closed else np.append(seg_face, seg_face[-1])
        curve = _curve(points[chain], keys[chain], t[chain], faces, point_face, closed)
        if curve is not None:
            curves.append(curve)
    return curves


def _chains(succ: list[int], pred: list[int]):
    """Walk the successor links: open chains from their starts, then the loops left over."""
    visited = [False] * len(succ)
    starts = [i for i in range(len(succ)) if pred[i] < 0 and succ[i] >= 0]
    for start in starts:
        chain, node = [start], start
        visited[start] = True
        while succ[node] >= 0:
            node = succ[node]
            chain.append(node)
            if visited[node]:
                break
            visited[node] = True
        yield chain, False
    for start in range(len(succ)):
        if visited[start] or succ[start] < 0:
            continue
        chain, node = [start], start
        visited[start] = True
        while succ[node] >= 0 and not visited[succ[node]]:
            node = succ[node]
            visited[node] = True
            chain.append(node)
        yield chain, succ[node] == start


def _curve(points: np.ndarray, edges: np.ndarray, t: np.ndarray, faces: np.ndarray, point_face: np.ndarray,
           closed: bool) -> SurfaceCurve | None:
    """A curve from edge points, with consecutive points closer than DUPLICATE_FRACTION of its
    extent merged (a level through or next to a vertex); None when fewer than two remain."""
    bary = np.zeros((len(points), 3))
    tri = faces[point_face]
    bary += (tri == edges[:, :1]) * (1.0 - t)[:, None]
    bary += (tri == edges[:, 1:]) * t[:, None]
    step = np.linalg.norm(np.diff(points, axis=0), axis=1)
    scale = max(float(np.ptp(points, axis=0).max()), 1e-300)
    keep = np.r_[True, step > DUPLICATE_FRACTION * scale]
    if closed and keep.sum() > 1 and np.linalg.norm(points[-1] - points[0]) <= DUPLICATE_FRACTION * scale:
        keep[-1] = False
    if keep.sum() < 2:
        return None
    return SurfaceCurve(points[keep], point_face[keep], bary[keep], bool(closed and keep.sum() > 2))
