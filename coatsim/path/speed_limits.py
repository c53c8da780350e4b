"""Where the input curve does not allow the programmed speed.

The fitter knows the input curve; the robot stage only sees the program. So that the twin can
measure the lowest speed "where the curve allows the speed" (``motion.min_speed_ratio``) from the
program file alone, a program's process record (coatsim.path.process) lists those stretches:
S0 <= S1 in mm of arc length along the curve proper (from its first point), V the largest speed
the curve allows there in mm/s — the fitter's speed-limited stretches (v = sqrt(a / curvature))
and every true corner as a zero-length stretch at speed 0. A program without the record (written
by hand or by another tool) is measured over its whole curve.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from coatsim.core.errors import InputError
from coatsim.geometry.polysegment import Polysegment


@dataclass(frozen=True)
class SpeedLimit:
    """A stretch [s0_mm, s1_mm] of the curve proper where the curve allows at most v_max_mm_s."""

    s0_mm: float
    s1_mm: float
    v_max_mm_s: float

    def __post_init__(self) -> None:
        values = (self.s0_mm, self.s1_mm, self.v_max_mm_s)
        if not all(math.isfinite(v) for v in values) or self.s1_mm < self.s0_mm or self.v_max_mm_s < 0.0:
            raise InputError(f"speed limit {self.s0_mm:g}:{self.s1_mm:g}:{self.v_max_mm_s:g}: expected "
                             "S0 <= S1 (mm) and a speed >= 0 (mm/s)")

    def scaled(self, factor: float) -> SpeedLimit:
        """The same stretch on a curve ``factor`` times as long (another variant's curve)."""
        return SpeedLimit(self.s0_mm * factor, self.s1_mm * factor, self.v_max_mm_s)


def corner_limits(poly: Polysegment) -> tuple[SpeedLimit, ...]:
    """A zero-speed point at every true corner of ``poly`` (arc length of its junction)."""
    ends, total = [], 0.0
    for seg in poly.segments:
        total += seg.length
        ends.append(total)
    return tuple(SpeedLimit(ends[k], ends[k], 0.0) for k in sorted(poly.corners) if k < len(ends))


def curve_limits(poly: Polysegment) -> tuple[SpeedLimit, ...]:
    """The stretches of ``poly`` where the curve does not allow the programmed speed: the
    fitter's ``speed_limited`` (known when it was given the speed) and every true corner, in
    arc-length order."""
    stretches = [SpeedLimit(float(a), float(b), float(v)) for a, b, v in poly.speed_limited]
    def listed(corner: SpeedLimit) -> bool:
        return any(x.v_max_mm_s == 0.0 and abs(x.s0_mm - corner.s0_mm) <= 1e-6 and abs(x.s1_mm - corner.s1_mm) <= 1e-6
                   for x in stretches)

    corners = [c for c in corner_limits(poly) if not listed(c)]
    return tuple(sorted(stretches + corners, key=lambda lim: (lim.s0_mm, lim.s1_mm)))
