"""Geometry of a program's Cartesian moves: lengths, points and tangents (a circular move is the
arc through its three poses, :func:`~coatsim.geometry.space.primitives.arc_through`)."""

from __future__ import annotations

import numpy as np

from coatsim.geometry.space.primitives import arc_through
from coatsim.path.toolpath import CircularMove, JointMove, LinearMove, Move


def move_length(move: Move) -> float:
    """Length of the TCP path of a move in mm (chord for a joint move)."""
    if isinstance(move, CircularMove):
        return arc_through(move.start.translation_mm, move.via.translation_mm, move.end.translation_mm).length
    if isinstance(move, LinearMove):
        return float(np.linalg.norm(move.end.translation_mm - move.start.translation_mm))
    start = move.start.translation_mm if move.start is not None else move.target.translation_mm
    return float(np.linalg.norm(move.target.translation_mm - start))


def sample_move(move: LinearMove | CircularMove, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Points (n, 3) and unit tangents (n, 3) at fractions ``u`` (n,) of the move's length."""
    u = np.atleast_1d(np.asarray(u, dtype=float))
    if isinstance(move, CircularMove):
        arc = arc_through(move.start.translation_mm, move.via.translation_mm, move.end.translation_mm)
        angles = u * arc.sweep
        return arc.at_angles(angles), arc.tangents_at_angles(angles)
    if isinstance(move, JointMove):
        raise TypeError("a joint move has no Cartesian path")
    delta = move.end.translation_mm - move.start.translation_mm
    length = float(np.linalg.norm(delta))
    direction = delta / length if length > 0.0 else np.zeros(3)
    return move.start.translation_mm + np.outer(u, delta), np.tile(direction, (len(u), 1))
