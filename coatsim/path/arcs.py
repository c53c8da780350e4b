"""Geometry of Cartesian moves: the circle through three points, points and tangents on moves.

Shared by the interpreter (which must reject arcs it cannot build), the writers (which must
never emit such an arc) and the robot stage (which samples the programmed path).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from coatsim.path.toolpath import CircularMove, JointMove, LinearMove, Move

# Three points define a circle only if they are distinct and not collinear; these limits
# are far below the 1e-4 mm a written pose can carry, so any arc a writer meant to emit
# passes, while a C1MOVE on the line through its neighbours is reported.
_MIN_POINT_GAP_MM = 1e-6
_MIN_SIN_ANGLE = 1e-10


class DegenerateArc(ValueError):
    """Start, via and end do not define a circle."""


@dataclass(frozen=True, eq=False)
class Circle3:
    """Arc of a circle in space: ``center`` (3,), unit ``normal`` (3,) such that the arc
    turns positively about it, ``radius`` mm, ``sweep`` rad in (0, 2 pi)."""

    center: np.ndarray
    normal: np.ndarray
    radius: float
    sweep: float


def circle_through(start: np.ndarray, via: np.ndarray, end: np.ndarray) -> Circle3:
    """The arc from ``start`` through ``via`` to ``end``; raises DegenerateArc."""
    p0, p1, p2 = (np.asarray(p, dtype=float) for p in (start, via, end))
    a, b = p0 - p2, p1 - p2
    gaps = (np.linalg.norm(a), np.linalg.norm(b), np.linalg.norm(p1 - p0))
    if min(gaps) < _MIN_POINT_GAP_MM:
        raise DegenerateArc("start, via and end points of the arc are not distinct")
    axb = np.cross(a, b)
    area = float(np.linalg.norm(axb))
    if not area > _MIN_SIN_ANGLE * gaps[0] * gaps[1]:
        raise DegenerateArc("start, via and end points of the arc lie on one line")
    center = p2 + np.cross(float(a @ a) * b - float(b @ b) * a, axb) / (2.0 * area * area)
    normal = np.cross(p1 - p0, p2 - p1)
    normal = normal / np.linalg.norm(normal)
    u0, u2 = p0 - center, p2 - center
    radius = float(np.linalg.norm(u0))
    sweep = math.atan2(float(normal @ np.cross(u0, u2)), float(u0 @ u2))
    if sweep <= 0.0:
        sweep += 2.0 * math.pi
    return Circle3(center=center, normal=normal, radius=radius, sweep=sweep)


def arc_offsets(radial: np.ndarray, axis: np.ndarray, angles: np.ndarray) -> np.ndarray:
    """Displacements (n, 3) of a point at ``radial`` (3,) from its centre when turned about
    the unit ``axis`` by each angle; written without ``centre + ...`` so huge radii keep
    their precision."""
    angles = np.asarray(angles, dtype=float)
    s, versine = np.sin(angles)[:, None], (2.0 * np.sin(angles / 2.0) ** 2)[:, None]
    n_x_v = np.cross(axis, radial)
    return s * n_x_v + versine * np.cross(axis, n_x_v)


def move_length(move: Move) -> float:
    """Length of the TCP path of a move in mm (chord for a joint move)."""
    if isinstance(move, CircularMove):
        circle = circle_through(move.start.position, move.via.position, move.end.position)
        return circle.radius * circle.sweep
    if isinstance(move, LinearMove):
        return float(np.linalg.norm(move.end.position - move.start.position))
    start = move.start.position if move.start is not None else move.target.position
    return float(np.linalg.norm(move.target.position - start))


def sample_move(move: LinearMove | CircularMove, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Points (n, 3) and unit tangents (n, 3) at fractions ``u`` (n,) of the move's length."""
    u = np.atleast_1d(np.asarray(u, dtype=float))
    if isinstance(move, CircularMove):
        circle = circle_through(move.start.position, move.via.position, move.end.position)
        radial0 = move.start.position - circle.center
        offsets = arc_offsets(radial0, circle.normal, u * circle.sweep)
        tangents = np.cross(circle.normal, radial0 + offsets) / circle.radius
        return move.start.position + offsets, tangents
    if isinstance(move, JointMove):
        raise TypeError("a joint move has no Cartesian path")
    delta = move.end.position - move.start.position
    length = float(np.linalg.norm(delta))
    direction = delta / length if length > 0.0 else np.zeros(3)
    return move.start.position + np.outer(u, delta), np.tile(direction, (len(u), 1))
