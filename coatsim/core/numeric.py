"""The round-off allowances of coatsim's float64 arithmetic, each in one place.

Lengths are millimetres up to 1e9 mm (the coordinate budget) and angles radians; float64 carries
~16 significant digits, so a relative difference of 1e-9 is far above what a computation's
rounding leaves and far below anything a user can measure or a controller can execute.
"""

from __future__ import annotations

import math

#: A relative difference this small is round-off: counts of steps, comparisons against limits.
ROUND_OFF = 1e-9
#: Lengths (mm) and angles (rad) below this are zero: coincident points, degenerate directions.
TINY = 1e-9


def steps_over(length: float, step: float) -> int:
    """How many steps of at most ``step`` cover ``length`` (a length a whole number of steps long,
    up to round-off, takes exactly that number)."""
    return int(math.ceil(length / step - ROUND_OFF))
