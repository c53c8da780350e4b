"""Geodesic distance on a triangle mesh, and the levels at which passes follow a distance field.

Two solvers:
- the heat method (Crane, Weischedel, Wardetzky), the discrete-exterior-calculus solve the seed's
  authors use: heat flows from the start for a time t = (mean edge length)^2, its normalised
  gradient is integrated back by one Poisson solve, here with the distance held at the
  vertices next to the start (zero on a border; the arc to a start curve or point that runs
  between vertices). (The operators are potpourri3d's; its own solver instead shifts a free
  Poisson solution to zero at its source vertices, and with a start of several curves, such as
  a border with a hole, the values on the start then differ by up to two edge lengths, so
  passes near it shift by as much.) It
  is first-order: on the meshes ``plan`` builds (edges up to a quarter of the spacing) its error
  is a few tenths of an edge inside the region and grows toward open borders that are not part
  of the start, where only the natural (Neumann) condition holds and the level sets bend to
  meet the border at right angles; it also rounds the distance's ridges (tests and
  scripts/bench_plan.py measure both against exact distances).
- fast marching (potpourri3d), which takes sources anywhere on a face: the distance from the
  region's border (edge band, boundary passes), and the distance between passes where the arc
  estimate below does not hold (across a sharp edge or a slot). It too is first-order, and
  worst on irregular meshes and where a start's ends meet a border (an edge length or two).
"""

from __future__ import annotations

import math
from typing import Callable, Sequence

import numpy as np

from coatsim.geometry.surface.boxes import SmallTriangles
from coatsim.geometry.surface.contours import SurfaceCurve
from coatsim.geometry.surface.topology import manifold_split

#: the heat method's time step in units of the mean edge length squared (geometry-central's default)
HEAT_TIME_COEFFICIENT = 1.0


def heat_distance(vertices: np.ndarray, faces: np.ndarray, sources: np.ndarray, values: np.ndarray | None = None,
                  weights: np.ndarray | None = None) -> np.ndarray:
    """Heat-method geodesic distance (mm) to every vertex of a connected mesh from a start known
    at the vertices ``sources`` (its distance there: ``values``, zero by default): (M + t L) u =
    delta (the start's heat at the sources: ``weights``, one by default), X = -grad u / |grad u|,
    L phi = -div X with phi held at the sources (cotangent Laplacian L and lumped masses M from
    potpourri3d)."""
    import potpourri3d as pp3d
    from scipy.sparse import diags
    from scipy.sparse.linalg import splu

    laplacian = pp3d.cotan_laplacian(vertices, faces, denom_eps=1e-12).tocsr()
    mass = pp3d.vertex_areas(vertices, faces)
    lengths = np.linalg.norm(vertices[faces] - vertices[np.roll(faces, 1, axis=1)], axis=2)
    t = HEAT_TIME_COEFFICIENT * float(lengths.mean()) ** 2
    delta = np.zeros(len(vertices))
    delta[sources] = 1.0 if weights is None else weights
    heat = splu((diags(mass) + t * laplacian).tocsc(), permc_spec="COLAMD").solve(delta)
    divergence = _divergence(vertices, faces, _unit_descent(vertices, faces, heat))
    free = np.ones(len(vertices), dtype=bool)
    free[sources] = False
    held = np.zeros(len(sources)) if values is None else np.asarray(values, dtype=float)
    # a tiny mass term keeps the system definite should a piece hold no source
    system = (laplacian[free][:, free] + diags(1e-12 * mass[free] / t)).tocsc()
    distance = np.zeros(len(vertices))
    distance[sources] = held
    distance[free] = splu(system, permc_spec="COLAMD").solve(-divergence[free] - laplacian[free][:, sources] @ held)
    return np.maximum(distance, 0.0)


def _unit_descent(vertices: np.ndarray, faces: np.ndarray, u: np.ndarray) -> np.ndarray:
    """-grad u / |grad u| per face (m, 3) for u linear on each face."""
    a, b, c = (vertices[faces[:, k]] for k in range(3))
    normal = np.cross(b - a, c - a)
    double_area = np.maximum(np.linalg.norm(normal, axis=1), 1e-300)
    unit = normal / double_area[:, None]
    gradient = sum(u[faces[:, k]][:, None] * np.cross(unit, edge)
                   for k, edge in enumerate((c - b, a - c, b - a))) / double_area[:, None]
    return -gradient / np.maximum(np.linalg.norm(gradient, axis=1), 1e-300)[:, None]


def _divergence(vertices: np.ndarray, faces: np.ndarray, field: np.ndarray) -> np.ndarray:
    """Integrated divergence at the vertices of a per-face vector field: for vertex i of a
    face, (cot(angle at k) (x_j - x_i) + cot(angle at j) (x_k - x_i)) . X / 2."""
    corners = [vertices[faces[:, k]] for k in range(3)]
    cot = []
    for k in range(3):
        p, q, r = corners[k], corners[(k + 1) % 3], corners[(k + 2) % 3]
        e1, e2 = q - p, r - p
        cot.append(np.einsum("ij,ij->i", e1, e2) / np.maximum(np.linalg.norm(np.cross(e1, e2), axis=1), 1e-300))
    total = np.zeros(len(vertices))
    for k in range(3):
        i, j, l_ = k, (k + 1) % 3, (k + 2) % 3
        flux = cot[l_] * np.einsum("ij,ij->i", corners[j] - corners[i], field)
        flux += cot[j] * np.einsum("ij,ij->i", corners[l_] - corners[i], field)
        np.add.at(total, faces[:, i], 0.5 * flux)
    return total


class Marching:
    """Fast-marching geodesic distance on one mesh, built once for many starts. Fast marching
    needs a manifold mesh: bow-tie vertices and non-manifold edges are split first (a split
    vertex gets the smallest distance of its copies)."""

    def __init__(self, vertices: np.ndarray, faces: np.ndarray):
        import potpourri3d as pp3d
        from scipy.sparse import coo_matrix
        from scipy.sparse.csgraph import connected_components

        self.n_vertices = len(vertices)
        self.faces, self.parent = manifold_split(faces)
        self.copy = np.full(len(vertices), -1)
        self.copy[self.parent[::-1]] = np.arange(len(self.parent))[::-1]  # the first copy of each vertex
        self.solver = pp3d.MeshFastMarchingDistanceSolver(vertices[self.parent], self.faces)
        f = self.faces
        rows, cols = np.concatenate([f[:, 0], f[:, 1]]), np.concatenate([f[:, 1], f[:, 2]])
        graph = coo_matrix((np.ones(len(rows)), (rows, cols)), shape=(len(self.parent),) * 2)
        self.label = connected_components(graph, directed=False)[1]

    def distance(self, curves: Sequence[SurfaceCurve] = (), source_vertices: np.ndarray | None = None) -> np.ndarray:
        """Distance (mm) from points on faces (the points of ``curves``, in faces of this mesh)
        and from the vertices ``source_vertices``; inf where no source reaches."""
        sources = [[(int(f), [float(w[0]), float(w[1])]) for f, w in zip(c.faces, c.bary)]
                   for c in curves if len(c.faces)]
        seeds = [self.faces[c.faces[:1], 0] for c in curves if len(c.faces)]
        if source_vertices is not None and len(source_vertices):
            sources.append([(int(self.copy[v]), []) for v in source_vertices])
            seeds.append(self.copy[np.asarray(source_vertices, dtype=np.int64)])
        distance = np.full(self.n_vertices, np.inf)
        if not sources:
            return distance
        value = np.asarray(self.solver.compute_distance(sources, [], False), dtype=float)
        value[~np.isin(self.label, self.label[np.concatenate(seeds)])] = np.inf  # unreached pieces
        np.minimum.at(distance, self.parent, value)
        return distance


def marching_distance(vertices: np.ndarray, faces: np.ndarray, curves: Sequence[SurfaceCurve] = (),
                      source_vertices: np.ndarray | None = None) -> np.ndarray:
    """Fast-marching distance (mm) on a mesh from one start (see Marching)."""
    return Marching(vertices, faces).distance(curves, source_vertices)


def distance_levels(low: float, high: float, first: float, spacing: float) -> np.ndarray:
    """Levels of a distance field for passes ``spacing`` apart, starting at ``first``, over the
    values [low, high] the coated area takes: every level first + k*spacing inside, and where
    more than half a spacing is left beyond the outermost one, one more level half a spacing in
    from that end (so that every point is within half a spacing of a pass); should that level
    come less than half a spacing from its neighbour, the neighbour moves to the middle of its
    own neighbour and the new level (two gaps of 1/2 to 3/4 spacing, no sliver of a pass)."""
    if not (math.isfinite(low) and math.isfinite(high)) or high < low:
        return np.zeros(0)
    k_lo, k_hi = math.ceil((low - first) / spacing - 1e-9), math.floor((high - first) / spacing + 1e-9)
    levels = first + spacing * np.arange(k_lo, k_hi + 1)
    levels = levels[(levels > low) & (levels < high)] if len(levels) else levels
    if not len(levels):
        return np.array([0.5 * (low + high)])
    if high - levels[-1] > 0.5 * spacing * (1 + 1e-9):
        levels = _extended(levels, high - 0.5 * spacing, spacing)
    if levels[0] - low > 0.5 * spacing * (1 + 1e-9):
        levels = -_extended(-levels[::-1], -(low + 0.5 * spacing), spacing)[::-1]
    return levels


def _extended(levels: np.ndarray, end: float, spacing: float) -> np.ndarray:
    """``levels`` (ascending) with ``end`` appended, the last one re-centred if ``end`` is closer
    than half a spacing to it."""
    if end - levels[-1] < 0.5 * spacing and len(levels) > 1:
        levels = np.r_[levels[:-1], 0.5 * (levels[-2] + end)]
    return np.r_[levels, end]


#: the arc estimate stands where its chord's midpoint lies within the arc's sagitta plus this
#: fraction of the chord from the surface (not across a sharp edge or a slot)
ARC_STRAY_FRACTION = 0.1


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
        foot, normal = self.points[i].copy(), self.normals[i].copy()
        best = np.linalg.norm(points - self.points[i], axis=1)
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

    def arc(self, points: np.ndarray, normals: np.ndarray) -> np.ndarray:
        """The arc from each point (with its unit normal) through the nearest curve point: the
        distance along the surface over short ranges (exact on planes, cylinders, spheres)."""
        foot, foot_normal, _ = self.query(points)
        return arc_length(points - foot, normals, foot_normal)

    def distance(self, points: np.ndarray, normals: np.ndarray, surface: SmallTriangles,
                 marching: Callable[[], np.ndarray], within: float = math.inf) -> tuple[np.ndarray, np.ndarray]:
        """Distance along the surface from each point (with its unit normal) to the curves, and
        whether the nearest curve point is an open end. The arc through the nearest curve point
        stands where the chord's midpoint lies on the ``surface`` as the arc would have it
        (within its sagitta plus ARC_STRAY_FRACTION of the chord); elsewhere (across a sharp
        edge, a slot, to another piece) fast marching's value does, ``marching()`` giving it at
        the points (asked for only then). Points whose arc is longer than ``within`` keep it
        (a caller that needs only nearer ones saves the check)."""
        if self.tree is None or not len(points):
            return np.full(len(points), np.inf), np.zeros(len(points), dtype=bool)
        foot, foot_normal, on_end = self.query(points)
        chord = points - foot
        arc = arc_length(chord, normals, foot_normal)
        length = np.linalg.norm(chord, axis=1)
        turn = np.arccos(np.clip(np.einsum("ij,ij->i", normals, foot_normal), -1.0, 1.0))
        allowed = 0.5 * length * np.tan(0.25 * turn) + ARC_STRAY_FRACTION * length + 1e-9
        check = np.flatnonzero(arc <= within)
        off = np.zeros(len(points), dtype=bool)
        if len(check):
            off[check] = ~(surface.distance(0.5 * (points[check] + foot[check])) <= allowed[check])
        if not off.any():
            return arc, on_end
        return np.where(off, marching(), arc), on_end
