"""Sharp edges and the feature regions they bound.

A CAD part's faces meet at sharp edges (the edge of a plate, a chamfer); a gun cannot follow
its normal round one, and averaging normals across one gives an axis that is off both faces
(45 deg at a right-angled edge). An edge is sharp when the normals of its two faces differ by
more than ``SHARP_EDGE_DEG``: more than a scan's noise or the facets of a curved surface
tessellated finely enough to plan on (a cylinder in 10 facets or more), less than the edges
of a box or a plate. Feature regions are the pieces of the surface joined by edges that are
not sharp; normals are smoothed within a region and passes stay in one.
"""

from __future__ import annotations

import math

import numpy as np

from coatsim.geometry.surface.topology import face_components, face_pairs, manifold_split, mesh_edges

#: an edge whose faces' normals differ by more than this is sharp
SHARP_EDGE_DEG = 40.0


def _pairs_cos(faces: np.ndarray, face_n: np.ndarray, consistent_only: bool) -> tuple[np.ndarray, np.ndarray]:
    """Faces sharing a manifold edge (K, 2) and the cosine of the angle between their normals
    (negated for a pair wound against each other unless ``consistent_only``)."""
    pairs, consistent = face_pairs(faces, mesh_edges(faces))
    cos = np.einsum("ij,ij->i", face_n[pairs[:, 0]], face_n[pairs[:, 1]])
    return pairs, cos if consistent_only else np.where(consistent, cos, -cos)


def smooth_pairs(faces: np.ndarray, face_n: np.ndarray, consistent_only: bool = True) -> np.ndarray:
    """Pairs of faces (K, 2) sharing a manifold edge that is not sharp. ``face_n`` are unit face
    normals; with ``consistent_only`` False the faces' winding may be inconsistent (a file as
    read): a pair wound against each other has its dot product negated, so that a flipped
    triangle makes no sharp edge."""
    pairs, cos = _pairs_cos(faces, face_n, consistent_only)
    return pairs[cos >= math.cos(math.radians(SHARP_EDGE_DEG))]


def sharp_length_mm(vertices: np.ndarray, faces: np.ndarray, face_n: np.ndarray) -> float:
    """The total length of the sharp edges between ``faces`` (consistently wound), mm."""
    pairs, cos = _pairs_cos(faces, face_n, True)
    sharp = pairs[cos < math.cos(math.radians(SHARP_EDGE_DEG))]
    first, second = faces[sharp[:, 0]], faces[sharp[:, 1]]
    shared = [first[np.arange(len(sharp)), k] for k in range(3)]
    on_both = np.column_stack([(second == v[:, None]).any(axis=1) for v in shared])
    ends = np.where(on_both, np.column_stack(shared), -1)
    ends = np.sort(ends, axis=1)[:, 1:]  # the two shared corners (the third is -1)
    return float(np.linalg.norm(vertices[ends[:, 0]] - vertices[ends[:, 1]], axis=1).sum())


def feature_labels(faces: np.ndarray, face_n: np.ndarray, consistent_only: bool = True) -> np.ndarray:
    """The feature region of each face, (m,) int (see ``smooth_pairs``)."""
    return face_components(len(faces), smooth_pairs(faces, face_n, consistent_only))[1]


def feature_split(faces: np.ndarray, face_n: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Faces on vertices split along sharp edges: each vertex gets one copy per fan of its faces
    joined by edges that are neither sharp nor non-manifold, so a sharp edge becomes a border on
    both sides. Returns (new faces, original vertex of each new vertex)."""
    return manifold_split(faces, smooth_pairs(faces, face_n))
