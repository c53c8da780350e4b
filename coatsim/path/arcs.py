"""Geometry of a program's Cartesian moves: lengths, points, tangents and tool rotations (a
circular move is the arc through its three poses, :func:`~coatsim.geometry.space.primitives.arc_through`;
the controller turns the tool from its start pose to its via pose, then to its end pose, each at a
constant rate). A controller that turns the tool over a circular move from its start pose to its
end pose whatever the via's orientation (RAPID's circle point, KRL's auxiliary point, URScript's
movec) is read with the via given the orientation that turn has there (:func:`via_on_turn`)."""

from __future__ import annotations

import numpy as np

from coatsim.geometry.space.pose import Pose, slerp
from coatsim.geometry.space.primitives import Arc3, DegenerateArc, arc_through
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


def via_on_turn(start: Pose, via: Pose, end: Pose) -> Pose:
    """``via`` with the tool's orientation where the turn from ``start``'s to ``end``'s at a
    constant rate along the arc through the three has it (three points on no circle: ``via`` as
    it is, for the motion's own check to refuse)."""
    try:
        arc = arc_through(start.translation_mm, via.translation_mm, end.translation_mm)
    except DegenerateArc:
        return via
    return Pose(slerp(start.rotation, end.rotation, _at_via(arc, via))[0], via.translation_mm)


def _at_via(arc: Arc3, via: Pose) -> float:
    """The fraction of ``arc``'s length at which it passes ``via``."""
    return float(arc.nearest(via.translation_mm[None])[1][0]) / arc.length


def move_rotations(move: LinearMove | CircularMove, u: np.ndarray) -> np.ndarray:
    """Tool rotations (n, 3, 3) at fractions ``u`` (n,) of the move's length, as the controller
    turns the tool (module text)."""
    u = np.atleast_1d(np.asarray(u, dtype=float))
    if not isinstance(move, CircularMove):
        return slerp(move.start.rotation, move.end.rotation, u)
    arc = arc_through(move.start.translation_mm, move.via.translation_mm, move.end.translation_mm)
    at_via = min(max(_at_via(arc, move.via), 1e-9), 1.0 - 1e-9)
    first = u <= at_via
    out = np.empty((len(u), 3, 3))
    out[first] = slerp(move.start.rotation, move.via.rotation, u[first] / at_via)
    out[~first] = slerp(move.via.rotation, move.end.rotation, (u[~first] - at_via) / (1.0 - at_via))
    return out
