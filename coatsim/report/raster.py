"""Per-vertex fields of a surface drawn as images of its 2-D view, for the heat maps.

A heat map of a fine coating mesh drawn triangle by triangle costs time in proportion to the
mesh and gives nothing a reader can see at report resolution. Instead the view is sampled
once on a pixel grid: each pixel centre's triangle and barycentric weights are found once per
surface (``ViewRaster``), and every field of that surface is then one weighted sum per pixel
(linear inside each triangle, as Gouraud shading), NaN off the part.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

EDGE = 1e-9  # barycentric slack: pixel centres on a shared edge belong to a triangle


@dataclass(frozen=True, eq=False)
class ViewRaster:
    """A pixel grid over a 2-D view: extent (x0, x1, y0, y1) mm of the pixel edges, shape
    (rows, columns), and per covered pixel (flat index) its triangle's corners (k, 3) and
    barycentric weights (k, 3)."""

    extent: tuple[float, float, float, float]
    shape: tuple[int, int]
    pixels: np.ndarray
    corners: np.ndarray
    weights: np.ndarray

    def image(self, values: np.ndarray) -> np.ndarray:
        """The field ``values`` (n_vertices,) as a (rows, columns) image, row 0 at y0."""
        out = np.full(self.shape[0] * self.shape[1], np.nan)
        out[self.pixels] = np.einsum("kj,kj->k", self.weights, np.asarray(values, float)[self.corners])
        return out.reshape(self.shape)


def view_raster(view: np.ndarray, faces: np.ndarray, columns: int) -> ViewRaster:
    """Sample the triangles ``faces`` of the 2-D points ``view`` (n, 2) on a grid ``columns``
    pixels wide (square pixels). Every triangle is tested against the pixel centres inside
    its bounding box only, so the cost is that of the mesh plus that of the image."""
    view = np.asarray(view, float)
    a, b, c = (view[faces[:, k]] for k in range(3))
    box_lo, box_hi = np.minimum(np.minimum(a, b), c), np.maximum(np.maximum(a, b), c)  # (reductions over an
    lo, hi = box_lo.min(axis=0), box_hi.max(axis=0)                                    # axis of 3 cost more)
    size = max(float(hi[0] - lo[0]), 1e-9) / columns
    shape = (max(1, int(np.ceil((hi[1] - lo[1]) / size))), columns)
    first = np.ceil((box_lo - lo) / size - 0.5).astype(np.int64)  # first pixel centre inside the box
    last = np.floor((box_hi - lo) / size - 0.5).astype(np.int64)
    first = np.maximum(first, 0)
    last = np.minimum(last, [shape[1] - 1, shape[0] - 1])
    span = np.maximum(last - first + 1, 0)
    count = span[:, 0] * span[:, 1]
    face = np.repeat(np.arange(len(faces)), count)
    offset = np.arange(int(count.sum())) - np.repeat(np.cumsum(count) - count, count)
    col = first[face, 0] + offset % span[face, 0]
    row = first[face, 1] + offset // span[face, 0]
    p = lo + (np.column_stack((col, row)) + 0.5) * size
    ab, ac, ap = b[face] - a[face], c[face] - a[face], p - a[face]
    det = ab[:, 0] * ac[:, 1] - ab[:, 1] * ac[:, 0]
    det = np.where(det == 0.0, np.inf, det)  # a degenerate triangle covers no pixel
    v = (ap[:, 0] * ac[:, 1] - ap[:, 1] * ac[:, 0]) / det
    w = (ab[:, 0] * ap[:, 1] - ab[:, 1] * ap[:, 0]) / det
    u = 1.0 - v - w
    inside = np.flatnonzero((u >= -EDGE) & (v >= -EDGE) & (w >= -EDGE))
    pixel = row[inside] * shape[1] + col[inside]
    pixel, keep = np.unique(pixel, return_index=True)  # a pixel on an edge: its first triangle
    inside = inside[keep]
    extent = (float(lo[0]), float(lo[0] + shape[1] * size), float(lo[1]), float(lo[1] + shape[0] * size))
    return ViewRaster(extent, shape, pixel, faces[face[inside]], np.column_stack((u[inside], v[inside], w[inside])))
