"""Shadows: which surface vertices the nozzle sees, by ray casting with Embree (``embreex``).

A vertex x with unit normal n is *exposed* when the whole surface lies behind its tangent plane
(n.(y - x) <= 0 for every vertex y): the segment from any nozzle in front of that plane to x then
stays strictly in front of it and meets no triangle, so nothing can hide x. Every vertex of a
plate, a cylinder, a sphere or any convex part is exposed; such a surface cannot shadow itself
and needs no ray at all. ``exposed_vertices`` finds them with one convex hull: the largest n.y
over the surface is attained at a hull vertex, found by climbing the hull's edges from the hull
vertex nearest to x (a linear function's local maximum on a convex polytope's edge graph is its
maximum).

Most vertices of a scanned or dished part are not exposed: its noise or its own concavity rises
above their tangent planes somewhere. Yet a nozzle seen from x steeply enough is still clear of
it: every point z of the segment from x to the nozzle p has n.(z - x) = cos g |z - x|, with g the
spray's incidence angle. ``ClearCosines`` bounds, per vertex, n.(z - x) / |z - x| over every point
z != x of the surface (a triangle with the vertex x lies in its plane, so its bound is the sine of
its tilt against n; any other triangle T gives at most max over its corners of n.(y - x) over its
distance to x); a pair whose cos g exceeds the bound needs no ray.

For the other pairs a ray runs from the nozzle towards the vertex and stops a hair short of
it (``coatsim.geometry.rays.RAY_END_GAP``); any triangle on the way blocks the spray. Embree answers such occlusion
queries directly (no hit points), about a microsecond each.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial import ConvexHull, QhullError, cKDTree
from trimesh.triangles import closest_point

from coatsim.core.numeric import ROUND_OFF
from coatsim.core.budgets import check_budget
from coatsim.core.errors import InputError
from coatsim.geometry.rays import RAY_BYTES, RAYS_PER_BATCH, RayCaster
from coatsim.geometry.surface.normals import face_normals

SHADOW_MODES = ("auto", "on", "off")
#: Memory of the exposure test per vertex (Qhull's hull, measured ~300 bytes per hull vertex) and
#: of Embree's scene per triangle (its BVH, measured ~66, and our float32 copies), with margin.
HULL_BYTES_PER_VERTEX = 400
SCENE_BYTES_PER_TRIANGLE = 100
SCENE_BYTES_PER_VERTEX = 16
#: ``ClearCosines`` proves no vertex clearer than CLEAR_FLOOR (an incidence of 60 deg: sprays land
#: well inside it). It buckets the triangles in cubes of CLEAR_CELL_EDGES median edge lengths,
#: those in cubes of 4 x 4 x 4 of them and so on, up to at most CLEAR_TOP boxes. A vertex that
#: sees a point of the surface at an incidence cosine above CLEAR_USEFUL (it would spare few
#: rays), or whose open boxes at one level hold more than CLEAR_LOAD boxes or triangles (a shelf
#: over a floor), is left to the rays (a bound of 1). Vertices go CLEAR_VERTICES at a time, so a
#: chunk holds at most CLEAR_VERTICES x CLEAR_LOAD vertex-box pairs of about CLEAR_PAIR_BYTES each.
CLEAR_FLOOR = 0.5
CLEAR_CELL_EDGES = 2.0
CLEAR_TOP = 16
CLEAR_USEFUL = 0.9
CLEAR_LOAD = 256
CLEAR_VERTICES = 512
CLEAR_PAIR_BYTES = 150
#: The clear cosines keep each triangle's corners, centre and extent, and its place in the cubes.
CLEAR_BYTES_PER_TRIANGLE = 120


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


def _tilt_sines(vertices: np.ndarray, normals: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """Per vertex, the largest sine between its normal and the plane normal of a triangle it
    belongs to (1 for a degenerate triangle, whose normal is 0): n.(z - x) / |z - x| over those
    triangles."""
    unit = face_normals(vertices, faces)[0]
    sines = np.zeros(len(vertices))
    for corner in range(3):
        cosine = np.einsum("ij,ij->i", normals[faces[:, corner]], unit)
        np.maximum.at(sines, faces[:, corner], np.sqrt(np.clip(1.0 - cosine**2, 0.0, 1.0)))
    return sines


@dataclass(frozen=True)
class _Boxes:
    """One level of a hierarchy of cubes over the triangles: each box's middle, half extent and
    radius (its contents lie within it of the middle), a point of the surface in it, and its
    children (finer boxes, or at the bottom triangles) in box order with each box's start."""

    middle: np.ndarray
    half: np.ndarray
    reach: np.ndarray
    point: np.ndarray
    children: np.ndarray
    start: np.ndarray


def _group(key: np.ndarray, lo: np.ndarray, hi: np.ndarray, point: np.ndarray) -> tuple[np.ndarray, _Boxes]:
    """Group items with integer cube keys (k, 3), boxes (lo, hi) and surface points: the distinct
    keys and the box of each group's items."""
    keys, group = np.unique(key, axis=0, return_inverse=True)
    group = group.ravel()
    box_lo = np.full((len(keys), 3), np.inf)
    box_hi = np.full((len(keys), 3), -np.inf)
    np.minimum.at(box_lo, group, lo)
    np.maximum.at(box_hi, group, hi)
    children = np.argsort(group, kind="stable")
    middle, half = 0.5 * (box_lo + box_hi), 0.5 * (box_hi - box_lo)
    start = np.searchsorted(group[children], np.arange(len(keys) + 1))
    return keys, _Boxes(middle, half, np.linalg.norm(half, axis=1), point[children[start[:-1]]], children, start)


def _hierarchy(corners: np.ndarray, size_mm: float) -> list[_Boxes]:
    """Cubes of ``size_mm`` over the triangles (m, 3, 3) by their centres, then cubes of 4 x 4 x 4
    of those, and so on up to at most CLEAR_TOP boxes; coarsest first."""
    centre = corners.mean(axis=1)
    keys, boxes = _group(np.floor(centre / size_mm).astype(np.int64), corners.min(axis=1), corners.max(axis=1), centre)
    levels = [boxes]
    while len(keys) > CLEAR_TOP:
        keys, boxes = _group(keys // 4, boxes.middle - boxes.half, boxes.middle + boxes.half, boxes.point)
        levels.append(boxes)
    return levels[::-1]


def _expand(owner: np.ndarray, box: np.ndarray, boxes: _Boxes) -> tuple[np.ndarray, np.ndarray]:
    """The pairs (owner, child) for every child of each pair's box."""
    count = boxes.start[box + 1] - boxes.start[box]
    offset = np.arange(int(count.sum())) - np.repeat(np.cumsum(count) - count, count)
    return np.repeat(owner, count), boxes.children[np.repeat(boxes.start[box], count) + offset]


class ClearCosines:
    """Per vertex x of a surface an upper bound, at least CLEAR_FLOOR, on n.(z - x) / |z - x| over
    every point z != x of the surface: a nozzle p with n.(p - x) > bound * |p - x| cannot be
    hidden (see the module docstring); 1 where nothing is proven. Bounded vertex by vertex as
    they are asked for (a coat asks only for the vertices it sprays), and kept.

    The triangles are bucketed in a hierarchy of cubes; a box whose highest corner over x's
    tangent plane, over its least distance from x, stays within the bound is passed over whole,
    the others are opened down to their triangles, which are bounded one by one."""

    def __init__(self, vertices: np.ndarray, normals: np.ndarray, faces: np.ndarray):
        self.vertices, self.normals = np.asarray(vertices, float), np.asarray(normals, float)
        self.faces = np.asarray(faces, np.int64)
        self.bound = np.maximum(_tilt_sines(self.vertices, self.normals, self.faces), CLEAR_FLOOR)
        self.asked = np.zeros(len(self.vertices), dtype=bool)
        if len(self.faces):
            self.corners = self.vertices[self.faces]
            self.centre = self.corners.mean(axis=1)
            self.spread = np.linalg.norm(self.corners - self.centre[:, None], axis=2).max(axis=1)  # corners within it
            edge = float(np.median(np.linalg.norm(self.corners[:, [1, 2, 0]] - self.corners, axis=2)))
            self.levels = _hierarchy(self.corners, max(CLEAR_CELL_EDGES * edge, 1e-9))
            self.slack = 1e-9 * max(float(np.abs(self.vertices).max()), 1.0)

    def __call__(self, which: np.ndarray) -> np.ndarray:
        """The bounds of the vertices ``which`` (indices)."""
        which = np.asarray(which, dtype=np.int64)
        todo = np.unique(which[~self.asked[which]])
        self.asked[todo] = True
        todo = todo[self.bound[todo] < 1.0]
        if len(self.faces):
            for first in range(0, len(todo), CLEAR_VERTICES):
                self._search(todo[first:first + CLEAR_VERTICES])
        return self.bound[which]

    def _search(self, x: np.ndarray) -> None:
        """Bound the vertices x (sorted indices) against every triangle but their own."""
        vertices, normals, faces, levels, slack, bound = self.vertices, self.normals, self.faces, self.levels, self.slack, self.bound
        v = np.repeat(x, len(levels[0].middle))
        box = np.tile(np.arange(len(levels[0].middle)), len(x))
        for level, boxes in enumerate(levels):
            if level:
                v, box = _expand(v, box, levels[level - 1])
            p, n = vertices[v], normals[v]
            rise = np.einsum("ij,ij->i", n, boxes.middle[box] - p) + np.einsum("ij,ij->i", np.abs(n), boxes.half[box]) + slack
            gap = np.linalg.norm(boxes.middle[box] - p, axis=1) - boxes.reach[box] - slack
            open_ = (rise > 0) & (rise > bound[v] * gap)
            v, box = v[open_], box[open_]
            # (v stays in vertex order: x is sorted and expanding and filtering keep the order)
            owner = np.searchsorted(x, v)
            # a vertex that sees a point of the surface above CLEAR_USEFUL, or that would open
            # more than CLEAR_LOAD boxes or triangles, is left to the rays
            seen = boxes.point[box] - p[open_]
            length = np.linalg.norm(seen, axis=1)
            steep = np.zeros(len(x), dtype=bool)
            steep[owner[np.einsum("ij,ij->i", seen, n[open_]) >= CLEAR_USEFUL * length]] = True
            load = np.bincount(owner, weights=boxes.start[box + 1] - boxes.start[box], minlength=len(x))
            crowded = steep | (load > CLEAR_LOAD)
            bound[x[crowded]] = 1.0
            v, box = v[~crowded[owner]], box[~crowded[owner]]
        v, t = _expand(v, box, levels[-1])
        apart = ~(faces[t] == v[:, None]).any(axis=1)  # the triangles with x: their tilt, above
        v, t = v[apart], t[apart]
        corners = self.corners[t]
        up = np.einsum("ikj,ij->ik", corners - vertices[v][:, None, :], normals[v]).max(axis=1)
        gap = np.linalg.norm(self.centre[t] - vertices[v], axis=1) - self.spread[t] - slack  # <= the distance
        open_ = (up > 0) & (up > bound[v] * gap)
        v, corners, up = v[open_], corners[open_], up[open_]
        distance = np.linalg.norm(closest_point(corners, vertices[v]) - vertices[v], axis=1)
        np.maximum.at(bound, v, np.where(distance > 0, np.minimum(up / np.where(distance > 0, distance, 1.0), 1.0), 1.0))


def clear_cosines(vertices: np.ndarray, normals: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """(n,) the ClearCosines of every vertex."""
    return ClearCosines(vertices, normals, faces)(np.arange(len(vertices)))


def shadow_memory_bytes(n_vertices: int, n_triangles: int) -> float:
    """Memory shadows need for a surface: the exposure test's hull, Embree's scene, the clear
    cosines' triangles and one chunk of their search, and one batch of rays."""
    return ((SCENE_BYTES_PER_TRIANGLE + CLEAR_BYTES_PER_TRIANGLE) * float(n_triangles)
            + (SCENE_BYTES_PER_VERTEX + HULL_BYTES_PER_VERTEX) * float(n_vertices)
            + CLEAR_PAIR_BYTES * float(CLEAR_VERTICES * CLEAR_LOAD) + RAY_BYTES * float(RAYS_PER_BATCH))


@dataclass(frozen=True, eq=False)
class Visibility:
    """What shadows need on one surface: the vertices nothing can hide (n,), a ray caster for
    the others and their ClearCosines (None when there are none, or when the Embree binding is
    ``unavailable``)."""

    exposed: np.ndarray
    caster: RayCaster | None
    clear: ClearCosines | None = None
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
        caster = RayCaster(vertices, faces)
    except ImportError as exc:
        if mode == "on":
            raise InputError(f"shadows need the embreex package (Embree ray casting), which cannot be imported "
                             f"({type(exc).__name__}: {exc}); install it (pip install embreex) or set shadows off",
                             parameters=("shadows",)) from None
        return Visibility(exposed, None, unavailable=True)
    return Visibility(exposed, caster, ClearCosines(vertices, normals, faces))


def check_shadow_mode(mode: str) -> str:
    if mode not in SHADOW_MODES:
        raise InputError(f"shadows must be one of {', '.join(SHADOW_MODES)}, found {mode!r}", parameters=("shadows",))
    return mode
