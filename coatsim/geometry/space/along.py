"""The wanted spray axis at points of a path fitted to a pass, by where they lie along the pass.

A pass's tool path may come back within the tolerance of itself (over a concave stretch the tool
centre points bunch up; a raster pass on a wavy scan came back within 0.73 mm). Looked up at the
nearest input point, the wanted axis of such a point switches between the two stretches, 37°
apart on that scan, and a fit that follows it splits its segments down to microns around a turn
in place. Here a point of the fitted path is first placed on the path (its arc length; the
point lies on the path, so its nearest path sample is on its own stretch), and each arc length
of the path is matched to an arc length of the input by following both from the start: every
input point is projected onto the path near where the previous one was, never behind it. Input
the path cuts across (a hook within the tolerance, which projects where the path already was)
is skipped, as the path skips it: its axes are not asked for over no length of path.
"""

from __future__ import annotations

import math
from typing import Sequence

import numpy as np
from scipy.spatial import cKDTree

from coatsim.geometry.space.primitives import Segment3

STEP_SHARE = 0.25  # the path is sampled every this share of the tolerance ...
MAX_STEP_MM = 0.1  # ... and at least this densely, ...
MAX_SAMPLES = 2_000_000  # ... in at most this many samples (the spacing grows past it)
_REACH = 4.0       # an input point is looked for this many tolerances before and after its expected place


class AlongPass:
    """The wanted unit axes at points of ``segments`` (a path within ``tolerance_mm`` of the
    input ``points``, in the same order), from the input ``axes`` (unit, one per point)."""

    def __init__(self, segments: Sequence[Segment3], points: np.ndarray, axes: np.ndarray, tolerance_mm: float):
        total = float(sum(seg.length for seg in segments))
        step = max(min(MAX_STEP_MM, STEP_SHARE * tolerance_mm), total / MAX_SAMPLES)
        pieces, offsets, start = [], [], 0.0
        for seg in segments:
            count = max(2, math.ceil(seg.length / step) + 1)
            local = np.linspace(0.0, seg.length, count)
            pieces.append(seg.points(local))
            offsets.append(start + local)
            start += seg.length
        self.samples = np.vstack(pieces)
        self.arc = np.concatenate(offsets)
        self.tree = cKDTree(self.samples)
        self.points, self.axes = np.asarray(points, float), np.asarray(axes, float)
        self.input_s = np.concatenate(([0.0], np.cumsum(np.linalg.norm(np.diff(self.points, axis=0), axis=1))))
        matched = self._matched(tolerance_mm)
        first = np.concatenate(([True], np.diff(matched) > 0))  # input the path cut across maps to where it began
        self.path_s, self.matched_s = matched[first], self.input_s[first]

    def _matched(self, tolerance_mm: float) -> np.ndarray:
        """The path's arc length at each input point: its nearest path point among those within
        the reach of where the previous one was (never before it)."""
        nearest = np.empty(len(self.points), dtype=int)
        here = 0.0
        reach = _REACH * tolerance_mm
        for i, p in enumerate(self.points):
            ahead = here + (self.input_s[i] - self.input_s[i - 1] if i else 0.0)
            lo = int(np.searchsorted(self.arc, here - reach, side="left"))
            hi = max(lo + 1, int(np.searchsorted(self.arc, ahead + reach, side="right")))
            window = self.samples[lo:hi]
            nearest[i] = lo + int(np.argmin(np.einsum("ij,ij->i", window - p, window - p)))
            here = max(here, float(self.arc[nearest[i]]))
        return np.maximum.accumulate(self._refined(self.points, nearest))

    def arc_length(self, x: np.ndarray) -> np.ndarray:
        """The path's arc length (n,) at points ``x`` (n, 3) on it."""
        return self._refined(x, self.tree.query(x)[1])

    def _refined(self, x: np.ndarray, k: np.ndarray) -> np.ndarray:
        """The arc length of the nearest point to each x on the two sample edges around its
        sample k."""
        best_d = np.full(len(x), np.inf)
        best_s = self.arc[k].astype(float)
        last = len(self.samples) - 1
        for a in (np.clip(k - 1, 0, last - 1), np.clip(k, 0, last - 1)):
            p, q = self.samples[a], self.samples[a + 1]
            pq = q - p
            u = np.clip(np.einsum("ij,ij->i", x - p, pq) / np.maximum(np.einsum("ij,ij->i", pq, pq), 1e-300), 0, 1)
            d = np.linalg.norm(x - p - u[:, None] * pq, axis=1)
            closer = d < best_d
            best_d[closer] = d[closer]
            best_s[closer] = (self.arc[a] + u * (self.arc[a + 1] - self.arc[a]))[closer]
        return best_s

    def input_place(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Where points ``x`` (n, 3) on the path lie along the input: the input edge (n,) (from
        point ``edge`` to ``edge + 1``) at the input's arc length matched to theirs, and the
        fraction (n,) of it."""
        s_in = np.interp(self.arc_length(np.atleast_2d(x)), self.path_s, self.matched_s)
        edge = np.clip(np.searchsorted(self.input_s, s_in, side="right") - 1, 0, len(self.points) - 2)
        span = self.input_s[edge + 1] - self.input_s[edge]
        return edge, np.clip((s_in - self.input_s[edge]) / np.where(span > 0, span, 1.0), 0.0, 1.0)

    def __call__(self, x: np.ndarray) -> np.ndarray:
        """The wanted unit axes (n, 3) at points ``x`` (n, 3) on the path: the input axes
        interpolated at their place along the input (:meth:`input_place`)."""
        edge, u = self.input_place(x)
        v = (1 - u)[:, None] * self.axes[edge] + u[:, None] * self.axes[edge + 1]
        return v / np.linalg.norm(v, axis=1)[:, None]
