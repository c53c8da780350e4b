"""G2/G3 arcs in the principal planes, both ways: a block's words -> three-point arc pieces (the
reader), a 3-D arc -> plane, direction and centre offsets (the writer).

Planes (RS274/NGC): G17 the XY plane about Z, G18 the ZX plane about Y, G19 the YZ plane about X;
G3 turns counter-clockwise seen from the positive end of that axis (a positive turn about it),
G2 clockwise. ``I J K`` are the centre's offsets from the start along X, Y, Z; ``R`` gives the
radius instead (negative: the arc of more than a half turn). An arc whose end is its start is a
full circle (centre format only); ``P n`` adds n − 1 full turns. A controller refuses an arc whose
start and end are at different distances from the centre by more than 0.5 mm, or by more than
0.005 mm and 0.1 % of the radius (LinuxCNC); within that the tool spirals from one radius to the
other, which the pieces follow.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional

import numpy as np

from coatsim.geometry.space.primitives import Arc3

#: (first axis, second axis, normal axis) of G17, G18, G19: first × second = normal.
PLANES = {17: (0, 1, 2), 18: (2, 0, 1), 19: (1, 2, 0)}
PLANE_OF_AXIS = {axes[2]: plane for plane, axes in PLANES.items()}
#: Radius mismatch a controller accepts (LinuxCNC): always within 0.005 mm, else within 0.1 % up to 0.5 mm.
RADIUS_TOL_MM, RADIUS_TOL_REL, RADIUS_TOL_MAX_MM = 0.005, 0.001, 0.5
FULL_CIRCLE_GAP_MM = 1e-6  # an end this close to the start (in the plane) closes a full circle
_NORMAL_TOL = 1e-9  # an arc's normal this close to an axis lies in that axis's principal plane


class ArcError(ValueError):
    """The words do not describe an arc (the interpreter names the line)."""


def centre_from_radius(start: np.ndarray, end: np.ndarray, radius: float, plane: int, clockwise: bool) -> np.ndarray:
    """The centre of the R-format arc from ``start`` to ``end`` (3-D, program coordinates)."""
    a, b, _ = PLANES[plane]
    chord = np.array([end[a] - start[a], end[b] - start[b]])
    d = float(np.linalg.norm(chord))
    if d < FULL_CIRCLE_GAP_MM:
        raise ArcError("an R-format arc cannot end where it starts (a full circle needs I J K)")
    half = d / 2.0
    if abs(radius) < half - RADIUS_TOL_MM:
        raise ArcError(f"radius {abs(radius):g} is shorter than half the chord ({half:g})")
    h = math.sqrt(max(radius * radius - half * half, 0.0))
    left = np.array([-chord[1], chord[0]]) / d
    side = (1.0 if not clockwise else -1.0) * (1.0 if radius > 0 else -1.0)  # short arc: centre on the turning side
    mid = np.array([start[a], start[b]]) + chord / 2.0 + side * h * left
    centre = np.array(start, dtype=float)
    centre[a], centre[b] = mid
    return centre


def arc_pieces(start: np.ndarray, end: np.ndarray, centre: np.ndarray, plane: int, clockwise: bool,
               turns: int = 1) -> list[tuple[np.ndarray, np.ndarray]]:
    """(via, end) points of the three-point arcs, each at most a half turn, that run the arc
    from ``start`` to ``end`` about ``centre`` (3-D points, program coordinates; the normal
    coordinate of the plane stays that of the start: a helix is the caller's refusal)."""
    a, b, _ = PLANES[plane]
    s = np.array([start[a] - centre[a], start[b] - centre[b]])
    e = np.array([end[a] - centre[a], end[b] - centre[b]])
    rs, re = float(np.linalg.norm(s)), float(np.linalg.norm(e))
    if rs < FULL_CIRCLE_GAP_MM or re < FULL_CIRCLE_GAP_MM:
        raise ArcError("the arc's centre is at its start or end")
    mismatch = abs(rs - re)
    if mismatch > RADIUS_TOL_MAX_MM or (mismatch > RADIUS_TOL_MM and mismatch > RADIUS_TOL_REL * rs):
        raise ArcError(f"the start is {rs:.4f} and the end {re:.4f} from the centre; correct I J K (or R) or the end")
    sign = -1.0 if clockwise else 1.0
    theta_s = math.atan2(s[1], s[0])
    gap = math.remainder(sign * (math.atan2(e[1], e[0]) - theta_s), 2.0 * math.pi) % (2.0 * math.pi)
    closed = float(np.linalg.norm(e - s)) < FULL_CIRCLE_GAP_MM
    sweep = (2.0 * math.pi if closed or gap == 0.0 else gap) + 2.0 * math.pi * (max(turns, 1) - 1)
    n = max(1, math.ceil(sweep / math.pi - 1e-12))

    def point(f: float) -> np.ndarray:
        angle, radius = theta_s + sign * f * sweep, rs + f * (re - rs)
        p = np.array(start, dtype=float)
        p[a], p[b] = centre[a] + radius * math.cos(angle), centre[b] + radius * math.sin(angle)
        return p

    pieces = [(point((k + 0.5) / n), point((k + 1) / n)) for k in range(n)]
    pieces[-1] = (pieces[-1][0], np.array(end, dtype=float))
    return pieces


@dataclass(frozen=True)
class ArcWords:
    """How a G-code block writes an arc: plane (17, 18, 19), ``clockwise`` (G2) or not (G3), the
    end point and the centre's offsets from the start (both in the program's frame)."""

    plane: int
    clockwise: bool
    end: np.ndarray
    offsets: np.ndarray


def arc_words(arc: Arc3) -> Optional[ArcWords]:
    """The G2/G3 of ``arc`` (given in the program's frame), or None when it lies in no
    principal plane."""
    axis = int(np.argmax(np.abs(arc.normal)))
    if abs(abs(float(arc.normal[axis])) - 1.0) > _NORMAL_TOL:
        return None
    return ArcWords(PLANE_OF_AXIS[axis], bool(arc.normal[axis] < 0.0), np.array(arc.end), arc.center - arc.start)
