"""Ramer–Douglas–Peucker simplification of a polyline (any dimension).

Used twice: on the (t, θ) graph for the paper's method, and on positions for the polyline
program variant.
"""

from __future__ import annotations

import numpy as np


def _segment_distances(points: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Distance of each row of ``points`` to the segment [a, b]."""
    ab = b - a
    denom = float(ab @ ab)
    if denom == 0.0:
        return np.linalg.norm(points - a, axis=1)
    u = np.clip((points - a) @ ab / denom, 0.0, 1.0)
    return np.linalg.norm(points - (a + u[:, None] * ab), axis=1)


def rdp_indices(points: np.ndarray, tolerance: float) -> np.ndarray:
    """Indices of the vertices RDP keeps so every point is within ``tolerance`` of the result.

    ``points`` has shape (n, d); the first and last vertex are always kept. Iterative (no
    recursion limit), O(n log n) on typical curves.
    """
    pts = np.asarray(points, dtype=float)
    n = len(pts)
    if n <= 2:
        return np.arange(n)
    keep = np.zeros(n, dtype=bool)
    keep[0] = keep[-1] = True
    stack = [(0, n - 1)]
    while stack:
        i, j = stack.pop()
        if j - i < 2:
            continue
        d = _segment_distances(pts[i + 1 : j], pts[i], pts[j])
        k = int(np.argmax(d))
        if d[k] > tolerance:
            m = i + 1 + k
            keep[m] = True
            stack.append((i, m))
            stack.append((m, j))
    return np.flatnonzero(keep)


def simplify_closed(points: np.ndarray, tolerance: float) -> np.ndarray:
    """RDP for a closed polyline (last point == first): split at the vertex farthest from
    the first so both halves are simplified with fixed ends. Returns indices, first == 0,
    last == n - 1."""
    pts = np.asarray(points, dtype=float)
    far = int(np.argmax(np.linalg.norm(pts - pts[0], axis=1)))
    if far in (0, len(pts) - 1):
        return rdp_indices(pts, tolerance)
    first = rdp_indices(pts[: far + 1], tolerance)
    second = rdp_indices(pts[far:], tolerance) + far
    return np.concatenate((first, second[1:]))
