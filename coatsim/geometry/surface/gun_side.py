"""The side of a part the gun comes from, and the part wound to face it.

The planner, the coat and the cell must see one surface: a file wound inwards, or with some
triangles the other way, is turned (normals.orient) towards the gun's side of the region: the
facing direction, the way a box's faces face, or the part's default side.
"""

from __future__ import annotations

import numpy as np

from coatsim.geometry.surface.mesh import Part
from coatsim.geometry.surface.normals import Orientation, closed_faces, orient
from coatsim.geometry.surface.region import Box, Facing, RegionSpec, box_toward, default_toward, unit_vector


def oriented_for(part: Part, region: RegionSpec) -> tuple[Orientation, np.ndarray, str]:
    """The part's triangles wound consistently and outward, open pieces towards the gun's side
    of ``region``; that side (a unit vector) and what it is, in words."""
    toward, why = _toward(region, part.vertices_mm, orient(part.vertices_mm, part.faces, None))
    return orient(part.vertices_mm, part.faces, toward), toward, why


def outward_faces(part: Part, region: RegionSpec) -> np.ndarray:
    """The part's triangles (m, 3) wound as the planner winds them for ``region``: the coat and
    the cell must see the surface the passes were planned on."""
    return oriented_for(part, region)[0].faces


def _toward(region: RegionSpec, vertices: np.ndarray, oriented: Orientation) -> tuple[np.ndarray, str]:
    """The gun's side and what it is: the facing direction, the way a box's faces face, or the
    part's default (see region.default_toward and box_toward)."""
    if isinstance(region, Facing) and region.direction is not None:
        return unit_vector(region.direction, "region facing direction", "region"), "the facing direction"
    if isinstance(region, Box) and (side := box_toward(vertices, oriented.faces, region)) is not None:
        return side, "the mean normal of the faces in the box"
    return default_toward(vertices, oriented.faces, closed_faces(oriented.faces)), \
        "the part's default side" + (" (the faces in the box face every way)" if isinstance(region, Box) else "")
