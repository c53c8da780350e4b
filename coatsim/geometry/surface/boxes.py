"""Which triangles of a mesh lie near points: an R-tree of the triangles' bounding boxes.

Used by the independent check of a plan (verify) and to keep a pass's normals out of the faces
that touch its points (normals.kept_outward).
"""

from __future__ import annotations

import numpy as np


class TriangleBoxes:
    """The triangles ``faces`` of a mesh (``vertices`` mm) in an R-tree of their bounding boxes."""

    def __init__(self, vertices: np.ndarray, faces: np.ndarray):
        from rtree import index

        self.triangles = vertices[faces]
        properties = index.Property()
        properties.dimension = 3
        self.tree = index.Index((np.arange(len(faces)), self.triangles.min(axis=1), self.triangles.max(axis=1)),
                                properties=properties)

    def near(self, points: np.ndarray, radius: float) -> tuple[np.ndarray, np.ndarray]:
        """Pairs (point, triangle) whose bounding box reaches within ``radius`` of the point (per
        axis): point indices ascending, triangle ids."""
        face, counts = self.tree.intersection_v(points - radius, points + radius)
        owner = np.repeat(np.arange(len(points)), np.asarray(counts, dtype=np.int64))
        return owner, np.asarray(face, dtype=np.int64)

    def touching(self, points: np.ndarray, tolerance: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Pairs (point, triangle) with the triangle within ``tolerance`` of the point, and the
        distances of every pair whose box is that near (to tell a point off the mesh)."""
        import trimesh

        owner, face = self.near(points, tolerance)
        distance = np.linalg.norm(trimesh.triangles.closest_point(self.triangles[face], points[owner]) - points[owner],
                                  axis=1)
        return owner, face, distance
