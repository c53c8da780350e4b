"""A connected piece of the coated region, with what every pattern needs at its vertices.

Patterns turn a piece into a field whose level sets are its passes.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from coatsim.geometry.surface.boxes import SmallTriangles
from coatsim.geometry.surface.distance import Marching


@dataclass(frozen=True, eq=False)
class Piece:
    """Vertices (n, 3) mm and faces (m, 3) of one connected piece of the region, its smoothed
    unit normals (n, 3), the distance along the surface to the region's border (n,) mm (inf on a
    closed piece), once a pattern has run the ``field`` (n,) and the ``levels`` of its passes; its
    fast-marching solver and its triangles by their centres."""

    vertices: np.ndarray
    faces: np.ndarray
    normals: np.ndarray
    border_mm: np.ndarray
    field: np.ndarray | None = None
    levels: np.ndarray | None = None
    marching: Marching | None = None
    surface: SmallTriangles | None = None

    def inside(self, band_mm: float) -> np.ndarray:
        """Vertices passes must cover: at least ``band_mm`` from the border."""
        return self.border_mm >= band_mm

    @property
    def on_border(self) -> np.ndarray:
        return self.border_mm <= 0.0

    @property
    def area_mm2(self) -> float:
        return float(self.vertex_areas_mm2().sum())

    def vertex_areas_mm2(self) -> np.ndarray:
        """A third of the area of every face around each vertex."""
        a, b, c = (self.vertices[self.faces[:, k]] for k in range(3))
        area = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1)
        return np.bincount(self.faces.ravel(), weights=np.repeat(area / 3, 3), minlength=len(self.vertices))

    def with_field(self, field: np.ndarray, levels: np.ndarray) -> Piece:
        return replace(self, field=field, levels=levels)
