"""What a polysegment asks of a tool moving along it at a programmed speed.

On an arc of radius r at speed v the tool accelerates sideways by v² / r; with a tool
acceleration limit a it can keep v only where r >= v² / a, and at most √(a·r) on tighter
arcs. At a corner (a listed tangent break) it must stop. ``speed_limited`` lists the
stretches of the path where the programmed speed cannot be kept, with the highest speed
there; ``max_curvature_jump`` the largest step of curvature at a tangent junction, which the
tool feels as a step v²·Δκ of its sideways acceleration.
"""

from __future__ import annotations

import math

from coatsim.core.errors import InputError
from coatsim.geometry.polysegment import Polysegment

#: Programmed speeds coatsim plans for, mm/s: a micrometre a second up to a kilometre a second
#: (outside, v² under- or overflows the arithmetic long before any machine could move so).
SPEED_RANGE_MM_S = (1e-3, 1e6)

Stretch = tuple[float, float, float]  # (s0 mm, s1 mm, v_max mm/s) along the polysegment


def _pairs(poly: Polysegment) -> list[tuple[int, int]]:
    """(k, k + 1) segment index pairs of every junction, the seam last for a closed chain."""
    n = poly.n_segments
    return [(k, k + 1) for k in range(n - 1)] + ([(n - 1, 0)] if poly.closed and n > 1 else [])


def curvature_limit(speed_mm_s: float | None, tool_accel_mm_s2: float | None) -> float | None:
    """The tightest curvature (1/mm) the tool takes at ``speed_mm_s`` without slowing down, a / v²
    (None without a speed); InputError naming speed_mm_s outside SPEED_RANGE_MM_S."""
    if speed_mm_s is None or tool_accel_mm_s2 is None:
        return None
    lo, hi = SPEED_RANGE_MM_S
    if not lo <= speed_mm_s <= hi:
        raise InputError(f"speed_mm_s: {speed_mm_s:g} mm/s is outside the speeds coatsim plans for ({lo:g} to "
                         f"{hi:g} mm/s); give a speed in that range", parameters=("speed_mm_s",))
    return tool_accel_mm_s2 / (speed_mm_s * speed_mm_s)


def max_curvature_jump(poly: Polysegment) -> float:
    """Largest |Δκ| (1/mm) at a junction that is not a listed corner (0 for one segment)."""
    segs = poly.segments
    return max((abs(segs[b].curvature - segs[a].curvature) for k, (a, b) in enumerate(_pairs(poly))
                if k not in poly.corners), default=0.0)


def speed_limited(poly: Polysegment, speed_mm_s: float, tool_accel_mm_s2: float) -> tuple[Stretch, ...]:
    """Stretches (s0, s1, v_max) where ``speed_mm_s`` exceeds what ``tool_accel_mm_s2``
    allows: runs of consecutive arcs tighter than v² / a (v_max = √(a·r) of the tightest),
    and every corner as a stretch of zero length with v_max 0. Sorted by s0."""
    kappa_limit = tool_accel_mm_s2 / speed_mm_s**2
    out: list[list[float]] = []
    s = 0.0
    previous_limited = False
    for seg in poly.segments:
        tight = abs(seg.curvature) > kappa_limit * (1 + 1e-9)
        if tight:
            v_max = math.sqrt(tool_accel_mm_s2 / abs(seg.curvature))
            if previous_limited:
                out[-1][1] = s + seg.length
                out[-1][2] = min(out[-1][2], v_max)
            else:
                out.append([s, s + seg.length, v_max])
        previous_limited = tight
        s += seg.length
    ends = [sum(seg.length for seg in poly.segments[: k + 1]) for k in poly.corners]
    stretches = [tuple(x) for x in out] + [(e, e, 0.0) for e in ends]
    return tuple(sorted(stretches))
