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
  the wrist up by half a turn each). The roll then turns too, which bends the slerped axis off
  the great circle.

An arc's via pose is written halfway along the turn from its start pose to its end pose: many
controllers turn the tool so over a circular move whatever the via's orientation (RAPID's circle
point, KRL's auxiliary point, URScript's movec), others through the via's; with the via there,
both turn it alike.

Pieces are halved, the new pose on the wanted axis, until the slerped axis stays within the angle
tolerance of the wanted one and the tool's turning rate changes little at every pose (a rate
that jumps makes the joints change speed at once: the tool slows there) — where halving lowers
the jump: on axes that wobble from point to point (a scan, a coarse mesh) more poses only give
more jumps.

``roll_deg`` turns the tool about its axis by a constant angle on top of either rule.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable, Sequence

import numpy as np

from coatsim.core.errors import InputError
from coatsim.geometry.space.pose import exp_rotation, slerp
from coatsim.geometry.space.primitives import Arc3, Line3, Segment3
from coatsim.geometry.space.rotations import rot_z

ROLL_RULES = ("fixed", "follow")
#: Largest change of the tool's turning rate at a pose, rad per mm of travel (0.06 degree/mm).
MAX_RATE_JUMP_RAD_MM = 1e-3
_SAMPLES = 17  # the slerped axis is compared with the wanted one this often per half piece
Wanted = Callable[[np.ndarray], np.ndarray]  # points (n, 3) -> the wanted unit axes there (n, 3)
_MIN_PIECE_MM = 1e-3
#: a halving for the turning rate leaves pieces at least this long: the controller blends the
#: orientation of shorter ones with their neighbours' (over about 10 mm), which slowed the twin on a
#: saddle's pass to 0.51 of its speed where two 2.3 mm pieces replaced one of 4.5 mm (0.997 without)
RATE_MIN_PIECE_MM = 10.0
_MAX_ROUNDS = 12
_HELPS = 0.75  # a halving for the turning rate is kept where it brings the jump down to this share (smooth axes: ~1/2)


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
    return np.column_stack((x, _cross(z, x), z))


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """a × b of two 3-vectors (np.cross's general machinery costs more than the product here)."""
    return np.array((a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]))


def _carry(rotation: np.ndarray, z_to: np.ndarray) -> np.ndarray:
    """``rotation`` turned by the smallest rotation taking its z onto ``z_to`` (made orthonormal
    again, so that long chains of such turns do not drift)."""
    z = rotation[:, 2]
    axis = _cross(z, z_to)
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
        if via is not None:  # written halfway along the turn from start to end (module text)
            via = slerp(here, end, 0.5)[0]
        out.append(Oriented(seg, here @ roll, None if via is None else via @ roll, end @ roll))
        here = end
    return out


def _stops(out: list[Oriented]) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Every stretch a controller slerps over, piece by piece (a line: start -> end; an arc:
    start -> via, via -> end): the rotations at its ends (m, 3, 3) each, the piece it belongs
    to (m,) and its length (m,) mm."""
    a, b, piece, length = [], [], [], []
    for k, o in enumerate(out):
        half = o.geometry.length if o.via is None else o.geometry.length / 2
        for r0, r1 in ((o.start, o.end),) if o.via is None else ((o.start, o.via), (o.via, o.end)):
            a.append(r0), b.append(r1), piece.append(k), length.append(half)
    return np.array(a), np.array(b), np.array(piece), np.array(length)


def _checked(out: list[Oriented], wanted: Wanted, angle_tol_rad: float) -> tuple[np.ndarray, np.ndarray]:
    """Per piece: whether its slerped axis strays more than ``angle_tol_rad`` from the wanted
    one, and the largest change of the tool's turning rate (world frame, rad/mm) at its via or
    either end: all pieces at once (one rotation log per stretch, one wanted-axis query)."""
    from scipy.spatial.transform import Rotation

    a, b, piece, length = _stops(out)
    steps = Rotation.from_matrix(np.einsum("mji,mjk->mik", a, b)).as_rotvec()  # log(aᵀ b) per stretch
    u = np.linspace(0.0, 1.0, 2 * _SAMPLES - 1)
    first = u <= 0.5
    stop_of, frac, where = [], [], []
    starts = np.searchsorted(piece, np.arange(len(out)))
    for k, o in enumerate(out):
        if o.via is None:
            stop_of.append(np.full(len(u), starts[k])), frac.append(u)
        else:
            stop_of.append(np.where(first, starts[k], starts[k] + 1)), frac.append(np.where(first, 2 * u, 2 * u - 1))
        where.append(o.geometry.points(u * o.geometry.length))
    stop, w = np.concatenate(stop_of), np.concatenate(frac)
    turn = exp_rotation(w[:, None] * steps[stop])
    got = np.einsum("nij,nj->ni", a[stop], turn[:, :, 2])
    want = wanted(np.vstack(where))
    error = np.arctan2(np.linalg.norm(np.cross(got, want), axis=1), np.einsum("ij,ij->i", got, want))
    rate = np.einsum("mij,mj->mi", a, steps) / length[:, None]
    jump = np.linalg.norm(np.diff(rate, axis=0), axis=1)  # between consecutive stretches
    worst = np.zeros(len(out))
    np.maximum.at(worst, piece[:-1], jump)
    np.maximum.at(worst, piece[1:], jump)
    return error.reshape(len(out), len(u)).max(axis=1) > angle_tol_rad, worst


def _halves(piece: AxisPiece, wanted: Wanted) -> tuple[AxisPiece, AxisPiece]:
    """A piece split at its middle, the new poses' axes the wanted ones there."""
    seg, (a0, _, a1) = piece.geometry, piece.axes
    first, second = seg.halves()
    q0, mid, q1 = wanted(np.array([first.via, seg.via, second.via]))
    return AxisPiece(first, (a0, q0, mid)), AxisPiece(second, (mid, q1, a1))


def _split(pieces: list[AxisPiece], which: np.ndarray, wanted: Wanted) -> tuple[list[AxisPiece], np.ndarray]:
    """The pieces with those marked halved, and the index each new piece came from."""
    out, origin = [], []
    for k, p in enumerate(pieces):
        parts = _halves(p, wanted) if which[k] else (p,)
        out.extend(parts)
        origin.extend([k] * len(parts))
    return out, np.array(origin)


def oriented_pieces(pieces: Sequence[AxisPiece], rule: str, roll_deg: float, reference: np.ndarray,
                    wanted: Wanted, angle_tol_rad: float,
                    max_rate_jump: float = MAX_RATE_JUMP_RAD_MM) -> list[Oriented]:
    """The pieces with their tool rotations, halved (the new poses on the wanted axis) where the
    slerped axis strays more than ``angle_tol_rad`` from the wanted one (the roll of ``follow``
    bends it off the great circle), or where the tool's turning rate changes by more than
    ``max_rate_jump`` rad/mm at a pose: the joints must change speed there, within the
    controller's orientation zone, so a large jump slows the tool. A halving for the rate is
    kept only where it clearly lowers the jump: on axes that are noisy at the scale of the piece (a
    scanned or coarsely faceted part) more poses give more jumps, not fewer, and halving on
    would end in micrometre moves."""
    check_rule(rule)
    pieces = list(pieces)
    firm = np.zeros(len(pieces), dtype=bool)  # halving did not lower this piece's rate jump
    for _ in range(_MAX_ROUNDS):
        out = orient(pieces, rule, roll_deg, reference)
        stray, jump = _checked(out, wanted, angle_tol_rad)
        half = np.array([p.geometry.length / 2 for p in pieces])
        stray, rate = stray & (half >= _MIN_PIECE_MM), (jump > max_rate_jump) & (half >= RATE_MIN_PIECE_MM) & ~firm & ~stray
        if not (stray | rate).any():
            return out
        trial, origin = _split(pieces, stray | rate, wanted)
        _, trial_jump = _checked(orient(trial, rule, roll_deg, reference), wanted, angle_tol_rad)
        after = np.zeros(len(pieces))
        np.maximum.at(after, origin, trial_jump)
        futile = rate & (after > _HELPS * jump)
        pieces, origin = _split(pieces, (stray | rate) & ~futile, wanted)
        firm = (firm | futile)[origin] & ~((stray | rate) & ~futile)[origin]
    return orient(pieces, rule, roll_deg, reference)
