"""Geodesic distance on a triangle mesh, and the levels at which passes follow a distance field.

Two solvers, both from potpourri3d (geometry-central):
- the heat method (Crane et al.), the discrete-exterior-calculus solve the seed's authors use:
  heat flows from the sources for a time t = (mean edge length)^2, its normalised gradient is
  integrated back by one Poisson solve. It is smooth but first-order: on the meshes ``plan``
  builds (edges up to 1/6 of the spacing) its error is about half an edge inside the part and
  grows to 2-3 edges along open borders, where only the natural (Neumann) condition holds and
  the level sets bend to meet the border at right angles (tests/geometry/surface measure both).
- fast marching, which takes sources anywhere on a face and is used to measure: the gap
  between passes, the distance from the region's border (edge band, boundary passes) and the
  coverage. It is also first-order (about a tenth of an edge near a source on the meshes
  ``plan`` builds, more far away and where wave fronts from a source's ends meet a border).
"""

from __future__ import annotations

import math
from typing import Sequence

import numpy as np

from coatsim.geometry.surface.contours import SurfaceCurve

#: the heat method's time step in units of the mean edge length squared (geometry-central's default)
HEAT_TIME_COEFFICIENT = 1.0


def heat_distance(vertices: np.ndarray, faces: np.ndarray, sources: np.ndarray) -> np.ndarray:
    """Heat-method geodesic distance (mm) from the vertices ``sources`` to every vertex."""
    import potpourri3d as pp3d

    solver = pp3d.MeshHeatMethodDistanceSolver(vertices, faces, t_coef=HEAT_TIME_COEFFICIENT, use_robust=True)
    distance = np.asarray(solver.compute_distance_multisource([int(v) for v in sources]), dtype=float)
    return np.maximum(distance, 0.0)


def marching_distance(vertices: np.ndarray, faces: np.ndarray, curves: Sequence[SurfaceCurve] = (),
                      source_vertices: np.ndarray | None = None) -> np.ndarray:
    """Fast-marching geodesic distance (mm) from points on faces (the points of ``curves``, in
    faces of this mesh) and from the vertices ``source_vertices``; inf where no source reaches."""
    import potpourri3d as pp3d

    sources = [[(int(f), [float(w[0]), float(w[1])]) for f, w in zip(c.faces, c.bary)] for c in curves if len(c.faces)]
    if source_vertices is not None and len(source_vertices):
        sources.append([(int(v), []) for v in source_vertices])
    if not sources:
        return np.full(len(vertices), np.inf)
    solver = pp3d.MeshFastMarchingDistanceSolver(vertices, faces)
    distance = np.asarray(solver.compute_distance(sources, [], False), dtype=float)
    reached = _reached(faces, len(vertices), curves, source_vertices)
    distance[~reached] = np.inf
    return distance


def _reached(faces: np.ndarray, n_vertices: int, curves: Sequence[SurfaceCurve],
             source_vertices: np.ndarray | None) -> np.ndarray:
    """Vertices connected to a source (fast marching leaves the others at an arbitrary value)."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    rows = np.concatenate([faces[:, 0], faces[:, 1]])
    cols = np.concatenate([faces[:, 1], faces[:, 2]])
    _, label = connected_components(coo_matrix((np.ones(len(rows)), (rows, cols)), shape=(n_vertices,) * 2),
                                    directed=False)
    seeds = [faces[c.faces[:1], 0] for c in curves if len(c.faces)]
    if source_vertices is not None:
        seeds.append(np.asarray(source_vertices, dtype=np.int64))
    hit = np.unique(label[np.concatenate(seeds)]) if seeds else np.zeros(0, dtype=np.int64)
    return np.isin(label, hit)


def distance_levels(low: float, high: float, first: float, spacing: float) -> np.ndarray:
    """Levels of a distance field for passes ``spacing`` apart, starting at ``first``, over the
    values [low, high] the coated area takes: every level first + k*spacing inside, and where
    more than half a spacing is left beyond the outermost one, one more level half a spacing in
    from that end (so that every point is within half a spacing of a pass)."""
    if not (math.isfinite(low) and math.isfinite(high)) or high < low:
        return np.zeros(0)
    k_lo, k_hi = math.ceil((low - first) / spacing - 1e-9), math.floor((high - first) / spacing + 1e-9)
    levels = first + spacing * np.arange(k_lo, k_hi + 1)
    levels = levels[(levels > low) & (levels < high)] if len(levels) else levels
    if not len(levels):
        return np.array([0.5 * (low + high)])
    if levels[0] - low > 0.5 * spacing * (1 + 1e-9):
        levels = np.r_[low + 0.5 * spacing, levels]
    if high - levels[-1] > 0.5 * spacing * (1 + 1e-9):
        levels = np.r_[levels, high - 0.5 * spacing]
    return levels


#: the arc estimate stands unless fast marching finds the way along the surface longer by this
#: fraction of the spacing (a sharp edge, a slot between the two points)
ARC_GUARD_FRACTION = 0.15


def arc_length(chord: np.ndarray, normal_a: np.ndarray, normal_b: np.ndarray) -> np.ndarray:
    """Length of the circular arc with chord vectors ``chord`` (k, 3) whose end normals are
    ``normal_a`` and ``normal_b``: |c| (t/2) / sin(t/2) for the angle t between the normals
    (exact on a plane, a cylinder and a sphere)."""
    cos = np.clip(np.einsum("ij,ij->i", normal_a, normal_b), -1.0, 1.0)
    half = 0.5 * np.arccos(cos)
    ratio = np.where(half > 1e-8, half / np.maximum(np.sin(half), 1e-300), 1.0)
    return np.linalg.norm(chord, axis=1) * ratio


class NearestOnCurves:
    """Nearest points on a set of polylines (with unit normals at their points), for the
    distance along the surface from a curve over short ranges."""

    def __init__(self, curves: Sequence[tuple[np.ndarray, np.ndarray, bool]]):
        from scipy.spatial import cKDTree

        self.points = np.concatenate([p for p, _, _ in curves]) if curves else np.zeros((0, 3))
        self.normals = np.concatenate([n for _, n, _ in curves]) if curves else np.zeros((0, 3))
        nxt, prv, end = [], [], []
        offset = 0
        for points, _, closed in curves:
            k = np.arange(len(points)) + offset
            nxt.append(np.roll(k, -1) if closed else np.r_[k[1:], -1])
            prv.append(np.roll(k, 1) if closed else np.r_[-1, k[:-1]])
            end.append(np.zeros(len(k), dtype=bool) if closed else np.isin(k, [k[0], k[-1]]))
            offset += len(points)
        self.next = np.concatenate(nxt) if curves else np.zeros(0, dtype=np.int64)
        self.prev = np.concatenate(prv) if curves else np.zeros(0, dtype=np.int64)
        self.end = np.concatenate(end) if curves else np.zeros(0, dtype=bool)
        self.tree = cKDTree(self.points) if len(self.points) else None

    def query(self, points: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """For each point: the nearest point on the curves (k, 3), the normal there (k, 3), and
        whether it is an open end of its curve (k,)."""
        i = self.tree.query(points)[1]
        foot, normal, best = self.points[i].copy(), self.normals[i].copy(), np.linalg.norm(points - self.points[i], axis=1)
        on_end = self.end[i].copy()
        for other in (self.prev[i], self.next[i]):
            ok = other >= 0
            a, b = self.points[i[ok]], self.points[other[ok]]
            ab = b - a
            s = np.clip(np.einsum("ij,ij->i", points[ok] - a, ab) / np.maximum(np.einsum("ij,ij->i", ab, ab), 1e-300),
                        0.0, 1.0)
            candidate = a + s[:, None] * ab
            d = np.linalg.norm(points[ok] - candidate, axis=1)
            better = d < best[ok]
            rows = np.flatnonzero(ok)[better]
            foot[rows], best[rows] = candidate[better], d[better]
            n = self.normals[i[ok]] + s[:, None] * (self.normals[other[ok]] - self.normals[i[ok]])
            normal[rows] = n[better] / np.linalg.norm(n[better], axis=1)[:, None]
            on_end[rows] = False
        return foot, normal, on_end

    def distance(self, points: np.ndarray, normals: np.ndarray, marching: np.ndarray,
                 spacing_mm: float) -> tuple[np.ndarray, np.ndarray]:
        """Distance along the surface from each point (with its unit normal) to the curves: the
        arc through the nearest curve point, or fast marching's ``marching`` value where that is
        longer by more than ARC_GUARD_FRACTION spacings; and whether the nearest is an open end."""
        if self.tree is None or not len(points):
            return np.full(len(points), np.inf), np.zeros(len(points), dtype=bool)
        foot, foot_normal, on_end = self.query(points)
        arc = arc_length(points - foot, normals, foot_normal)
        longer = np.isfinite(marching) & (marching > arc + ARC_GUARD_FRACTION * spacing_mm)
        reached = np.isfinite(marching)
        return np.where(longer, marching, np.where(reached, arc, np.inf)), on_end
