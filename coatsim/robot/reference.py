"""The programmed path as one chain of 3-D primitives, and distances to it.

Cartesian moves contribute their taught lines and arcs (corners unrounded, so a blended corner
shows up as path error); a joint move contributes the TCP path its joint interpolation
commands. ``progress`` is arc length along this chain (mm).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from coatsim.geometry.space.primitives import Segment3


@dataclass(frozen=True, eq=False)
class ReferencePath:
    """Primitives in execution order with their start offsets (P,) mm and owning move index
    (P,) (-1 for the implicit start move)."""

    primitives: tuple[Segment3, ...]
    offsets: np.ndarray
    moves: np.ndarray

    @property
    def length(self) -> float:
        return float(self.offsets[-1] + self.primitives[-1].length) if self.primitives else 0.0

    def move_span(self, move: int) -> tuple[float, float]:
        """Progress interval (mm) covered by one program move."""
        idx = np.flatnonzero(self.moves == move)
        return float(self.offsets[idx[0]]), float(self.offsets[idx[-1]] + self.primitives[idx[-1]].length)

    def project(self, points: np.ndarray, hint: np.ndarray, window: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Distance (n,), progress (n,) and path curvature (n,) 1/mm of the closest point for each
        point, searching primitives within ``window`` mm of the non-decreasing progress ``hint``."""
        n = len(points)
        dist = np.full(n, np.inf)
        prog = np.zeros(n)
        curv = np.zeros(n)
        for k, prim in enumerate(self.primitives):
            lo = np.searchsorted(hint, self.offsets[k] - window, side="left")
            hi = np.searchsorted(hint, self.offsets[k] + prim.length + window, side="right")
            if hi <= lo:
                continue
            d, s = prim.nearest(points[lo:hi])
            better = d < dist[lo:hi]
            dist[lo:hi] = np.where(better, d, dist[lo:hi])
            prog[lo:hi] = np.where(better, self.offsets[k] + s, prog[lo:hi])
            curv[lo:hi] = np.where(better, prim.curvature, curv[lo:hi])
        return dist, prog, curv


def build_reference(chunks: list[tuple[tuple[Segment3, ...], tuple[int, ...]]]) -> ReferencePath:
    """Chain primitive groups (each with the move index of every primitive) into one path."""
    prims: list[Segment3] = []
    moves: list[int] = []
    for group, owners in chunks:
        prims.extend(group)
        moves.extend(owners)
    lengths = np.array([p.length for p in prims])
    offsets = np.concatenate(([0.0], np.cumsum(lengths)[:-1])) if prims else np.zeros(0)
    return ReferencePath(tuple(prims), offsets, np.asarray(moves, dtype=int))
