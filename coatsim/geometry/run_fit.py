"""What fitting one run gives: its chain, the deviation verified, and what the user should know."""

from __future__ import annotations

from dataclasses import dataclass

from coatsim.geometry.primitives import Segment


@dataclass(frozen=True)
class RunFit:
    """A run's chain, its verified deviation (mm), whether it keeps the run's curvature
    caps and minimum length (False: loosened caps or the fillet fallback), the junctions
    of the chain that are corners (k: end of segment k; a sparse run σ cannot follow with
    arcs as gentle as its own turning comes back as its lines) and what the user should know."""

    segments: tuple[Segment, ...]
    deviation_mm: float
    limits_kept: bool = True
    corners: tuple[int, ...] = ()
    notes: tuple[str, ...] = ()

    def reversed(self) -> RunFit:
        """The same chain run backwards (an open run's fit with its start pinned, turned round
        to pin the end): segments reversed, corner k (end of segment k) now at n - 2 - k."""
        n = len(self.segments)
        return RunFit(tuple(s.reversed() for s in reversed(self.segments)), self.deviation_mm, self.limits_kept,
                      tuple(sorted(n - 2 - k for k in self.corners)), self.notes)
