"""What a program coatsim wrote records about how it was made, beyond its motions.

The twin runs the program text, not the in-memory plan; so that it can tell each curve proper
from its lead-in and lead-out, and measure the speed only where the curve allows it, a program
carries this record. Each language's writer encodes it in the program file and its reader
decodes it (for Kawasaki AS: ``; coatsim: key=value`` header comments); everything downstream
sees these typed values. A program written by anyone else has the empty record.
"""

from __future__ import annotations

from dataclasses import dataclass

from coatsim.core.errors import InputError
from coatsim.geometry.space.pose import Pose
from coatsim.path.speed_limits import SpeedLimit


#: Where a program's speed holds: at the tool centre point, or at the trace on the surface.
SPEED_ON = ("tcp", "trace")


@dataclass(frozen=True)
class SprayedContour:
    """One sprayed contour: whether it is ``closed`` (sprayed exactly once around, from the
    seam to the seam), whether the gun covers its lead-in and lead-out too (``leads_sprayed``:
    an open contour; a closed one is sprayed on its curve only, no double coat at the seam), and
    the stretches of its curve proper where the curve does not allow the programmed speed."""

    closed: bool = False
    leads_sprayed: bool = True
    speed_limits: tuple[SpeedLimit, ...] = ()


@dataclass(frozen=True)
class ProcessInfo:
    """The record of a coatsim program (every field None or empty when the program does not
    say: a program written by hand or by another tool).

    ``contours`` holds one entry per sprayed contour in spray order, or a single entry that
    holds for every contour; ``contour_order`` the drawing's contour numbers (1-based) in spray
    order for a program of several contours. ``speed_on`` says where ``speed_mm_s`` holds:
    ``tcp`` (the tool centre point, the programmed speed of every move) or ``trace`` (the spot
    on the surface: the moves' speeds vary so that it moves at that speed). Totals (``curve_length_mm``, segment counts) are
    over every contour.
    """

    variant: str | None = None
    source: str | None = None
    tolerance_mm: float | None = None
    curve_length_mm: float | None = None
    lead_in_mm: float = 0.0
    lead_out_mm: float = 0.0
    standoff_mm: float | None = None
    speed_mm_s: float | None = None
    accuracy_mm: float | None = None
    gun_signal: int | None = None
    frame: Pose | None = None
    n_segments: int | None = None
    n_lines: int | None = None
    n_arcs: int | None = None
    contours: tuple[SprayedContour, ...] = ()
    contour_order: tuple[int, ...] | None = None
    speed_on: str | None = None

    def contours_for(self, n: int, where: str) -> tuple[SprayedContour, ...]:
        """The record of each of ``n`` sprayed contours: one entry holds for all of them, none
        means the defaults; InputError naming ``where`` when the counts disagree."""
        if len(self.contours) == n:
            return self.contours
        if len(self.contours) <= 1:
            return (self.contours[0] if self.contours else SprayedContour(),) * n
        raise InputError(f"{where}: the program records {len(self.contours)} sprayed contours but sprays {n}")
