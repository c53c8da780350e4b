"""Boundary passes: contour-parallel loops inward from the region's border.

The field is the fast-marching distance from the border (measured along the surface); the
passes are its level sets at the edge band plus (k + 1/2) spacing, so the first loop runs half a
spacing inside the band and every loop is closed (inside a piece a level set of the distance
from the whole border cannot end). Where the distance has several ridges (a long narrow part,
a hole) the innermost levels split into several loops.
"""

from __future__ import annotations

import numpy as np

from coatsim.core.errors import InputError
from coatsim.geometry.surface.distance import distance_levels
from coatsim.geometry.surface.piece import Piece


def boundary_piece(piece: Piece, spacing_mm: float, band_mm: float) -> Piece:
    """The piece with its border distance as the field and the levels of its loops."""
    if not piece.on_border.any():
        raise InputError("boundary passes need a region with a border: a piece of this one is closed; choose "
                         "another or the raster or geodesic pattern", parameters=("region", "pattern"))
    inside = piece.inside(band_mm)
    if not inside.any():
        return piece.with_field(piece.border_mm, np.zeros(0))
    field = piece.border_mm
    levels = distance_levels(float(field[inside].min()), float(field[inside].max()), band_mm + 0.5 * spacing_mm,
                             spacing_mm)
    return piece.with_field(field, levels)
