"""Passes added where a pattern's level sets leave part of a piece uncovered.

The level sets of a distance from a start (geodesic, boundary patterns) at (k + 1/2) spacings
miss what lies farther than half a spacing from all of them: a strip narrower than a spacing
(an arm of a bracket, a rim; the first level, half a spacing in, does not enter it) and the top
of a ridge that stops short of the next level. Raster planes miss an arm that runs between two
of them. Each such patch (the faces whose corners all lie
more than half a spacing from every pass, measured along the surface by fast marching; patches
under ``MIN_PATCH_FRACTION`` of a spacing squared are left, and show in the coverage) gets level
curves of the same field over the patch's own range of values (distance.distance_levels from
its low end: a patch under a spacing across gets one through the middle of its range), cut to
the patch and one ring of faces around it so that they meet the passes beside it; pieces of
them shorter than half a spacing are dropped.
"""

from __future__ import annotations

import numpy as np

from coatsim.geometry.surface.contours import SurfaceCurve, level_curves
from coatsim.geometry.surface.distance import distance_levels
from coatsim.geometry.surface.piece import Piece
from coatsim.geometry.surface.topology import face_components, face_pairs, mesh_edges, submesh

#: patches smaller than this fraction of a spacing squared get no pass
MIN_PATCH_FRACTION = 0.25
#: an added pass shorter than this fraction of a spacing is dropped (the footprint covers so short a patch
#: from the passes beside it about as well)
MIN_LENGTH_FRACTION = 0.5
#: a vertex counts as covered up to this fraction beyond half a spacing (as spacing.measure)
SLACK = 1e-6


def filled(piece: Piece, curves: list[SurfaceCurve], spacing_mm: float) -> list[SurfaceCurve]:
    """Curves on ``piece`` (its faces' ids) covering the patches its ``curves`` leave (see the
    module docstring); ``piece.field`` is the field whose levels they are."""
    if not curves:
        return []
    far = piece.marching.distance(curves=curves) > 0.5 * spacing_mm * (1 + SLACK)
    patch_face = far[piece.faces].all(axis=1)
    if not patch_face.any():
        return []
    pairs = face_pairs(piece.faces, mesh_edges(piece.faces))[0]
    _, label = face_components(len(piece.faces), pairs[patch_face[pairs].all(axis=1)])
    a, b, c = (piece.vertices[piece.faces[:, k]] for k in range(3))
    area = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1)
    added: list[SurfaceCurve] = []
    for patch in np.unique(label[patch_face]).tolist():
        faces = patch_face & (label == patch)
        if area[faces].sum() < MIN_PATCH_FRACTION * spacing_mm**2:
            continue
        corners = np.unique(piece.faces[faces])
        low, high = float(piece.field[corners].min()), float(piece.field[corners].max())
        ring = np.zeros(len(piece.vertices), dtype=bool)
        ring[corners] = True
        grown = np.flatnonzero(ring[piece.faces].any(axis=1))
        v, f, parent = submesh(piece.vertices, piece.faces, grown)
        for level in distance_levels(low, high, low + 0.5 * spacing_mm, spacing_mm).tolist():
            added.extend(SurfaceCurve(q.points, grown[q.faces], q.bary, q.closed)
                         for q in level_curves(v, f, piece.field[parent], level)
                         if q.length_mm >= MIN_LENGTH_FRACTION * spacing_mm)
    return added
