"""Shadows: which surface vertices the nozzle sees, by ray casting with Embree (``embreex``).

A vertex x with unit normal n is *exposed* when the whole surface lies behind its tangent plane
(n.(y - x) <= 0 for every vertex y): the segment from any nozzle in front of that plane to x then
stays strictly in front of it and meets no triangle, so nothing can hide x. Every vertex of a
plate, a cylinder, a sphere or any convex part is exposed; such a surface cannot shadow itself
and needs no ray at all. ``exposed_vertices`` finds them with one convex hull: the largest n.y
over the surface is attained at a hull vertex, found by climbing the hull's edges from the hull
vertex nearest to x (a linear function's local maximum on a convex polytope's edge graph is its
maximum).

For the other vertices a ray runs from the nozzle towards the vertex and stops a hair short of
it (``RAY_END_GAP``); any triangle on the way blocks the spray. Embree answers such occlusion
queries directly (no hit points), about a microsecond each.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial import ConvexHull, QhullError, cKDTree

from coatsim.core.numeric import ROUND_OFF
from coatsim.core.budgets import check_budget
from coatsim.core.errors import InputError

SHADOW_MODES = ("auto", "on", "off")
#: A ray from the nozzle stops this fraction of its length before the vertex it aims at, so the
#: vertex's own triangles never block it (0.01 mm at 100 mm: ten times float32 rounding at
#: 1 % incidence cosine), plus 1e-6 of the part's size.
RAY_END_GAP = 1e-4
#: Memory of the exposure test per vertex (Qhull's hull, measured ~300 bytes per hull vertex) and
#: of Embree's scene per triangle (its BVH, measured ~66, and our float32 copies), with margin.
HULL_BYTES_PER_VERTEX = 400
SCENE_BYTES_PER_TRIANGLE = 100
SCENE_BYTES_PER_VERTEX = 16
#: Rays are cast in batches of at most this many (28 bytes each in float32 arrays).
RAYS_PER_BATCH = 1_000_000
RAY_BYTES = 28


def _relative_tolerance(vertices: np.ndarray) -> float:
    """1e-9 of the coordinates' scale: float64 rounding of n.(y - x) stays far below it."""
    return ROUND_OFF * max(float(np.abs(vertices).max(initial=0.0)), float(np.ptp(vertices, axis=0).max(initial=0.0)), 1.0)


def _planar_exposed(vertices: np.ndarray, normals: np.ndarray, plane_normal: np.ndarray, tol: float) -> np.ndarray:
    """Exposure on a flat surface: n.(y - x) over the plane's points, by their 2-D hull."""
    in_plane = normals - (normals @ plane_normal)[:, None] * plane_normal
    extent = max(float(np.ptp(vertices, axis=0).max()), 1.0)
    exposed = np.linalg.norm(in_plane, axis=1) * extent <= tol  # |n.(y - x)| <= |in-plane n| |y - x|
    if exposed.all():
        return exposed
    basis = np.linalg.svd(np.eye(3) - np.outer(plane_normal, plane_normal))[0][:, :2]
    try:
        corners = vertices[ConvexHull(vertices @ basis).vertices]
    except QhullError:  # collinear: the line's two ends
        along = vertices @ basis[:, 0]
        corners = vertices[[int(np.argmin(along)), int(np.argmax(along))]]
    rest = np.flatnonzero(~exposed)
    support = (normals[rest] @ corners.T).max(axis=1)
    exposed[rest] = support <= np.einsum("ij,ij->i", normals[rest], vertices[rest]) + tol
    return exposed


def _hull_climb(points: np.ndarray, simplices: np.ndarray, directions: np.ndarray, start: np.ndarray,
                limit: np.ndarray) -> np.ndarray:
    """Whether max over ``points`` (a convex polytope's vertices with its triangles ``simplices``)
    of d.p stays <= ``limit`` for every direction d: steepest ascent along the polytope's edges
    from ``start``, given up as soon as it passes the limit."""
    edges = np.unique(np.sort(simplices[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1), axis=0)
    edges = np.concatenate([edges, edges[:, ::-1]])
    edges = edges[np.lexsort((edges[:, 1], edges[:, 0]))]
    indptr = np.searchsorted(edges[:, 0], np.arange(len(points) + 1))
    current = start.copy()
    value = np.einsum("ij,ij->i", directions, points[current])
    active = np.flatnonzero(value <= limit)
    while len(active):
        node = current[active]
        degree = indptr[node + 1] - indptr[node]
        first = np.cumsum(degree) - degree
        owner = np.repeat(np.arange(len(active)), degree)
        neighbour = edges[np.repeat(indptr[node] - first, degree) + np.arange(int(degree.sum())), 1]
        candidate = np.einsum("ij,ij->i", directions[active[owner]], points[neighbour])
        best = np.maximum.reduceat(candidate, first)
        at_best = np.flatnonzero(candidate >= best[owner])
        pick = at_best[np.searchsorted(owner[at_best], np.arange(len(active)))]
        better = best > value[active]
        moved = active[better]
        current[moved] = neighbour[pick[better]]
        value[moved] = best[better]
        active = moved[value[moved] <= limit[moved]]
    return value <= limit


def exposed_vertices(vertices: np.ndarray, normals: np.ndarray) -> np.ndarray:
    """(n,) True where no part of the surface can hide the vertex from a nozzle in front of it
    (see the module docstring)."""
    vertices, normals = np.asarray(vertices, float), np.asarray(normals, float)
    if len(vertices) == 0:
        return np.zeros(0, dtype=bool)
    tol = _relative_tolerance(vertices)
    centred = vertices - vertices.mean(axis=0)
    plane_normal = np.linalg.eigh(centred.T @ centred)[1][:, 0]
    if np.abs(centred @ plane_normal).max() <= tol:
        return _planar_exposed(vertices, normals, plane_normal, tol)
    try:
        hull = ConvexHull(vertices)
    except QhullError:  # numerically flat beyond the tolerance above: treat as possibly shadowed
        return np.zeros(len(vertices), dtype=bool)
    local = np.full(len(vertices), -1, dtype=np.int64)
    local[hull.vertices] = np.arange(len(hull.vertices))
    points = vertices[hull.vertices]
    start = np.asarray(cKDTree(points).query(vertices)[1], dtype=np.int64)
    return _hull_climb(points, local[hull.simplices], normals, start, np.einsum("ij,ij->i", normals, vertices) + tol)


def shadow_memory_bytes(n_vertices: int, n_triangles: int) -> float:
    """Memory shadows need for a surface: the exposure test's hull, Embree's scene and one
    batch of rays."""
    return (SCENE_BYTES_PER_TRIANGLE * float(n_triangles) + (SCENE_BYTES_PER_VERTEX + HULL_BYTES_PER_VERTEX)
            * float(n_vertices) + RAY_BYTES * float(RAYS_PER_BATCH))


class RayCaster:
    """Occlusion queries against a triangle mesh (mm) with Embree; coordinates are taken
    relative to the mesh's bounding-box centre so float32 keeps its resolution."""

    def __init__(self, vertices: np.ndarray, faces: np.ndarray):
        from embreex import rtcore_scene
        from embreex.mesh_construction import TriangleMesh

        lo, hi = vertices.min(axis=0), vertices.max(axis=0)
        self.origin = 0.5 * (lo + hi)
        self.gap_mm = 1e-6 * max(float(np.max(hi - lo)), 1e-3)
        self.scene = rtcore_scene.EmbreeScene()
        TriangleMesh(scene=self.scene, vertices=(vertices - self.origin).astype(np.float32),
                     indices=np.asarray(faces, dtype=np.int32))

    def blocked(self, origins: np.ndarray, offsets: np.ndarray, lengths: np.ndarray) -> np.ndarray:
        """True where a triangle lies on the segment from ``origins`` towards ``origins + offsets``
        (lengths = |offsets|), short of its end by RAY_END_GAP of the length."""
        out = np.zeros(len(origins), dtype=bool)
        for lo in range(0, len(origins), RAYS_PER_BATCH):
            sl = slice(lo, lo + RAYS_PER_BATCH)
            stop = 1.0 - RAY_END_GAP - self.gap_mm / lengths[sl]
            hit = self.scene.run((origins[sl] - self.origin).astype(np.float32), offsets[sl].astype(np.float32),
                                 dists=stop.astype(np.float32), query="OCCLUDED")
            out[sl] = np.asarray(hit) != -1
        return out


@dataclass(frozen=True, eq=False)
class Visibility:
    """What shadows need on one surface: the vertices nothing can hide (n,), and a ray caster
    for the others (None when there are none, or when the Embree binding is ``unavailable``)."""

    exposed: np.ndarray
    caster: RayCaster | None
    unavailable: bool = False


def visibility(vertices: np.ndarray, normals: np.ndarray, faces: np.ndarray, mode: str) -> Visibility:
    """The surface's Visibility for shadows ``mode`` (``auto`` or ``on``), its memory checked
    against the budget shadow_bytes first. Without the Embree binding: an error when shadows were asked
    for (``on``); in ``auto``, ``unavailable`` (the caller warns and coats without shadows)."""
    check_budget(f"shadows: convex hull and ray-casting scene of {len(vertices)} vertices, {len(faces)} "
                 f"triangles, bytes", shadow_memory_bytes(len(vertices), len(faces)), "shadow_bytes",
                 "use a larger spacing, or set shadows off")
    exposed = exposed_vertices(vertices, normals)
    if exposed.all():
        return Visibility(exposed, None)
    try:
        return Visibility(exposed, RayCaster(vertices, faces))
    except ImportError as exc:
        if mode == "on":
            raise InputError(f"shadows need the embreex package (Embree ray casting), which cannot be imported "
                             f"({type(exc).__name__}: {exc}); install it (pip install embreex) or set shadows off",
                             parameters=("shadows",)) from None
        return Visibility(exposed, None, unavailable=True)


def check_shadow_mode(mode: str) -> str:
    if mode not in SHADOW_MODES:
        raise InputError(f"shadows must be one of {', '.join(SHADOW_MODES)}, found {mode!r}", parameters=("shadows",))
    return mode
