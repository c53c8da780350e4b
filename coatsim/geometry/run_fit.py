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
