"""The execute stage: ToolPath -> IK -> timing -> MuJoCo playback -> trajectory log + metrics."""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from coatsim.core.budgets import check_budget, limit
from coatsim.core.errors import ExecutionError, InputError
from coatsim.path.toolpath import Dwell, ToolPath
from coatsim.robot.cell import Cell, load_cell
from coatsim.robot.chain import tcp_positions_mm
from coatsim.robot.checks import check_playback
from coatsim.robot.ik import Residual, Tracker, joint_path_events
from coatsim.robot.motion_metrics import CurveAllowance, MotionMetrics, motion_metrics
from coatsim.robot.playback import play
from coatsim.robot.primitives3d import line
from coatsim.robot.reachable import accuracy_event, speed_event
from coatsim.robot.reference import ReferencePath, build_reference
from coatsim.robot.sampling import CartesianPiece, JointPiece, min_motion_time_s, plan_pieces, step_label
from coatsim.robot.timing import TimedPiece, time_cartesian, time_joint
from coatsim.robot.tooling import mount, to_gun, tool_mismatches, with_tool_changes
from coatsim.robot.trajectory_log import TrajectoryLog

_WINDOW_MM = 10.0  # progress search window around the commanded point (plus blend radii)


@dataclass(frozen=True, eq=False)
class Execution:
    """Result of executing one program: the log, its metrics, the warnings by program step (TOOL
    mismatch, joint-limit approach, singularity, small tracking or limit excesses), the largest
    IK residual, the programmed reference path, the curve-proper progress interval (mm; from
    the first contour's start to the last one's end), wall time per phase (s), and for a part
    each contour's interval and metrics."""

    log: TrajectoryLog
    metrics: MotionMetrics
    events: tuple[str, ...]
    residual: Residual
    reference: ReferencePath
    curve: tuple[float, float]
    wall: dict[str, float] = field(default_factory=dict)
    warnings: tuple[str, ...] = ()
    curves: tuple[tuple[float, float], ...] = ()
    contour_metrics: tuple[MotionMetrics, ...] = ()


@dataclass
class _Segment:
    """A timed piece placed on the global timeline, with what the log needs about it."""

    timed: TimedPiece
    progress: np.ndarray  # commanded progress (mm) per row
    spray: np.ndarray     # commanded spray flag per row
    move: np.ndarray      # program move per row (-1: the implicit move from home)


def _spray_runs(toolpath: ToolPath, cartesian: list[int]) -> list[list[int]]:
    """Indices of the Cartesian moves of each unbroken run of spray-on moves (the contours of a
    part); every Cartesian move as one run if none sprays."""
    runs: list[list[int]] = [[]]
    members = set(cartesian)
    for i, move in enumerate(toolpath.moves):  # a move with the gun off ends a run
        if move.spray and i in members:
            runs[-1].append(i)
        elif not move.spray and runs[-1]:
            runs.append([])
    return [r for r in runs if r] or [cartesian]


def _curves_proper(toolpath: ToolPath, ref: ReferencePath) -> tuple[list[tuple[float, float]], float]:
    """Progress interval of each curve proper and the programmed speed: the sprayed moves of
    each contour, without the lead-in and lead-out where the gun covers them."""
    cartesian = [i for i, m in enumerate(toolpath.moves) if m.kind != "joint" and np.any(ref.moves == i)]
    if not cartesian:
        raise ExecutionError(f"{toolpath.name}: the program has no Cartesian motion to measure")
    runs = _spray_runs(toolpath, cartesian)
    process = toolpath.process
    lead_in, lead_out = process.lead_in_mm, process.lead_out_mm
    spans, inside = [], []
    for run, contour in zip(runs, process.contours_for(len(runs), toolpath.name)):
        a = ref.move_span(run[0])[0] + (lead_in if contour.leads_sprayed else 0.0)
        b = ref.move_span(run[-1])[1] - (lead_out if contour.leads_sprayed else 0.0)
        if b <= a:
            raise InputError(f"{toolpath.name}: lead_in_mm + lead_out_mm leave no curve between them")
        spans.append((a, b))
        inside += [i for i in run if ref.move_span(i)[1] > a and ref.move_span(i)[0] < b]
    speed = max(toolpath.moves[i].settings.speed_mm_s for i in inside)
    return spans, float(speed)


def _joint_target(cell: Cell, q: np.ndarray, label: str) -> np.ndarray:
    """A configuration the program gives, checked against the joint ranges."""
    q = np.asarray(q, dtype=float)
    outside = np.flatnonzero((q < cell.q_min - 1e-9) | (q > cell.q_max + 1e-9))
    if len(outside):
        j = int(outside[0])
        raise ExecutionError(f"{label}: joint {j + 1} at {math.degrees(q[j]):.3f} deg is outside its range "
                             f"{math.degrees(cell.q_min[j]):.1f}..{math.degrees(cell.q_max[j]):.1f} deg")
    return q.copy()


def _rest(cell: Cell, q: np.ndarray, dwell: Dwell, offset: float) -> _Segment | None:
    """The arm standing still at ``q`` for the dwell (None if shorter than half a time step)."""
    m = int(round(dwell.seconds / cell.timestep))
    if m == 0:
        return None
    zeros = np.zeros((m + 1, 6))
    timed = TimedPiece(t=np.arange(m + 1) * cell.timestep, q=np.tile(q, (m + 1, 1)), qd=zeros, qdd=zeros,
                       s=np.zeros(m + 1), sd=np.zeros(m + 1))
    return _Segment(timed, np.full(m + 1, offset), np.full(m + 1, dwell.spray), np.full(m + 1, dwell.after))


def _first_move(piece) -> float:
    """Index of the program move a piece starts with (the implicit move from home: before all)."""
    if isinstance(piece, JointPiece):
        return -0.5 if piece.move is None else float(piece.move)
    return float(piece.move[0])


def _mounts(toolpath: ToolPath, cell: Cell) -> tuple[np.ndarray, np.ndarray]:
    """Per move, where the gun sits in the frame of the controller's TCP: (M, 3, 3), (M, 3) mm."""
    pairs = [mount(m.settings.tool, cell) for m in toolpath.moves]
    return np.array([r for r, _ in pairs]), np.array([p for _, p in pairs])


def _allowances(toolpath: ToolPath, n: int) -> list[CurveAllowance]:
    """Where the program's record says each curve proper allows the programmed speed (no record:
    everywhere but near the rest points at the ends)."""
    process = toolpath.process
    return [CurveAllowance(tuple((lim.s0_mm, lim.s1_mm, lim.v_max_mm_s) for lim in contour.speed_limits),
                           contour.closed, process.lead_in_mm, process.lead_out_mm)
            for contour in process.contours_for(n, toolpath.name)]


def _ik_targets(piece: CartesianPiece, mount_r: np.ndarray, mount_p: np.ndarray
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """What the IK tracks on a Cartesian piece: the time the programmed speed allows to each
    sample (s), and the gun's position (mm) and rotation there."""
    m = piece.move
    step_time = np.concatenate(([0.0], np.diff(piece.s))) / piece.speed
    return step_time, piece.position + np.einsum("nij,nj->ni", piece.rotation, mount_p[m]), piece.rotation @ mount_r[m]


def _batchable_run(tracker: Tracker, pieces: tuple, k: int) -> list[int]:
    """Indices of the consecutive Cartesian pieces from ``k`` whose IK ``track_run`` can solve together."""
    run = []
    while k < len(pieces) and isinstance(pieces[k], CartesianPiece) and tracker.batchable(pieces[k].s):
        run.append(k)
        k += 1
    return run


def execute(toolpath: ToolPath, cell: Cell | None = None, step_mm: float = 1.0) -> Execution:
    """Run ``toolpath`` on the simulated arm, starting from the cell's home configuration.

    The controller computes every pose with the program's TOOL; the IK puts the cell's gun
    where that puts it (see :mod:`coatsim.robot.tooling`). After playback the simulated arm is
    checked against the commanded motion and the joint limits (:mod:`coatsim.robot.checks`):
    ExecutionError when it diverged, warnings for small excesses.
    """
    cell = cell or load_cell()
    wall: dict[str, float] = {"ik_s": 0.0, "timing_s": 0.0}
    t_start = time.perf_counter()
    toolpath = with_tool_changes(toolpath, cell)
    pieces = plan_pieces(toolpath, step_mm)
    least_s = min_motion_time_s(toolpath, pieces)
    check_budget(f"{toolpath.name}: simulation steps of {cell.timestep * 1e3:g} ms (at least {least_s:.4g} s of "
                 "motion and dwells at the programmed speeds)", least_s / cell.timestep, "sim_steps",
                 "raise the programmed SPEED (coatsim program --speed, the scenario's motion.speed_mm_s) or "
                 "shorten the dwells")
    mount_r, mount_p = _mounts(toolpath, cell)
    tracker = Tracker(cell)
    q_now = cell.home.copy()
    segments: list[_Segment] = []
    steps = [0]  # simulation steps of the segments so far (the budget left is limit('sim_steps') - steps)
    chunks: list = []
    events: list[str] = tool_mismatches(toolpath, cell) + [e for e in (accuracy_event(toolpath, pieces),) if e]
    known = set(events)
    solved: dict[int, tuple] = {}  # IK of pieces solved ahead (runs of short exact-stop moves)
    too_fast: list[str] = []
    worst = [0.0, 0.0, 0]
    offset = 0.0
    max_blend = 0.0
    dwells = list(toolpath.dwells)

    def add(segment: _Segment) -> None:
        segments.append(segment)
        steps[0] += len(segment.timed.t)

    def rest_until(before: float) -> None:
        while dwells and dwells[0].after < before:
            segment = _rest(cell, q_now, dwells.pop(0), offset)
            if segment is not None:
                add(segment)

    for k, piece in enumerate(pieces):
        rest_until(_first_move(piece))
        if isinstance(piece, JointPiece):
            label = step_label(toolpath, piece.move)
            # the implicit first move goes to the start of the first Cartesian move, with its TOOL
            tool_move = piece.move if piece.move is not None else int(pieces[k + 1].move[0])
            p_gun, r_gun = to_gun(piece.target.position, piece.target.rotation, mount_r[tool_move], mount_p[tool_move])
            t0 = time.perf_counter()
            if piece.joints_rad is not None:
                q_goal = _joint_target(cell, piece.joints_rad, label)
            else:
                q_goal = tracker.solve_pose(q_now, p_gun, r_gun, label)
            wall["ik_s"] += time.perf_counter() - t0
            if np.max(np.abs(q_goal - q_now)) < 1e-9:
                continue
            t0 = time.perf_counter()
            timed = time_joint(cell, q_now, q_goal, piece.speed_mm_s, label, max_steps=limit("sim_steps") - steps[0])
            wall["timing_s"] += time.perf_counter() - t0
            tcp = tcp_positions_mm(cell, timed.q)
            chords = tuple(line(p0, p1) for p0, p1 in zip(tcp[:-1], tcp[1:]))
            owner = -1 if piece.move is None else piece.move
            chunks.append((chords, (owner,) * len(chords)))
            along = np.concatenate(([0.0], np.cumsum([c.length for c in chords])))
            add(_Segment(timed, offset + along, np.full(len(timed.t), piece.spray), np.full(len(timed.t), owner)))
            offset += float(along[-1])
            q_now = q_goal
            continue
        labels = [step_label(toolpath, int(m)) for m in piece.move]
        step_time, p_gun, r_gun = _ik_targets(piece, mount_r, mount_p)
        t0 = time.perf_counter()
        if k not in solved and tracker.batchable(piece.s):
            run = _batchable_run(tracker, pieces, k)
            if len(run) > 1:  # the next pieces' IK too, in one go
                targets = [(pieces[j].s, *_ik_targets(pieces[j], mount_r, mount_p)) for j in run]
                results = tracker.track_run(q_now, [(s, p, r, dt) for s, dt, p, r in targets])
                solved.update(zip(run, results))
        if k in solved:
            qs, wrist, res = solved.pop(k)
        else:
            qs, wrist, res = tracker.track(q_now, piece.s, p_gun, r_gun, step_time, lambda i: labels[i])
        wall["ik_s"] += time.perf_counter() - t0
        worst = [max(worst[0], res.position_mm), max(worst[1], res.rotation_deg), max(worst[2], res.iterations)]
        for e in joint_path_events(cell, qs, wrist, labels):
            if e not in known:
                known.add(e)
                events.append(e)
        too_fast.extend(filter(None, [speed_event(cell, piece, qs, labels[int(np.argmax(piece.speed))])]))
        t0 = time.perf_counter()
        timed = time_cartesian(cell, piece.s, qs, piece.speed, piece.curvature, labels[0],
                               max_steps=limit("sim_steps") - steps[0])
        wall["timing_s"] += time.perf_counter() - t0
        idx = np.clip(np.searchsorted(piece.s, timed.s), 0, len(piece.s) - 1)
        add(_Segment(timed, offset + np.interp(timed.s, piece.s, piece.ref_s), piece.spray[idx], piece.move[idx]))
        chunks.append((piece.reference, piece.reference_moves))
        offset += float(sum(p.length for p in piece.reference))
        max_blend = max(max_blend, max(toolpath.moves[m].settings.accuracy_mm for m in piece.reference_moves))
        q_now = qs[-1]
    rest_until(float("inf"))
    if not segments:
        raise ExecutionError(f"{toolpath.name}: the program moves the tool nowhere")
    if too_fast:
        events.append(too_fast[0] + (f" (and on {len(too_fast) - 1} more stretches)" if len(too_fast) > 1 else ""))

    # one timeline on the simulation grid; consecutive pieces share their rest point
    keep = [slice(None)] + [slice(1, None)] * (len(segments) - 1)
    cat = lambda attr: np.concatenate([getattr(s.timed, attr)[k] for s, k in zip(segments, keep)])  # noqa: E731
    q, qd, qdd = cat("q"), cat("qd"), cat("qdd")
    hint = np.maximum.accumulate(np.concatenate([s.progress[k] for s, k in zip(segments, keep)]))
    spray = np.concatenate([s.spray[k] for s, k in zip(segments, keep)])
    row_move = np.concatenate([s.move[k] for s, k in zip(segments, keep)])

    t0 = time.perf_counter()
    run = play(cell, q, qd, qdd)
    wall["playback_s"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    events += check_playback(cell, run.t, run.q, run.tcp, q,
                             lambda i: step_label(toolpath, None if row_move[i] < 0 else int(row_move[i])))
    wall["checks_s"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    ref = build_reference(chunks)
    dist, progress, curvature = ref.project(run.tcp, hint, _WINDOW_MM + 2 * max_blend)
    log = TrajectoryLog(t=run.t, position=run.tcp, axis=run.axis, speed=run.speed, spray=spray,
                        progress=progress, path_error=dist, q=run.q)
    spans, speed = _curves_proper(toolpath, ref)
    allowances = _allowances(toolpath, len(spans))
    limits = (curvature, cell.tool_accel_mm_s2, cell.v_max, cell.a_max, (worst[0], worst[1]))
    metrics = motion_metrics(log, spans, speed, *limits, allowances)
    per_contour = tuple(motion_metrics(log, span, speed, *limits, allowance) for span, allowance in zip(spans, allowances)) \
        if len(spans) > 1 else (metrics,)
    wall["metrics_s"] = time.perf_counter() - t0
    wall["total_s"] = time.perf_counter() - t_start
    return Execution(log=log, metrics=metrics, events=tuple(events), residual=Residual(*worst), reference=ref,
                     curve=(spans[0][0], spans[-1][1]), wall=wall, warnings=toolpath.warnings, curves=tuple(spans),
                     contour_metrics=per_contour)
