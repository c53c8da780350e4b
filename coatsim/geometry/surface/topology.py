"""Mesh topology: edges, which faces share them, border and non-manifold edges, face components.

An edge is an unordered vertex pair; face ``f``'s edge ``k`` runs from ``faces[f, k]`` to
``faces[f, (k + 1) % 3]``. An edge with one face is on the border, with two it is manifold,
with more it is non-manifold (a fin or a T-junction of a scan or a bad export).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True, eq=False)
class Edges:
    """The unique edges of a triangle mesh: ``pairs`` (E, 2) sorted vertex ids, ``of_face``
    (m, 3) the edge id of each face edge, ``face_count`` (E,) faces on each edge."""

    pairs: np.ndarray
    of_face: np.ndarray
    face_count: np.ndarray

    @property
    def border(self) -> np.ndarray:
        """Ids of the edges with one face."""
        return np.flatnonzero(self.face_count == 1)

    @property
    def nonmanifold(self) -> np.ndarray:
        """Ids of the edges with more than two faces."""
        return np.flatnonzero(self.face_count > 2)


def mesh_edges(faces: np.ndarray) -> Edges:
    """The edges of ``faces`` (m, 3)."""
    directed = np.stack([faces, np.roll(faces, -1, axis=1)], axis=2).reshape(-1, 2)
    pairs, inverse, counts = np.unique(np.sort(directed, axis=1), axis=0, return_inverse=True, return_counts=True)
    return Edges(pairs.reshape(-1, 2), inverse.reshape(-1, 3), counts)


def face_pairs(faces: np.ndarray, edges: Edges) -> tuple[np.ndarray, np.ndarray]:
    """Faces that share a manifold edge, (K, 2), and whether each pair is wound consistently
    (the shared edge runs in opposite directions in the two faces), (K,) bool."""
    manifold = edges.face_count[edges.of_face.ravel()] == 2
    slots = np.flatnonzero(manifold)  # face * 3 + k of every manifold face edge
    order = np.argsort(edges.of_face.ravel()[slots], kind="stable")
    first, second = slots[order[0::2]], slots[order[1::2]]
    flat = faces.ravel()
    forward_1 = flat[first] < flat[first - first % 3 + (first % 3 + 1) % 3]
    forward_2 = flat[second] < flat[second - second % 3 + (second % 3 + 1) % 3]
    return np.column_stack([first // 3, second // 3]), forward_1 != forward_2


def face_components(n_faces: int, pairs: np.ndarray) -> tuple[int, np.ndarray]:
    """Connected components of faces joined by manifold edges: (count, label per face)."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n_faces, n_faces))
    return connected_components(graph, directed=False)


def border_vertices(n_vertices: int, edges: Edges) -> np.ndarray:
    """Vertices on a border edge, (n,) bool."""
    mask = np.zeros(n_vertices, dtype=bool)
    mask[edges.pairs[edges.border].ravel()] = True
    return mask


def submesh(vertices: np.ndarray, faces: np.ndarray, keep: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The faces ``keep`` (bool mask or ids) with only their vertices: (vertices, faces,
    parent vertex id of each new vertex)."""
    kept = faces[keep]
    used, local = np.unique(kept, return_inverse=True)
    return vertices[used], local.reshape(-1, 3), used
