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


def unique_pairs(pairs: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Unordered vertex pairs (k, 2) made unique: (sorted unique pairs (E, 2), index of each
    input pair among them (k,))."""
    low, high = pairs.min(axis=1), pairs.max(axis=1)
    base = int(high.max()) + 1 if len(pairs) else 1
    keys, inverse = np.unique(low * base + high, return_inverse=True)
    return np.column_stack([keys // base, keys % base]), inverse.ravel()


def mesh_edges(faces: np.ndarray) -> Edges:
    """The edges of ``faces`` (m, 3)."""
    directed = np.stack([faces, np.roll(faces, -1, axis=1)], axis=2).reshape(-1, 2)
    low, high = directed.min(axis=1), directed.max(axis=1)
    base = int(faces.max()) + 1 if len(faces) else 1
    keys, inverse, counts = np.unique(low * base + high, return_inverse=True, return_counts=True)
    return Edges(np.column_stack([keys // base, keys % base]), inverse.reshape(-1, 3), counts)


def face_pairs(faces: np.ndarray, edges: Edges, slots: bool = False):
    """Faces that share a manifold edge, (K, 2), and whether each pair is wound consistently
    (the shared edge runs in opposite directions in the two faces), (K,) bool; with ``slots``
    also the shared edge's index (0-2) in each of the two faces."""
    manifold = edges.face_count[edges.of_face.ravel()] == 2
    where = np.flatnonzero(manifold)  # face * 3 + k of every manifold face edge
    order = np.argsort(edges.of_face.ravel()[where], kind="stable")
    first, second = where[order[0::2]], where[order[1::2]]
    flat = faces.ravel()
    forward_1 = flat[first] < flat[first - first % 3 + (first % 3 + 1) % 3]
    forward_2 = flat[second] < flat[second - second % 3 + (second % 3 + 1) % 3]
    pairs, consistent = np.column_stack([first // 3, second // 3]), forward_1 != forward_2
    return (pairs, consistent, first % 3, second % 3) if slots else (pairs, consistent)


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


def manifold_split(faces: np.ndarray, pairs: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Faces on vertices made manifold: each vertex is split into one copy per fan of faces
    around it joined by manifold edges (a bow-tie vertex becomes two, the faces of a
    non-manifold edge part along it); only by the face ``pairs`` (K, 2) given, when given (a
    subset of face_pairs: the others part too). Returns (new faces, original vertex of each new
    vertex), new vertices numbered in order of their first face corner."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    if pairs is None:
        pairs, _ = face_pairs(faces, mesh_edges(faces))
    f, g = pairs[:, 0], pairs[:, 1]
    rows, cols = [], []
    for k in range(3):  # the corners of f and g at each vertex they share are one corner group
        match = faces[g] == faces[f, k][:, None]
        has = match.any(axis=1)
        rows.append(f[has] * 3 + k)
        cols.append(g[has] * 3 + np.argmax(match[has], axis=1))
    n = 3 * len(faces)
    graph = coo_matrix((np.ones(sum(map(len, rows))), (np.concatenate(rows), np.concatenate(cols))), shape=(n, n))
    _, group = connected_components(graph, directed=False)
    _, first = np.unique(group, return_index=True)
    return group.reshape(-1, 3).astype(np.int64), faces.ravel()[first].astype(np.int64)
