"""A chain in the σ-tube around a run as the tube fit's unknowns: its knots (arc lengths of the
run where pieces meet), its state at every knot and every piece's curvature vector; and what
the run's ends keep besides their points."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True, eq=False)
class TubeChain:
    """Knots (n + 1,) mm, states (n + 1, 4) = (y_u, y_v, a_u, a_v) and curvature vectors
    (n, 2) 1/mm of a chain of n pieces."""

    knots: np.ndarray
    states: np.ndarray
    kappa: np.ndarray

    @property
    def n(self) -> int:
        return len(self.kappa)

    def params(self) -> np.ndarray:
        """Per piece (s0, s1, y_u, y_v, a_u, a_v, c_u, c_v), shape (n, 8)."""
        return np.column_stack((self.knots[:-1], self.knots[1:], self.states[:-1], self.kappa))

    def merged(self, j: int) -> TubeChain:
        """Pieces j − 1 and j as one (knot j removed), its curvature the length-weighted mean."""
        h = np.diff(self.knots)
        c = (h[j - 1] * self.kappa[j - 1] + h[j] * self.kappa[j]) / (h[j - 1] + h[j])
        return TubeChain(np.delete(self.knots, j), np.delete(self.states, j, axis=0),
                         np.vstack((self.kappa[: j - 1], c, self.kappa[j + 1 :])))

    def split(self, j: int, state: np.ndarray) -> TubeChain:
        """Piece j cut at its middle, the new knot in ``state``."""
        mid = (self.knots[j] + self.knots[j + 1]) / 2
        return TubeChain(np.insert(self.knots, j + 1, mid), np.insert(self.states, j + 1, state, axis=0),
                         np.insert(self.kappa, j, self.kappa[j], axis=0))


@dataclass(frozen=True)
class Ends:
    """What the run's ends keep besides their points: ``start_tangent`` / ``end_tangent``
    the reference tangents there (tilt 0); ``seam`` (2, 2), for a closed loop, turns the
    start state into the end frame (the end state must equal it; the seam point is then
    free in the tube, not pinned to the input's first point)."""

    start_tangent: bool = False
    end_tangent: bool = False
    seam: np.ndarray | None = None
