"""Which triangles of a mesh lie near points.

``TriangleBoxes``, an R-tree of the triangles' bounding boxes, serves any mesh (a part as read,
with CAD triangles of any size): the independent check of a plan (verify) and keeping a pass's
normals out of the faces that touch its points (normals.kept_outward). ``SmallTriangles``, a
KD-tree of their centres, serves the refined region: whether a chord between passes runs along
the surface (distance.NearestOnCurves).
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


class SmallTriangles:
    """The triangles of a mesh refined to small, even triangles, their centres in a KD-tree: how
    far points lie from the surface near them (the nearest of the triangles with the nearest
    centres; exact where the triangles are much smaller than the distances that matter)."""

    #: triangles looked at per point
    NEAREST = 8

    def __init__(self, vertices: np.ndarray, faces: np.ndarray):
        from scipy.spatial import cKDTree

        self.triangles = vertices[faces]
        self.tree = cKDTree(self.triangles.mean(axis=1))

    def distance(self, points: np.ndarray) -> np.ndarray:
        """Distance (mm) from each point to the surface."""
        import trimesh

        k = min(self.NEAREST, len(self.triangles))
        index = self.tree.query(points, k=k)[1].reshape(len(points), k)
        repeated = np.repeat(points, k, axis=0)
        closest = trimesh.triangles.closest_point(self.triangles[index.ravel()], repeated)
        return np.linalg.norm(closest - repeated, axis=1).reshape(len(points), k).min(axis=1)
