"""The tool's full orientation along a 3-D pass: its spray axis (given) and its roll about it.

A pass comes as pieces (a Line3 or an Arc3) with the unit spray axis at each piece's start, via
point and end, the interpolated axis within the fit's angle tolerance of the wanted one when it
turns along the great circle between them (coatsim.geometry.space.orient). A controller turns
the whole tool between two given poses by the shortest rotation (slerp); the roll rule decides
the tool's x axis at every pose:

- ``fixed``: the tool is carried along without turning about its axis (parallel transport: the
  rotation between consecutive poses is the smallest one that turns one axis onto the next), from
  a start frame whose x is a program-wide reference direction. The slerp between such poses turns
  the axis exactly along the great circle, so the fit's bound holds as it is.
- ``follow``: the tool's x axis lies along the line of travel (the move's tangent at each pose,
  projected across the axis), pointing with it or against it, whichever is nearer the reference
  (for a pass after another, the tool's x where that one ended: serpentine passes do not wind
  the wrist up by half a turn each). The roll then turns too, which bends the slerped axis off the great
  circle; pieces are halved until it stays within ``max_deviation_rad`` of it.

``roll_deg`` turns the tool about its axis by a constant angle on top of either rule.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence

import numpy as np

from coatsim.core.errors import InputError
from coatsim.geometry.space.orient import slerp_axes
from coatsim.geometry.space.pose import slerp
from coatsim.geometry.space.primitives import Arc3, Line3, Segment3
from coatsim.geometry.space.rotations import rot_z

ROLL_RULES = ("fixed", "follow")
#: With ``follow`` the fit keeps the axis within (1 − this share) of the angle tolerance and the
#: roll may bend it by the rest.
FOLLOW_SHARE = 0.25
_SAMPLES = 17  # the slerped axis is compared with the great circle this often per piece
_MIN_PIECE_MM = 1e-3
_MAX_ROUNDS = 12


@dataclass(frozen=True, eq=False)
class AxisPiece:
    """A move's geometry with the unit spray axis at its start, via point and end."""

    geometry: Segment3
    axes: tuple[np.ndarray, np.ndarray, np.ndarray]


@dataclass(frozen=True, eq=False)
class Oriented:
    """A piece with the tool rotation at its start, via point (arcs; None for a line) and end."""

    geometry: Segment3
    start: np.ndarray
    via: np.ndarray | None
    end: np.ndarray


def check_rule(rule: str) -> str:
    if rule not in ROLL_RULES:
        raise InputError(f"roll: expected one of {', '.join(ROLL_RULES)}, got {rule!r}", parameters=("roll",))
    return rule


def reference_direction(axes: np.ndarray) -> np.ndarray:
    """The direction (3,) the tool's x axis starts from under ``fixed`` (projected across the
    axis): minus the base x axis, as a planar program holds the tool (pointing back to the robot),
    unless that comes within 30 degrees of an axis (n, 3); then the base y axis, the base z axis,
    or else the direction most nearly perpendicular to every axis (the eigenvector of Σ a aᵀ with
    the smallest eigenvalue, its largest component positive)."""
    a = np.asarray(axes, dtype=float)
    for r in (np.array([-1.0, 0.0, 0.0]), np.array([0.0, 1.0, 0.0]), np.array([0.0, 0.0, 1.0])):
        if float(np.abs(a @ r).max()) < math.cos(math.radians(30.0)):
            return r
    _, vectors = np.linalg.eigh(a.T @ a)
    r = vectors[:, 0]
    return r if r[int(np.argmax(np.abs(r)))] > 0 else -r


def _frame(z: np.ndarray, x_hint: np.ndarray) -> np.ndarray:
    """The rotation whose z is ``z`` and whose x is ``x_hint`` made perpendicular to it."""
    x = x_hint - (x_hint @ z) * z
    n = float(np.linalg.norm(x))
    if n < 1e-9:  # the hint lies along the axis: any perpendicular
        x = np.cross(z, [1.0, 0.0, 0.0] if abs(z[0]) < 0.9 else [0.0, 1.0, 0.0])
        n = float(np.linalg.norm(x))
    x = x / n
    return np.column_stack((x, np.cross(z, x), z))


def _carry(rotation: np.ndarray, z_to: np.ndarray) -> np.ndarray:
    """``rotation`` turned by the smallest rotation taking its z onto ``z_to`` (made orthonormal
    again, so that long chains of such turns do not drift)."""
    z = rotation[:, 2]
    axis = np.cross(z, z_to)
    s, c = float(np.linalg.norm(axis)), float(z @ z_to)
    if s < 1e-15:
        return _frame(z_to, rotation[:, 0] if c > 0 else -rotation[:, 0])
    k = axis / s
    kx = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
    turn = np.eye(3) + s * kx + (1.0 - c) * (kx @ kx)
    return _frame(z_to, turn @ rotation[:, 0])


def _tangent(seg: Segment3, where: str) -> np.ndarray:
    if isinstance(seg, Line3):
        return seg.direction
    return {"start": seg.start_tangent, "via": seg.tangents(np.array([seg.length / 2]))[0], "end": seg.end_tangent}[where]


def orient(pieces: Sequence[AxisPiece], rule: str, roll_deg: float, reference: np.ndarray) -> list[Oriented]:
    """The tool rotation at every pose of the pieces (consecutive pieces share their junction pose);
    ``reference`` the direction the tool's x starts nearest to (see the module text)."""
    roll = rot_z(math.radians(roll_deg))
    out: list[Oriented] = []
    here = None  # the rotation at the current pose, before the roll offset
    start_tangent = _tangent(pieces[0].geometry, "start")
    sign = 1.0 if float(start_tangent @ reference) >= 0.0 else -1.0  # follow: along or against the travel
    for k, piece in enumerate(pieces):
        a0, av, a1 = piece.axes
        seg = piece.geometry
        if here is None:
            here = _frame(a0, reference if rule == "fixed" else sign * start_tangent)
        elif rule == "fixed":
            here = _carry(here, a0)  # the same axis at a junction: no turn at all
        via = None
        if isinstance(seg, Arc3):
            via = _carry(here, av) if rule == "fixed" else _frame(av, sign * _tangent(seg, "via"))
        end = _carry(via if via is not None else here, a1) if rule == "fixed" else _frame(a1, sign * _tangent(seg, "end"))
        out.append(Oriented(seg, here @ roll, None if via is None else via @ roll, end @ roll))
        here = end
    return out


def _deviation(o: Oriented, axes: tuple[np.ndarray, np.ndarray, np.ndarray]) -> float:
    """Largest angle (rad) between the slerped tool axis and the great-circle axis of a piece."""
    u = np.linspace(0.0, 1.0, _SAMPLES)
    a0, av, a1 = axes
    if o.via is None:
        got = slerp(o.start, o.end, u)[:, :, 2]
        want = slerp_axes(a0, a1, u)
    else:
        got = np.vstack((slerp(o.start, o.via, u)[:, :, 2], slerp(o.via, o.end, u)[:, :, 2]))
        want = np.vstack((slerp_axes(a0, av, u), slerp_axes(av, a1, u)))
    cross = np.linalg.norm(np.cross(got, want), axis=1)
    return float(np.arctan2(cross, np.einsum("ij,ij->i", got, want)).max())


def _halves(piece: AxisPiece) -> tuple[AxisPiece, AxisPiece]:
    """A piece split at its middle, the axes on the great circles it turns along."""
    seg, (a0, av, a1) = piece.geometry, piece.axes
    mid = seg.via
    if isinstance(seg, Line3):
        am = slerp_axes(a0, a1, np.array([0.5]))[0]
        q0, q1 = slerp_axes(a0, am, np.array([0.5]))[0], slerp_axes(am, a1, np.array([0.5]))[0]
        return (AxisPiece(Line3(seg.start, mid), (a0, q0, am)), AxisPiece(Line3(mid, seg.end), (am, q1, a1)))
    q0, q1 = slerp_axes(a0, av, np.array([0.5]))[0], slerp_axes(av, a1, np.array([0.5]))[0]
    first = Arc3(seg.start, mid, seg.center, seg.normal, seg.radius, seg.sweep / 2)
    second = Arc3(mid, seg.end, seg.center, seg.normal, seg.radius, seg.sweep / 2)
    return AxisPiece(first, (a0, q0, av)), AxisPiece(second, (av, q1, a1))


def oriented_pieces(pieces: Sequence[AxisPiece], rule: str, roll_deg: float, reference: np.ndarray,
                    max_deviation_rad: float) -> list[Oriented]:
    """The pieces with their tool rotations, halved where the roll bends the slerped axis more
    than ``max_deviation_rad`` off the great circle of the given axes (never with ``fixed``)."""
    check_rule(rule)
    pieces = list(pieces)
    for _ in range(_MAX_ROUNDS):
        out = orient(pieces, rule, roll_deg, reference)
        if rule == "fixed":
            return out
        bad = {k for k, (o, p) in enumerate(zip(out, pieces))
               if p.geometry.length / 2 >= _MIN_PIECE_MM and _deviation(o, p.axes) > max_deviation_rad}
        if not bad:
            return out
        pieces = [h for k, p in enumerate(pieces) for h in (_halves(p) if k in bad else (p,))]
    return orient(pieces, rule, roll_deg, reference)
