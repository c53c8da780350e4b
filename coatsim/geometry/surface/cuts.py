"""Cutting a mesh so that a start curve or start points become vertices (heat-method sources).

The heat method takes its sources at vertices. A start plane's section is inserted into the mesh
(each crossed triangle split in three along the section) and a start point splits the triangle it
lies in; the surface does not change, and per-vertex values (normals, distances) are carried over
linearly.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from coatsim.geometry.surface.contours import crossings, edge_points
from coatsim.geometry.surface.topology import unique_pairs

#: an edge point this close to a vertex (fraction of the edge) is that vertex
SNAP_FRACTION = 1e-6


@dataclass(frozen=True, eq=False)
class Cut:
    """The cut mesh: vertices, faces, per-vertex ``values`` carried over, the vertices on the
    cut (sources), and the original face of each new face."""

    vertices: np.ndarray
    faces: np.ndarray
    values: np.ndarray
    on_cut: np.ndarray
    parent: np.ndarray


def cut_at_level(vertices: np.ndarray, faces: np.ndarray, field: np.ndarray, level: float,
                 values: np.ndarray) -> Cut:
    """Insert the level set ``field == level`` as vertices and edges."""
    crossed, start, end = crossings(faces, field, level)
    keys, node = unique_pairs(np.concatenate([start, end]))
    points, t = edge_points(vertices, field, level, keys)
    new_id = len(vertices) + np.arange(len(keys))
    new_id = np.where(t <= SNAP_FRACTION, keys[:, 0], np.where(t >= 1 - SNAP_FRACTION, keys[:, 1], new_id))
    fresh = new_id >= len(vertices)
    # renumber the fresh points densely after the old vertices
    dense = np.cumsum(fresh) - 1 + len(vertices)
    new_id = np.where(fresh, dense, new_id)
    carried = values[keys[:, 0]] + t.reshape(-1, *([1] * (values.ndim - 1))) * (values[keys[:, 1]] - values[keys[:, 0]])
    vertices2 = np.vstack([vertices, points[fresh]])
    values2 = np.concatenate([values, carried[fresh]])
    x, y = new_id[node[: len(crossed)]], new_id[node[len(crossed):]]
    # each crossed face (L, P, Q) with X on L-P and Y on Q-L becomes (L, X, Y), (X, P, Q), (X, Q, Y)
    above = (field >= level)[faces[crossed]]
    lone_above = above.sum(axis=1) == 1
    k = np.where(lone_above, np.argmax(above, axis=1), np.argmin(above, axis=1))
    tri = faces[crossed]
    rows = np.arange(len(crossed))
    lone, nxt, prv = tri[rows, k], tri[rows, (k + 1) % 3], tri[rows, (k + 2) % 3]
    on_lp = np.where(lone_above, x, y)  # the segment runs L-P -> Q-L when L is above
    on_ql = np.where(lone_above, y, x)
    pieces = np.concatenate([np.column_stack([lone, on_lp, on_ql]), np.column_stack([on_lp, nxt, prv]),
                             np.column_stack([on_lp, prv, on_ql])])
    keep = np.ones(len(faces), dtype=bool)
    keep[crossed] = False
    faces2 = np.concatenate([faces[keep], pieces])
    parent = np.concatenate([np.flatnonzero(keep), np.tile(crossed, 3)])
    good = (faces2[:, 0] != faces2[:, 1]) & (faces2[:, 1] != faces2[:, 2]) & (faces2[:, 2] != faces2[:, 0])
    on_cut = np.union1d(np.unique(new_id), np.flatnonzero(field == level))
    return Cut(vertices2, faces2[good], values2, on_cut, parent[good])


def insert_points(vertices: np.ndarray, faces: np.ndarray, face_ids: np.ndarray, bary: np.ndarray,
                  values: np.ndarray) -> Cut:
    """Insert points given by face and barycentric weights; a point at a corner is that vertex.
    Two points in one face: only the first is inserted, the second goes to its nearest corner."""
    face_ids = np.asarray(face_ids, dtype=np.int64)
    corner = np.argmax(bary, axis=1)
    at_corner = bary[np.arange(len(bary)), corner] >= 1 - SNAP_FRACTION
    _, first = np.unique(face_ids, return_index=True)
    split = np.zeros(len(face_ids), dtype=bool)
    split[first] = True
    split &= ~at_corner
    ids = faces[face_ids, corner].copy()
    ids[split] = len(vertices) + np.arange(split.sum())
    weights = bary[split].reshape(-1, 3, *([1] * (values.ndim - 1)))
    new_points = np.einsum("ij,ijk->ik", bary[split], vertices[faces[face_ids[split]]])
    new_values = (weights * values[faces[face_ids[split]]]).sum(axis=1)
    tri = faces[face_ids[split]]
    p = ids[split]
    pieces = np.concatenate([np.column_stack([tri[:, 0], tri[:, 1], p]), np.column_stack([tri[:, 1], tri[:, 2], p]),
                             np.column_stack([tri[:, 2], tri[:, 0], p])])
    keep = np.ones(len(faces), dtype=bool)
    keep[face_ids[split]] = False
    faces2 = np.concatenate([faces[keep], pieces])
    parent = np.concatenate([np.flatnonzero(keep), np.tile(face_ids[split], 3)])
    return Cut(np.vstack([vertices, new_points]), faces2, np.concatenate([values, new_values]), np.unique(ids), parent)
