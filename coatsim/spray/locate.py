"""Points on a coated surface: the closest point of the mesh to given 3-D points, as a face and
barycentric weights, so per-vertex fields (thickness, the 2-D view coordinates of the heat maps)
can be read anywhere on the part, e.g. along the track's centre line.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

from coatsim.spray.surfaces import Surface

_CANDIDATES = 12  # nearest face centroids tried per point


@dataclass(frozen=True, eq=False)
class SurfacePoints:
    """Closest points of a surface: face index (n,), barycentric weights (n, 3), distance (n,) mm."""

    faces: np.ndarray
    weights: np.ndarray
    distance_mm: np.ndarray

    def field(self, surface: Surface, values: np.ndarray) -> np.ndarray:
        """A per-vertex field (n_vertices,) or (n_vertices, k) interpolated at the points."""
        corners = surface.faces[self.faces]
        values = np.asarray(values, dtype=float)
        if values.ndim == 1:
            return np.einsum("nk,nk->n", self.weights, values[corners])
        return np.einsum("nk,nkd->nd", self.weights, values[corners])


def _closest_on_triangles(p: np.ndarray, a: np.ndarray, b: np.ndarray, c: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Closest points of triangles (a, b, c) to p, all (..., 3): (distance (...), weights (..., 3)).
    Clamps the plane projection's barycentric coordinates onto the triangle's edges."""
    ab, ac, ap = b - a, c - a, p - a
    d00 = np.einsum("...i,...i", ab, ab)
    d01 = np.einsum("...i,...i", ab, ac)
    d11 = np.einsum("...i,...i", ac, ac)
    d20 = np.einsum("...i,...i", ap, ab)
    d21 = np.einsum("...i,...i", ap, ac)
    den = np.where(np.abs(d00 * d11 - d01 * d01) > 1e-18, d00 * d11 - d01 * d01, 1e-18)
    v = (d11 * d20 - d01 * d21) / den
    w = (d00 * d21 - d01 * d20) / den
    weights = np.stack((1.0 - v - w, v, w), axis=-1)
    best_d = np.full(p.shape[:-1], np.inf)
    best_w = np.zeros(weights.shape)
    inside = np.all(weights >= 0.0, axis=-1)
    q = a + v[..., None] * ab + w[..., None] * ac
    d_in = np.where(inside, np.linalg.norm(p - q, axis=-1), np.inf)
    best_d, best_w = d_in, np.where(inside[..., None], weights, best_w)
    corners = (a, b, c)
    for i, j in ((0, 1), (1, 2), (2, 0)):
        e = corners[j] - corners[i]
        t = np.clip(np.einsum("...i,...i", p - corners[i], e) / np.maximum(np.einsum("...i,...i", e, e), 1e-18), 0.0, 1.0)
        d = np.linalg.norm(p - (corners[i] + t[..., None] * e), axis=-1)
        better = d < best_d
        edge_w = np.zeros(weights.shape)
        edge_w[..., i] = 1.0 - t
        edge_w[..., j] = t
        best_d = np.where(better, d, best_d)
        best_w = np.where(better[..., None], edge_w, best_w)
    return best_d, best_w


def locate(surface: Surface, points_mm: np.ndarray) -> SurfacePoints:
    """The closest point of ``surface`` to each of ``points_mm`` (n, 3), searched among the
    faces whose centroids are nearest (exact for points near the surface, as a track's centre
    line is)."""
    points = np.asarray(points_mm, dtype=float).reshape(-1, 3)
    tri = surface.vertices[surface.faces]
    k = min(_CANDIDATES, len(surface.faces))
    centroids = (tri[:, 0] + tri[:, 1] + tri[:, 2]) / 3.0  # tri.mean(axis=1), which reduces slowly over three
    _, near = cKDTree(centroids).query(points, k=k)
    near = np.asarray(near).reshape(len(points), k)
    dist, weights = _closest_on_triangles(points[:, None, :], tri[near, 0], tri[near, 1], tri[near, 2])
    pick = np.argmin(dist, axis=1)
    rows = np.arange(len(points))
    return SurfacePoints(near[rows, pick], weights[rows, pick], dist[rows, pick])
