"""A coarser copy of a surface mesh for pictures: vertex clustering on a cubic grid (every vertex
in a cell merges into one at their area-weighted mean), so a 3-D view stays light however fine
the coating mesh is. Per-vertex fields carry over as area-weighted means of the merged vertices.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from coatsim.spray.surfaces import Surface


@dataclass(frozen=True, eq=False)
class Coarse:
    """The coarse mesh: vertices (k, 3) mm, faces (f, 3), unit normals (k, 3), and for every
    original vertex the coarse vertex it merged into (n,) with its area weight (n,)."""

    vertices: np.ndarray
    faces: np.ndarray
    normals: np.ndarray
    cluster: np.ndarray
    weight: np.ndarray

    def field(self, values: np.ndarray) -> np.ndarray:
        """A per-vertex field of the original mesh on the coarse one (area-weighted mean)."""
        k = len(self.vertices)
        total = np.bincount(self.cluster, weights=self.weight, minlength=k)
        return np.bincount(self.cluster, weights=self.weight * np.asarray(values, float), minlength=k) / total


def _row_keys(rows: np.ndarray) -> np.ndarray:
    """One int64 per row of non-negative integers (k, 3), in the rows' lexicographic order (as
    ``np.unique(rows, axis=0)`` sorts them, at the cost of a 1-D sort)."""
    return np.ravel_multi_index(rows.T, tuple(rows.max(axis=0, initial=0) + 1))


def decimate(surface: Surface, max_faces: int) -> Coarse:
    """Cluster ``surface`` until it has at most about ``max_faces`` triangles (the mesh itself,
    re-indexed, when it already has fewer)."""
    weight = np.maximum(surface.areas, 1e-12)
    if len(surface.faces) <= max_faces:
        return Coarse(surface.vertices, surface.faces, surface.normals, np.arange(surface.n_vertices), weight)
    cell = math.sqrt(2.0 * surface.area_mm2 / max_faces)
    for _ in range(8):
        keys = np.floor((surface.vertices - surface.vertices.min(axis=0)) / cell).astype(np.int64)
        _, cluster = np.unique(_row_keys(keys), return_inverse=True)
        cluster = cluster.ravel()
        faces = cluster[surface.faces]
        keep = (faces[:, 0] != faces[:, 1]) & (faces[:, 1] != faces[:, 2]) & (faces[:, 0] != faces[:, 2])
        faces = faces[keep]
        _, first = np.unique(_row_keys(faces), return_index=True)
        faces = faces[first]
        if len(faces) <= max_faces * 1.15:
            break
        cell *= 1.15
    k = int(cluster.max()) + 1
    total = np.bincount(cluster, weights=weight, minlength=k)
    vertices = np.column_stack([np.bincount(cluster, weights=weight * surface.vertices[:, j], minlength=k)
                                for j in range(3)]) / total[:, None]
    normals = np.column_stack([np.bincount(cluster, weights=weight * surface.normals[:, j], minlength=k)
                               for j in range(3)])
    normals /= np.maximum(np.linalg.norm(normals, axis=1), 1e-12)[:, None]
    return Coarse(vertices, faces, normals, cluster, weight)
