"""From planned pieces to one timed joint path: the inverse kinematics and the timing of each piece,
the rests of the program's dwells, all on one timeline of simulation steps.

Every piece is solved first (the first pose the arm cannot reach is named with the reason, and a
configuration flip inside a sprayed pass is refused, before any timing); then each is timed. A joint piece (JMOVE, the implicit move from home) is solved to its goal configuration and timed
in joint space; a Cartesian piece is tracked by the IK sample by sample (runs of short
exact-stop pieces solved together) and timed along its path. Each piece also contributes its
programmed reference path (the TCP chords of a joint move), which the measurement projects the
simulated tool onto.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Callable, Iterator

import numpy as np

from coatsim.core.numeric import ROUND_OFF, TINY
from coatsim.core.budgets import limit
from coatsim.core.errors import ExecutionError
from coatsim.geometry.space.primitives import Line3, Segment3
from coatsim.path.toolpath import Dwell, ToolPath
from coatsim.robot.cell import Cell
from coatsim.robot.chain import tcp_positions_mm
from coatsim.robot.configuration import check_no_flip, kept_goal
from coatsim.robot.ik import Residual, Tracker, UnreachablePose
from coatsim.robot.joint_events import joint_path_events
from coatsim.robot.reachability import explained
from coatsim.robot.reachable import accuracy_event, speed_event
from coatsim.robot.sampling import CartesianPiece, JointPiece, step_label
from coatsim.robot.timing import TimedPiece, time_cartesian, time_joint
from coatsim.robot.tooling import mount, to_gun, tool_mismatches



@dataclass(frozen=True, eq=False)
class TimedSegment:
    """A timed piece placed on the timeline, with what the log needs per row: the commanded
    progress (mm), the commanded spray flag and the program move (-1: the implicit move from home)."""

    timed: TimedPiece
    progress: np.ndarray
    spray: np.ndarray
    move: np.ndarray

    @property
    def rows(self) -> int:
        return len(self.timed.t)


@dataclass(frozen=True, eq=False)
class JointPath:
    """The commanded joint path on the simulation grid (consecutive pieces share their rest
    point): configurations and velocities (n, 6), the commanded progress hint,
    spray flag and move per row; the reference path in pieces with their moves, the events met,
    the largest IK residual and the widest blend."""

    q: np.ndarray
    qd: np.ndarray
    hint: np.ndarray
    spray: np.ndarray
    row_move: np.ndarray
    chunks: tuple[tuple[tuple[Segment3, ...], tuple[int, ...]], ...]
    events: tuple[str, ...]
    residual: Residual
    max_blend_mm: float


@dataclass
class Stopwatch:
    """Wall seconds per phase, accumulated (reported on request, never written to a file)."""

    seconds: dict[str, float] = field(default_factory=dict)

    def phase(self, name: str) -> "_Lap":
        return _Lap(self, name)


class _Lap:
    def __init__(self, watch: Stopwatch, name: str) -> None:
        self.watch, self.name = watch, name

    def __enter__(self) -> None:
        self.started = time.perf_counter()

    def __exit__(self, *exc: object) -> None:
        self.watch.seconds[self.name] = self.watch.seconds.get(self.name, 0.0) + time.perf_counter() - self.started


def _joint_target(cell: Cell, q: np.ndarray, label: str) -> np.ndarray:
    """A configuration the program gives, checked against the joint ranges."""
    q = np.asarray(q, dtype=float)
    outside = np.flatnonzero((q < cell.q_min - ROUND_OFF) | (q > cell.q_max + ROUND_OFF))
    if len(outside):
        j = int(outside[0])
        raise ExecutionError(f"{label}: joint {j + 1} at {math.degrees(q[j]):.3f} deg is outside its range "
                             f"{math.degrees(cell.q_min[j]):.1f}..{math.degrees(cell.q_max[j]):.1f} deg")
    return q.copy()


def _rest(cell: Cell, q: np.ndarray, dwell: Dwell, offset: float) -> TimedSegment | None:
    """The arm standing still at ``q`` for the dwell (None if shorter than half a time step)."""
    m = int(round(dwell.seconds / cell.timestep))
    if m == 0:
        return None
    zeros = np.zeros((m + 1, 6))
    timed = TimedPiece(t=np.arange(m + 1) * cell.timestep, q=np.tile(q, (m + 1, 1)), qd=zeros, qdd=zeros,
                       s=np.zeros(m + 1), sd=np.zeros(m + 1))
    return TimedSegment(timed, np.full(m + 1, offset), np.full(m + 1, dwell.spray), np.full(m + 1, dwell.after))


def _first_move(piece: JointPiece | CartesianPiece) -> float:
    """Index of the program move a piece starts with (the implicit move from home: before all)."""
    if isinstance(piece, JointPiece):
        return -0.5 if piece.move is None else float(piece.move)
    return float(piece.move[0])


def _ik_targets(piece: CartesianPiece, mount_r: np.ndarray, mount_p: np.ndarray
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """What the IK tracks on a Cartesian piece: the time the programmed speed allows to each
    sample (s), and the gun's position (mm) and rotation there."""
    m = piece.move
    step_time = np.concatenate(([0.0], np.diff(piece.s))) / piece.speed
    return step_time, piece.position + np.einsum("nij,nj->ni", piece.rotation, mount_p[m]), piece.rotation @ mount_r[m]


class _Timeline:
    """The pieces solved and timed one after the other from the home configuration."""

    def __init__(self, toolpath: ToolPath, cell: Cell, pieces: tuple, watch: Stopwatch) -> None:
        self.toolpath, self.cell, self.pieces, self.watch = toolpath, cell, pieces, watch
        pairs = [mount(m.settings.tool, cell) for m in toolpath.moves]  # the gun in the controller TCP's frame
        self.mount_r, self.mount_p = np.array([r for r, _ in pairs]), np.array([p for _, p in pairs])
        self.tracker = Tracker(cell)
        self.q_now = cell.home.copy()
        self.segments: list[TimedSegment] = []
        self.steps = 0
        self.offset = 0.0
        self.chunks: list[tuple[tuple[Segment3, ...], tuple[int, ...]]] = []
        self.events: list[str] = tool_mismatches(toolpath, cell) + [e for e in (accuracy_event(toolpath, pieces),) if e]
        self.solved: dict[int, tuple] = {}  # IK of pieces solved ahead (runs of short exact-stop moves)
        self.too_fast: list[str] = []
        self.worst = [0.0, 0.0, 0]
        self.max_blend = 0.0
        self.dwells = list(toolpath.dwells)

    def add(self, segment: TimedSegment) -> None:
        self.segments.append(segment)
        self.steps += segment.rows

    def rest_until(self, before: float) -> None:
        """Rest for every dwell that comes before move ``before``."""
        while self.dwells and self.dwells[0].after < before:
            segment = _rest(self.cell, self.q_now, self.dwells.pop(0), self.offset)
            if segment is not None:
                self.add(segment)

    def note(self, events: Iterator[str]) -> None:
        for e in events:
            if e not in self.events:
                self.events.append(e)

    def solve_joint(self, k: int, piece: JointPiece) -> np.ndarray:
        """The goal configuration of a joint move (the IK of its target, or the program's joints)."""
        label = step_label(self.toolpath, piece.move)
        # the implicit first move goes to the start of the first Cartesian move, with its TOOL
        tool_move = piece.move if piece.move is not None else int(self.pieces[k + 1].move[0])
        p_gun, r_gun = to_gun(piece.target.translation_mm, piece.target.rotation, self.mount_r[tool_move],
                              self.mount_p[tool_move])
        if piece.joints_rad is not None:
            q_goal = _joint_target(self.cell, piece.joints_rad, label)
        else:
            q_goal = kept_goal(self.cell, self.q_now, self.tracker.solve_pose(self.q_now, p_gun, r_gun, label))
        self.q_now = q_goal
        return q_goal

    def joint_piece(self, piece: JointPiece, q_goal: np.ndarray) -> None:
        """Time a joint move from where the arm stands to its goal in joint space."""
        label = step_label(self.toolpath, piece.move)
        if np.max(np.abs(q_goal - self.q_now)) < TINY:  # already there
            return
        with self.watch.phase("timing_s"):
            timed = time_joint(self.cell, self.q_now, q_goal, piece.speed_mm_s, label,
                               max_steps=limit("sim_steps") - self.steps)
        tcp = tcp_positions_mm(self.cell, timed.q)
        chords = tuple(Line3(p0, p1) for p0, p1 in zip(tcp[:-1], tcp[1:]))
        owner = -1 if piece.move is None else piece.move
        self.chunks.append((chords, (owner,) * len(chords)))
        along = np.concatenate(([0.0], np.cumsum([c.length for c in chords])))
        self.add(TimedSegment(timed, self.offset + along, np.full(len(timed.t), piece.spray),
                              np.full(len(timed.t), owner)))
        self.offset += float(along[-1])
        self.q_now = q_goal

    def _track(self, k: int, piece: CartesianPiece, labels: list[str]) -> tuple:
        """The IK of a Cartesian piece (with the next pieces' when they can be solved together)."""
        step_time, p_gun, r_gun = _ik_targets(piece, self.mount_r, self.mount_p)
        if k not in self.solved and self.tracker.batchable(piece.s):
            run = []
            while (k + len(run) < len(self.pieces) and isinstance(self.pieces[k + len(run)], CartesianPiece)
                   and self.tracker.batchable(self.pieces[k + len(run)].s)):
                run.append(k + len(run))
            if len(run) > 1:  # the next pieces' IK too, in one go
                targets = [(self.pieces[j].s, *_ik_targets(self.pieces[j], self.mount_r, self.mount_p)) for j in run]
                results = self.tracker.track_run(self.q_now, [(s, p, r, dt) for s, dt, p, r in targets])
                self.solved.update(zip(run, results))
        if k in self.solved:
            return self.solved.pop(k)
        return self.tracker.track(self.q_now, piece.s, p_gun, r_gun, step_time, lambda i: labels[i])

    def solve_cartesian(self, k: int, piece: CartesianPiece) -> np.ndarray:
        """The IK of a Cartesian piece, its events, and no configuration flip where it sprays."""
        labels = [step_label(self.toolpath, int(m)) for m in piece.move]
        qs, wrist, res = self._track(k, piece, labels)
        self.worst = [max(self.worst[0], res.position_mm), max(self.worst[1], res.rotation_deg),
                      max(self.worst[2], res.iterations)]
        self.note(joint_path_events(self.cell, qs, wrist, labels))
        check_no_flip(self.cell, qs, piece.spray, lambda i: labels[i])
        self.too_fast.extend(filter(None, [speed_event(self.cell, piece, qs, labels[int(np.argmax(piece.speed))])]))
        self.q_now = qs[-1]
        return qs

    def cartesian_piece(self, piece: CartesianPiece, qs: np.ndarray) -> None:
        """Time a solved Cartesian piece along its path."""
        label = step_label(self.toolpath, int(piece.move[0]))
        with self.watch.phase("timing_s"):
            timed = time_cartesian(self.cell, piece.s, qs, piece.speed, piece.curvature, label,
                                   max_steps=limit("sim_steps") - self.steps)
        idx = np.clip(np.searchsorted(piece.s, timed.s), 0, len(piece.s) - 1)
        self.add(TimedSegment(timed, self.offset + np.interp(timed.s, piece.s, piece.ref_s), piece.spray[idx],
                              piece.move[idx]))
        self.chunks.append((piece.reference, piece.reference_moves))
        self.offset += float(sum(p.length for p in piece.reference))
        self.max_blend = max(self.max_blend,
                             max(self.toolpath.moves[m].settings.accuracy_mm for m in piece.reference_moves))
        self.q_now = qs[-1]


def solve_and_time(toolpath: ToolPath, cell: Cell, pieces: tuple, watch: Stopwatch) -> JointPath:
    """Every piece of ``toolpath`` solved and timed from the cell's home configuration, with the
    program's dwells as rests; ExecutionError where a piece cannot be reached or timed."""
    line = _Timeline(toolpath, cell, pieces, watch)
    watch.seconds.setdefault("ik_s", 0.0)
    watch.seconds.setdefault("timing_s", 0.0)
    solved = []
    with watch.phase("ik_s"):  # every pose is reached (or the first one that is not is named) before any timing
        try:
            for k, piece in enumerate(pieces):
                solved.append(line.solve_joint(k, piece) if isinstance(piece, JointPiece)
                              else line.solve_cartesian(k, piece))
        except UnreachablePose as error:
            raise explained(error, line.tracker) from None
    line.q_now = cell.home.copy()
    for piece, q in zip(pieces, solved):
        line.rest_until(_first_move(piece))
        if isinstance(piece, JointPiece):
            line.joint_piece(piece, q)
        else:
            line.cartesian_piece(piece, q)
    line.rest_until(float("inf"))
    if not line.segments:
        raise ExecutionError(f"{toolpath.name}: the program moves the tool nowhere")
    events = list(line.events)
    if line.too_fast:
        more = len(line.too_fast) - 1
        events.append(line.too_fast[0] + (f" (and on {more} more stretch{'es' if more > 1 else ''})" if more else ""))
    return _concatenated(line.segments, tuple(line.chunks), tuple(events), Residual(*line.worst), line.max_blend)


def _concatenated(segments: list[TimedSegment], chunks: tuple, events: tuple[str, ...], residual: Residual,
                  max_blend: float) -> JointPath:
    """One timeline on the simulation grid; consecutive segments share their rest point."""
    keep = [slice(None)] + [slice(1, None)] * (len(segments) - 1)
    cat: Callable[[Callable[[TimedSegment], np.ndarray]], np.ndarray] = \
        lambda get: np.concatenate([get(s)[k] for s, k in zip(segments, keep)])  # noqa: E731
    return JointPath(q=cat(lambda s: s.timed.q), qd=cat(lambda s: s.timed.qd),
                     hint=np.maximum.accumulate(cat(lambda s: s.progress)), spray=cat(lambda s: s.spray),
                     row_move=cat(lambda s: s.move), chunks=chunks, events=events, residual=residual,
                     max_blend_mm=max_blend)
