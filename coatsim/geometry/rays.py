"""Segments against a triangle mesh (mm), by ray casting with Embree (``embreex``): whether a
triangle lies on the way. Shared by the coat's shadows (coatsim.spray.visibility) and the plan's
check that the gun stands clear of the part (coatsim.geometry.surface.standoff)."""

from __future__ import annotations

import numpy as np

#: A segment stops this fraction of its length before its end, so the triangles at its end never
#: block it (0.01 mm at 100 mm: ten times float32 rounding at 1 % incidence cosine), plus 1e-6 of
#: the mesh's size.
RAY_END_GAP = 1e-4
#: Rays are cast in batches of at most this many (28 bytes each in float32 arrays).
RAYS_PER_BATCH = 1_000_000
RAY_BYTES = 28


class RayCaster:
    """Occlusion queries against a triangle mesh (mm) with Embree; coordinates are taken
    relative to the mesh's bounding-box centre so float32 keeps its resolution."""

    def __init__(self, vertices: np.ndarray, faces: np.ndarray):
        from embreex import rtcore_scene
        from embreex.mesh_construction import TriangleMesh

        lo, hi = vertices.min(axis=0), vertices.max(axis=0)
        self.origin = 0.5 * (lo + hi)
        self.gap_mm = 1e-6 * max(float(np.max(hi - lo)), 1e-3)
        self.scene = rtcore_scene.EmbreeScene()
        TriangleMesh(scene=self.scene, vertices=(vertices - self.origin).astype(np.float32),
                     indices=np.asarray(faces, dtype=np.int32))

    def blocked(self, origins: np.ndarray, offsets: np.ndarray, lengths: np.ndarray) -> np.ndarray:
        """True where a triangle lies on the segment from ``origins`` towards ``origins + offsets``
        (lengths = |offsets|), short of its end by RAY_END_GAP of the length."""
        out = np.zeros(len(origins), dtype=bool)
        for lo in range(0, len(origins), RAYS_PER_BATCH):
            sl = slice(lo, lo + RAYS_PER_BATCH)
            stop = 1.0 - RAY_END_GAP - self.gap_mm / lengths[sl]
            hit = self.scene.run((origins[sl] - self.origin).astype(np.float32), offsets[sl].astype(np.float32),
                                 dists=stop.astype(np.float32), query="OCCLUDED")
            out[sl] = np.asarray(hit) != -1
        return out
