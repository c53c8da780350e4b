"""ToolPath -> dense Cartesian samples, split into rest-to-rest pieces.

Controller semantics modelled here (docs/explanation/controller.md and docs/guide/execute.md):
- a move with ``stop_at_end`` brings the tool to rest at its end point (piece boundary);
- a joint move (JMOVE) starts and ends at rest;
- where two Cartesian moves meet tangentially (heading change below ``TANGENT_TOL_RAD``) the
  tool runs straight through;
- where a move turns back on the previous one (more than 179.5 deg) the tool stops and reverses;
- where the rate at which the tool turns changes between blended moves (each move turns it at its
  own constant rate from its start pose to its end pose, an arc through its via pose), the
  orientation is blended over ``ORIENTATION_ZONE_MM`` either side, as controllers approximate
  orientation over a zone of their own (ABB's zone_ori, KUKA's $APO.CORI): the joints' speeds
  stay continuous, and the orientation departs from the taught one by at most 0.07 times the
  rate change (rad/mm) times the zone length (0.3 degree for a change of 0.4 degree/mm);
- at a true corner between blended moves (CP ON, no stop) the corner is rounded: the tool leaves
  the incoming move ``d`` mm before the corner and joins the outgoing one ``d`` mm after it,
  ``d`` = the accuracy radius of the incoming move, capped at half of each neighbouring move, on a
  cubic blend tangent to both moves (for two lines: the classic parabolic blend). The blend
  belongs to the outgoing move as far as the gun is concerned: a signal that switches as a
  move starts switches where the tool enters the accuracy zone of the corner before it.
Samples are at most ``step`` mm apart and include every primitive's (trimmed) end points exactly.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import mujoco
import numpy as np

from coatsim.core.numeric import TINY, steps_over
from coatsim.core.budgets import check_budget
from coatsim.core.errors import ExecutionError, InputError
from coatsim.geometry.space.pose import Pose
from coatsim.path.toolpath import CircularMove, JointMove, LinearMove, ToolPath
from coatsim.robot.ik_batch import row_norms
from coatsim.geometry.space.primitives import DegenerateArc, Line3, Segment3, arc_through

TANGENT_TOL_RAD = math.radians(0.5)
# A junction turning back by more than this is a reversal: the tool stops there (no blend can
# turn it round; the blend curve would fold onto itself).
REVERSAL_RAD = math.radians(179.5)
MIN_MOVE_MM = 1e-6
SAMPLES_PER_MOVE = 10  # samples the blends at a Cartesian move's ends add, as the budget path_samples counts them
MERGE_MM = 1e-3  # what is left of a move between two blends, below which it gets no sample of its own
# Where the tool's turning rate changes between two blended moves, the controller blends the
# orientation over this far either side (capped at half the distance to the next such change).
ORIENTATION_ZONE_MM = 10.0
_RATE_JUMP_RAD_MM = 1e-5  # a change of the turning rate (rad per mm) above this is blended


@dataclass(frozen=True, eq=False)
class CartesianPiece:
    """One rest-to-rest stretch of Cartesian motion, n samples.

    s (n,) mm from the piece start along the executed (blended) path; position (n, 3) mm;
    rotation (n, 3, 3); tangent (n, 3); curvature (n,) 1/mm; speed (n,) programmed speed mm/s;
    move (n,) index of the program move; spray (n,) bool; ref_s (n,) mm along this piece's
    programmed reference path ``reference`` (the taught lines and arcs, corners unrounded).
    """

    s: np.ndarray
    position: np.ndarray
    rotation: np.ndarray
    tangent: np.ndarray
    curvature: np.ndarray
    speed: np.ndarray
    move: np.ndarray
    spray: np.ndarray
    ref_s: np.ndarray
    reference: tuple[Segment3, ...]
    reference_moves: tuple[int, ...]

    @property
    def length(self) -> float:
        return float(self.s[-1])


@dataclass(frozen=True, eq=False)
class JointPiece:
    """A joint-interpolated move to ``target`` (rest to rest), to the configuration
    ``joints_rad`` when the program gives one; ``move`` is None for the implicit move from home
    to the start of the first Cartesian move."""

    target: Pose
    speed_mm_s: float
    spray: bool
    move: int | None
    joints_rad: np.ndarray | None = None


Piece = CartesianPiece | JointPiece


@dataclass(frozen=True)
class _Span:
    """One Cartesian move resolved to a primitive with its end orientations; an arc also with
    its via orientation ``rv`` at the fraction ``fv`` of its length (the controller turns the
    tool from the start pose to the via pose, then to the end pose, each at a constant rate)."""

    index: int
    prim: Segment3
    r0: np.ndarray
    r1: np.ndarray
    speed: float
    spray: bool
    accuracy: float
    stop: bool
    rv: np.ndarray | None = None
    fv: float = 0.5

    def rotations(self, frac: np.ndarray) -> np.ndarray:
        """Tool rotations (n, 3, 3) at fractions ``frac`` (n,) of the move's length."""
        frac = np.asarray(frac, dtype=float)
        if self.rv is None:
            return _slerp(self.r0, self.r1, frac)
        first = frac <= self.fv
        out = np.empty((len(frac), 3, 3))
        out[first] = _slerp(self.r0, self.rv, frac[first] / self.fv)
        out[~first] = _slerp(self.rv, self.r1, (frac[~first] - self.fv) / (1.0 - self.fv))
        return out


def step_label(toolpath: ToolPath, index: int | None) -> str:
    """How error messages name a program step: source line and instruction kind."""
    if index is None:
        return f"{toolpath.name}: start (joint move from home)"
    move = toolpath.moves[index]
    kind = {"joint": "joint move", "line": "linear move", "arc": "circular move"}[move.kind]  # any language's
    return f"{toolpath.name}: line {move.line} ({kind})"


def _span(toolpath: ToolPath, index: int) -> _Span:
    move = toolpath.moves[index]
    a = np.asarray(move.start.translation_mm, float)
    b = np.asarray(move.end.translation_mm, float)
    if isinstance(move, CircularMove):
        try:
            prim = arc_through(a, np.asarray(move.via.translation_mm, float), b)
        except DegenerateArc:
            raise ExecutionError(
                f"{step_label(toolpath, index)}: start, via and end points are collinear or coincide, "
                "so they define no circle; split a full circle into two circular moves"
            ) from None
        via_s = float(prim.nearest(np.asarray(move.via.translation_mm, float)[None])[1][0])
        rv, fv = np.asarray(move.via.rotation, float), min(max(via_s / prim.length, 1e-9), 1.0 - 1e-9)
    else:
        prim = Line3(a, b)
        rv, fv = None, 0.5
    s = move.settings
    if not s.speed_mm_s > 0:
        raise ExecutionError(f"{step_label(toolpath, index)}: programmed speed must be positive, got {s.speed_mm_s}")
    return _Span(index, prim, np.asarray(move.start.rotation, float), np.asarray(move.end.rotation, float),
                 float(s.speed_mm_s), bool(move.spray), max(float(s.accuracy_mm), 0.0), bool(s.stop_at_end), rv, fv)


def _slerp(r0: np.ndarray, r1: np.ndarray, f: np.ndarray) -> np.ndarray:
    """Rotations (n, 3, 3) from r0 to r1 at fractions f (n,), along the shortest rotation."""
    quat = np.empty(4)
    mujoco.mju_mat2Quat(quat, np.ascontiguousarray(r0.T @ r1).ravel())
    if quat[0] < 0.0:
        quat = -quat  # the shorter way round
    sin_half = float(np.linalg.norm(quat[1:]))
    if sin_half == 0.0:
        return np.broadcast_to(r0, (len(f), 3, 3)).copy()
    x, y, z = quat[1:] / sin_half
    k = np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])
    angle = 2.0 * math.atan2(sin_half, quat[0]) * np.asarray(f, float)
    turn = np.eye(3) + np.sin(angle)[:, None, None] * k + (1.0 - np.cos(angle))[:, None, None] * (k @ k)
    return r0 @ turn


def smooth_orientation(s: np.ndarray, rotations: np.ndarray, zone_mm: float) -> np.ndarray:
    """Rotations (n, 3, 3) at arc lengths ``s`` with every jump of the turning rate blended over
    ``zone_mm`` either side (less where the next jump is nearer): across the zone the orientation
    goes from the incoming rate's continuation to the outgoing one's with weights
    10u³ − 15u⁴ + 6u⁵, so it, its rate and the rate's change are continuous."""
    from scipy.spatial.transform import Rotation

    if len(s) < 3:
        return rotations
    ds = np.diff(s)
    rel = Rotation.from_matrix(np.swapaxes(rotations[:-1], 1, 2) @ rotations[1:])
    rate = rel.as_rotvec() / np.maximum(ds, 1e-12)[:, None]  # body-frame turning rate per interval
    jumps = 1 + np.flatnonzero(np.linalg.norm(np.diff(rate, axis=0), axis=1) > _RATE_JUMP_RAD_MM)
    if not len(jumps):
        return rotations
    # a pose between two samples (an arc's via) makes the interval across it a jump of its own:
    # jumps on consecutive samples are one change, from the rate before them to the rate after
    groups = np.split(jumps, 1 + np.flatnonzero(np.diff(jumps) > 1))
    out = rotations.copy()
    middles = [(s[g[0]] + s[g[-1]]) / 2 for g in groups]
    bounds = np.concatenate(([s[0]], middles, [s[-1]]))
    for k, g in enumerate(groups):
        a, b, mid = int(g[0]), int(g[-1]), middles[k]  # samples on the incoming and the outgoing path
        d = min(zone_mm, (bounds[k + 1] - bounds[k]) / 2, (bounds[k + 2] - bounds[k + 1]) / 2)
        rows = np.flatnonzero(np.abs(s - mid) < d)
        if d <= 0 or len(rows) < 2:
            continue
        r_in = Rotation.from_matrix(rotations[a]) * Rotation.from_rotvec((s[rows] - s[a])[:, None] * rate[a - 1])
        r_out = Rotation.from_matrix(rotations[b]) * Rotation.from_rotvec((s[rows] - s[b])[:, None] * rate[b])
        u = (s[rows] - mid + d) / (2 * d)
        w = (u**3 * (10 - 15 * u + 6 * u**2))[:, None]
        out[rows] = (r_in * Rotation.from_rotvec(w * (r_in.inv() * r_out).as_rotvec())).as_matrix()
    return out


def _uniform(length: float, step: float) -> np.ndarray:
    """Samples every ``step`` or closer from 0 to ``length``, both ends included; at least
    two intervals, so a short rest-to-rest move still has a point where it moves."""
    n = max(2, steps_over(length, step))
    return np.linspace(0.0, length, n + 1)


def _blend(a: np.ndarray, ta: np.ndarray, b: np.ndarray, tb: np.ndarray, d: float, step: float):
    """Cubic Bezier blend from a (tangent ta) to b (tangent tb) with handles 2d/3.

    Returns samples (points, tangents, curvature, chord-length fraction) at most ``step`` apart,
    the first sample (a) excluded.
    """
    ctrl = np.array([a, a + (2 * d / 3) * ta, b - (2 * d / 3) * tb, b])
    dense = _DENSE_BASIS @ ctrl
    arc = np.concatenate(([0.0], np.cumsum(row_norms(np.diff(dense, axis=0)))))
    # at least 8 intervals, so the curvature peak of a short blend is resolved for timing
    s = _uniform(float(arc[-1]), min(step, float(arc[-1]) / 8))[1:]
    u = np.interp(s, arc, _DENSE_W)
    d1, d2 = _bezier_basis(u, 1) @ ctrl, _bezier_basis(u, 2) @ ctrl
    speed = row_norms(d1)
    cross = np.column_stack((d1[:, 1] * d2[:, 2] - d1[:, 2] * d2[:, 1], d1[:, 2] * d2[:, 0] - d1[:, 0] * d2[:, 2],
                             d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]))
    curv = row_norms(cross) / speed**3
    pts = _bezier_basis(u, 0) @ ctrl
    pts[-1] = b
    return pts, d1 / speed[:, None], curv, s / arc[-1], float(arc[-1])


def _bezier_basis(u: np.ndarray, order: int) -> np.ndarray:
    """Weights (n, 4) of the control points in a cubic Bezier's point (order 0) or its first or
    second derivative at parameters ``u`` (n,)."""
    v = 1.0 - u
    if order == 0:
        return np.column_stack((v**3, 3 * v**2 * u, 3 * v * u**2, u**3))
    if order == 1:
        return np.column_stack((-3 * v**2, 3 * v**2 - 6 * v * u, 6 * v * u - 3 * u**2, 3 * u**2))
    return np.column_stack((6 * v, 6 * u - 12 * v, 6 * v - 12 * u, 6 * u))


_DENSE_W = np.linspace(0.0, 1.0, 257)  # the parameters where a blend's arc length is tabulated
_DENSE_BASIS = _bezier_basis(_DENSE_W, 0)


def _heading_change(a: Segment3, b: Segment3) -> float:
    ta, tb = a.tangents(np.array([a.length]))[0], b.tangents(np.array([0.0]))[0]
    return float(math.acos(np.clip(ta @ tb, -1.0, 1.0)))


def _chain_piece(spans: list[_Span], step: float) -> CartesianPiece:
    """Sample a run of Cartesian moves that the controller executes without stopping."""
    n = len(spans)
    trims = [0.0] * (n + 1)  # trims[k] = blend half-length at the junction before span k
    for k in range(1, n):
        a, b = spans[k - 1], spans[k]
        if _heading_change(a.prim, b.prim) > TANGENT_TOL_RAD:
            trims[k] = min(a.accuracy, a.prim.length / 2, b.prim.length / 2)
    cols: dict[str, list[np.ndarray]] = {k: [] for k in ("p", "r", "t", "c", "v", "m", "y", "rs")}
    ref_offset = 0.0

    def add(p, r, t, c, v, m, y, rs):
        for key, val in zip(cols, (p, r, t, c, v, m, y, rs)):
            cols[key].append(val)

    for k, sp in enumerate(spans):
        lo, hi = trims[k], sp.prim.length - trims[k + 1]
        if k == 0:
            s = lo + _uniform(max(hi - lo, 0.0), step)
        elif hi - lo > MERGE_MM or k == n - 1:
            # the first point is the previous blend's (or span's) last sample
            s = lo + np.linspace(0.0, hi - lo, max(1, steps_over(hi - lo, step)) + 1)[1:]
        else:
            # blends that meet mid-move leave (almost) nothing of it: samples a fraction of a
            # micrometre apart would make the joint spline through them swing
            s = np.zeros(0)
        if len(s):
            m = len(s)
            frac = s / sp.prim.length if sp.prim.length > 0 else np.zeros(m)
            add(sp.prim.points(s), sp.rotations(frac), sp.prim.tangents(s), np.full(m, sp.prim.curvature),
                np.full(m, sp.speed), np.full(m, sp.index), np.full(m, sp.spray), ref_offset + s)
        if k + 1 < n and trims[k + 1] > 0:
            nxt, d = spans[k + 1], trims[k + 1]
            a = sp.prim.points(np.array([hi]))[0]
            ta = sp.prim.tangents(np.array([hi]))[0]
            b = nxt.prim.points(np.array([d]))[0]
            tb = nxt.prim.tangents(np.array([d]))[0]
            pts, tan, curv, frac, _ = _blend(a, ta, b, tb, d, step)
            ra = sp.rotations(np.array([hi / sp.prim.length]))[0]
            rb = nxt.rotations(np.array([d / nxt.prim.length]))[0]
            first = frac <= 0.5
            add(pts, _slerp(ra, rb, frac), tan, curv, np.full(len(pts), min(sp.speed, nxt.speed)),
                np.where(first, sp.index, nxt.index), np.full(len(pts), nxt.spray),
                ref_offset + hi + frac * (sp.prim.length - hi + d))
        ref_offset += sp.prim.length
    p = np.vstack(cols["p"])
    # Where the blends at both ends of a short move meet, a blend starts on the sample the
    # previous one ended on: keep one of each pair of coincident samples.
    keep = np.concatenate(([True], np.linalg.norm(np.diff(p, axis=0), axis=1) > TINY))
    p = p[keep]
    s_exec = np.concatenate(([0.0], np.cumsum(np.linalg.norm(np.diff(p, axis=0), axis=1))))
    return CartesianPiece(
        s=s_exec, position=p, rotation=smooth_orientation(s_exec, np.concatenate(cols["r"])[keep], ORIENTATION_ZONE_MM), tangent=np.vstack(cols["t"])[keep],
        curvature=np.concatenate(cols["c"])[keep], speed=np.concatenate(cols["v"])[keep],
        move=np.concatenate(cols["m"]).astype(int)[keep], spray=np.concatenate(cols["y"]).astype(bool)[keep],
        ref_s=np.concatenate(cols["rs"])[keep], reference=tuple(sp.prim for sp in spans),
        reference_moves=tuple(sp.index for sp in spans),
    )


def plan_pieces(toolpath: ToolPath, step: float = 1.0) -> tuple[Piece, ...]:
    """Split ``toolpath`` into rest-to-rest pieces, Cartesian ones sampled every ``step`` mm.

    The number of samples is checked against the budget path_samples before any is made."""
    if not (math.isfinite(step) and step > 0):
        raise InputError(f"sampling step (--step-mm) must be a positive number of mm, got {step}")
    if not toolpath.moves:
        raise ExecutionError(f"{toolpath.name}: the program has no motion")
    spans: dict[int, _Span] = {}
    for index, move in enumerate(toolpath.moves):
        if not isinstance(move, (JointMove, LinearMove, CircularMove)):
            raise ExecutionError(f"{toolpath.name}: unsupported move kind {getattr(move, 'kind', type(move).__name__)!r}")
        if not isinstance(move, JointMove):
            spans[index] = _span(toolpath, index)
    length = sum(sp.prim.length for sp in spans.values())
    check_budget(f"{toolpath.name}: IK samples of the path ({length:.6g} mm every {step:g} mm, and "
                 f"{SAMPLES_PER_MOVE} for each of its {len(spans):,} moves)",
                 length / step + SAMPLES_PER_MOVE * len(spans), "path_samples",
                 "use a larger sampling step (execute --step-mm, or the scenario's fast.sample_step_mm)")
    pieces: list[Piece] = []
    chain: list[_Span] = []

    def flush() -> None:
        if chain:
            pieces.append(_chain_piece(chain, step))
            chain.clear()

    for index, move in enumerate(toolpath.moves):
        if isinstance(move, JointMove):
            flush()
            pieces.append(JointPiece(move.target, float(move.settings.speed_mm_s), bool(move.spray), index,
                                     move.joints_rad))
            continue
        span = spans[index]
        if span.prim.length <= MIN_MOVE_MM:
            if span.stop:
                flush()  # nothing to execute, but the tool comes to rest here (a dwell may follow)
            continue  # a move to where the tool already is
        if chain and _heading_change(chain[-1].prim, span.prim) > REVERSAL_RAD:
            flush()
        chain.append(span)
        if span.stop:
            flush()
    flush()
    if not pieces:
        raise ExecutionError(f"{toolpath.name}: the program moves the tool nowhere")
    first = pieces[0]
    if isinstance(first, CartesianPiece):
        m = toolpath.moves[int(first.move[0])]
        pieces.insert(0, JointPiece(m.start, float(m.settings.speed_mm_s), False, None))
    return tuple(pieces)


def min_motion_time_s(toolpath: ToolPath, pieces: tuple[Piece, ...]) -> float:
    """A lower bound on the time the program takes: every path length at its programmed speed,
    joint moves by the straight distance between their end points, every dwell (the budget of
    simulation steps is checked with it before any timing)."""
    total, here = sum(d.seconds for d in toolpath.dwells), None
    for piece in pieces:
        if isinstance(piece, JointPiece):
            target = np.asarray(piece.target.translation_mm, float)
            distance = 0.0 if here is None else float(np.linalg.norm(target - here))
            total += distance / piece.speed_mm_s if piece.speed_mm_s > 0 else (math.inf if distance else 0.0)
            here = target
        else:
            total += float(np.sum(np.diff(piece.s) / piece.speed[1:]))
            here = piece.position[-1]
    return total
