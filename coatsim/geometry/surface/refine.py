"""Refining a mesh for planning: every edge at most a given length, triangles kept well shaped.

Long edges are bisected at shared midpoints (trimesh's ``subdivide_to_size``: crack-free, the
surface unchanged). Bisection leaves fans of long thin triangles where a big flat CAD triangle is
cut down, and both the heat method and fast marching lose accuracy on those (an edge's worth of
error near a source); so edges between two coplanar triangles are then flipped until every such
edge is Delaunay (the two angles opposite it sum to at most 180 degrees), which changes no point
of the surface.
"""

from __future__ import annotations

import numpy as np

from coatsim.core.budgets import check_budget
from coatsim.geometry.surface.topology import face_pairs, mesh_edges

#: two faces count as coplanar when their unit normals' dot product exceeds 1 minus this
COPLANAR_TOLERANCE = 1e-10
#: rounds of simultaneous flips (each round flips a set of edges that share no triangle)
MAX_FLIP_ROUNDS = 200


def refined(vertices: np.ndarray, faces: np.ndarray, max_edge_mm: float, what: str, fix: str,
            labels: np.ndarray | None = None,
            parameters: tuple[str, ...] = ()) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The mesh with every edge longer than ``max_edge_mm`` bisected, then flipped toward
    Delaunay (see the module docstring): (vertices, faces, the ``labels`` (m,) of the original
    face each new face lies in; edges between differently labelled faces are not flipped). The
    triangle count is checked against the budget before anything is built;
    ``fix`` says what to change (naming ``parameters``)."""
    import trimesh.remesh

    a, b, c = (vertices[faces[:, k]] for k in range(3))
    area = 0.5 * float(np.linalg.norm(np.cross(b - a, c - a), axis=1).sum())
    lengths = np.linalg.norm(np.stack([b - a, c - b, a - c]), axis=2)
    labels = np.zeros(len(faces), dtype=np.int64) if labels is None else np.asarray(labels)
    if not (lengths > max_edge_mm).any():
        return vertices, faces, labels
    # bisected triangles end with edges between max_edge/2 and max_edge: at least a quarter of max_edge^2 each
    estimate = max(len(faces), 4.0 * area / max_edge_mm**2)
    check_budget(f"{what} refined to edges of {max_edge_mm:.3g} mm: triangles", estimate, "plan_triangles", fix,
                 parameters)
    iterations = int(np.ceil(np.log2(max(lengths.max() / max_edge_mm, 1.0)))) + 2
    v, f, index = trimesh.remesh.subdivide_to_size(vertices, faces, max_edge=max_edge_mm, max_iter=iterations,
                                                   return_index=True)
    v, f = np.asarray(v, dtype=float), np.asarray(f, dtype=np.int64)
    new_labels = labels[np.asarray(index, dtype=np.int64)]
    return v, delaunay_flips(v, f, new_labels), new_labels


def _angle(at: np.ndarray, p: np.ndarray, q: np.ndarray) -> np.ndarray:
    a, b = p - at, q - at
    return np.arctan2(np.linalg.norm(np.cross(a, b), axis=1), np.einsum("ij,ij->i", a, b))


def delaunay_flips(vertices: np.ndarray, faces: np.ndarray, labels: np.ndarray) -> np.ndarray:
    """Flip edges between coplanar triangles of one label until each is Delaunay (see the
    module docstring)."""
    faces = faces.copy()
    for _ in range(MAX_FLIP_ROUNDS):
        pairs, consistent, slot_f, slot_g = face_pairs(faces, mesh_edges(faces), slots=True)
        f, g = pairs[consistent, 0], pairs[consistent, 1]
        k, l_ = slot_f[consistent], slot_g[consistent]
        u, w, a = faces[f, k], faces[f, (k + 1) % 3], faces[f, (k + 2) % 3]
        b = faces[g, (l_ + 2) % 3]
        excess = (_angle(vertices[a], vertices[u], vertices[w]) + _angle(vertices[b], vertices[u], vertices[w])
                  - np.pi)
        nf = np.cross(vertices[w] - vertices[u], vertices[a] - vertices[u])
        ng = np.cross(vertices[u] - vertices[w], vertices[b] - vertices[w])
        cos = np.einsum("ij,ij->i", nf, ng) / np.maximum(np.linalg.norm(nf, axis=1) * np.linalg.norm(ng, axis=1),
                                                         1e-300)
        flip = np.flatnonzero((excess > 1e-9) & (cos > 1 - COPLANAR_TOLERANCE) & (a != b) & (labels[f] == labels[g]))
        if not len(flip):
            break
        # flip at once the edges that are the worst candidate of both their triangles
        rank = np.empty(len(flip), dtype=np.int64)
        rank[np.lexsort((flip, -excess[flip]))] = np.arange(len(flip))
        best = np.full(len(faces), len(flip))
        np.minimum.at(best, f[flip], rank)
        np.minimum.at(best, g[flip], rank)
        chosen = flip[(best[f[flip]] == rank) & (best[g[flip]] == rank)]
        faces[f[chosen]] = np.column_stack([a[chosen], u[chosen], b[chosen]])
        faces[g[chosen]] = np.column_stack([b[chosen], w[chosen], a[chosen]])
    return faces
