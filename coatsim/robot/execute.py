"""The execute stage: ToolPath -> pieces -> IK and timing (coatsim.robot.joint_path) -> MuJoCo
playback -> checks -> trajectory log + metrics."""

from __future__ import annotations

import time
from dataclasses import dataclass, field, replace

import numpy as np

from coatsim.core import defaults
from coatsim.core.budgets import check_budget
from coatsim.core.errors import ExecutionError, InputError
from coatsim.path.toolpath import ToolPath
from coatsim.robot.cell import Cell, load_cell
from coatsim.robot.checks import check_playback
from coatsim.robot.collisions import check_collisions
from coatsim.robot.ik import Residual
from coatsim.robot.joint_path import JointPath, Stopwatch, solve_and_time
from coatsim.robot.motion_metrics import (CurveAllowance, MotionMetrics, TraceMetrics, motion_metrics, spot_speed,
                                          trace_metrics)
from coatsim.robot.playback import Playback, play
from coatsim.robot.reference import ReferencePath, build_reference
from coatsim.robot.sampling import min_motion_time_s, plan_pieces, step_label
from coatsim.robot.tooling import with_tool_changes
from coatsim.robot.trajectory_log import TrajectoryLog

_WINDOW_MM = 10.0  # progress search window around the commanded point (plus blend radii)


@dataclass(frozen=True, eq=False)
class Execution:
    """Result of executing one program: the log, its metrics, the warnings by program step (TOOL
    mismatch, joint-limit approach, singularity, small tracking or limit excesses), the largest
    IK residual, the programmed reference path, the curve-proper progress interval (mm; from
    the first contour's start to the last one's end), wall time per phase (s), for a part
    each contour's interval and metrics, and the spray spot's speed on the surface (the
    program's stand-off from its record; 0, the tool's own speed, for a program without one)."""

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
    trace: TraceMetrics | None = None


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


def _asked(toolpath: ToolPath, ref: ReferencePath, progress_mm: np.ndarray) -> np.ndarray:
    """The speed each log row's move asks for (n,) mm/s: with the speed on the trace, every move
    of a pass has its own (see coatsim.path.surface_program), and the tool is measured against it."""
    k = np.clip(np.searchsorted(ref.offsets, progress_mm, side="right") - 1, 0, len(ref.moves) - 1)
    speeds = np.array([m.settings.speed_mm_s for m in toolpath.moves])
    move = ref.moves[k]
    return np.where(move >= 0, speeds[np.maximum(move, 0)], speeds[0])


def _allowances(toolpath: ToolPath, n: int) -> list[CurveAllowance]:
    """Where the program's record says each curve proper allows the programmed speed (no record:
    everywhere but near the rest points at the ends)."""
    process = toolpath.process
    return [CurveAllowance(tuple((lim.s0_mm, lim.s1_mm, lim.v_max_mm_s) for lim in contour.speed_limits),
                           contour.closed, process.lead_in_mm, process.lead_out_mm)
            for contour in process.contours_for(n, toolpath.name)]


def execute(toolpath: ToolPath, cell: Cell | None = None, step_mm: float = defaults.STEP_MM) -> Execution:
    """Run ``toolpath`` on the simulated arm, starting from the cell's home configuration.

    The controller computes every pose with the program's TOOL; the IK puts the cell's gun
    where that puts it (see :mod:`coatsim.robot.tooling`). After playback the simulated arm is
    checked against the commanded motion and the joint limits (:mod:`coatsim.robot.checks`):
    ExecutionError when it diverged, warnings for small excesses. Before playback the commanded
    motion is checked for contact between the arm (with its gun) and the rest of the cell, a part
    added with :func:`coatsim.robot.collisions.with_part` included (Collision, exit 3).

    Args:
        toolpath: the program as read by its language (coatsim.path.toolpath.ToolPath).
        cell: the arm, its gun and anything placed in the cell; default the shipped cell.
        step_mm: the IK sampling step along Cartesian moves, mm.

    Returns:
        The Execution: timed joint trajectory, simulated TCP, motion metrics and events.

    Raises:
        ExecutionError: a pose out of reach (UnreachablePose, with the reason), a configuration
            flip inside a sprayed pass, a collision, or a simulated arm that diverged (exit 3).
        BudgetExceeded: more IK samples or simulation steps than their budgets (exit 2).
    """
    cell = cell or load_cell()
    watch = Stopwatch()
    t_start = time.perf_counter()
    toolpath = with_tool_changes(toolpath, cell)
    pieces = plan_pieces(toolpath, step_mm)
    least_s = min_motion_time_s(toolpath, pieces)
    check_budget(f"{toolpath.name}: simulation steps of {cell.timestep * 1e3:g} ms (at least {least_s:.4g} s of "
                 "motion and dwells at the programmed speeds)", least_s / cell.timestep, "sim_steps",
                 "raise the programmed speed (speed_mm_s) or shorten the dwells", parameters=("speed_mm_s",))
    path = solve_and_time(toolpath, cell, pieces, watch)
    label = lambda i: step_label(toolpath, None if path.row_move[i] < 0 else int(path.row_move[i]))  # noqa: E731
    with watch.phase("collisions_s"):
        check_collisions(cell, path.q, label)
    with watch.phase("playback_s"):
        run = play(cell, path.q, path.qd)
    with watch.phase("checks_s"):
        events = list(path.events) + check_playback(cell, run.t, run.q, run.tcp, path.q, label)
    with watch.phase("metrics_s"):
        measured = _measure(toolpath, cell, run, path)
    watch.seconds["total_s"] = time.perf_counter() - t_start
    return replace(measured, events=tuple(events), wall=watch.seconds)


def _measure(toolpath: ToolPath, cell: Cell, run: Playback, path: JointPath) -> Execution:
    """The simulated tool against the programmed path: the log and the motion metrics of the
    curve proper (of each contour of a part)."""
    ref = build_reference(list(path.chunks))
    dist, progress, curvature = ref.project(run.tcp, path.hint, _WINDOW_MM + 2 * path.max_blend_mm)
    standoff = toolpath.process.standoff_mm or 0.0
    log = TrajectoryLog(t=run.t, position=run.tcp, axis=run.axis, speed=run.speed, spray=path.spray,
                        progress=progress, path_error=dist, q=run.q,
                        trace_speed=spot_speed(run.t, run.tcp, run.axis, standoff))
    spans, speed = _curves_proper(toolpath, ref)
    allowances = _allowances(toolpath, len(spans))
    process = toolpath.process
    target = process.speed_mm_s if process.speed_on == "trace" and process.speed_mm_s else speed
    trace = trace_metrics(log, spans, speed, target, standoff, cell.tool_accel_mm_s2, allowances)
    residual = path.residual
    limits = (curvature, cell.tool_accel_mm_s2, cell.v_max, cell.a_max, (residual.position_mm, residual.rotation_deg))
    asked = _asked(toolpath, ref, progress) if process.speed_on == "trace" else speed
    metrics = motion_metrics(log, spans, asked, *limits, allowances)
    per_contour = tuple(motion_metrics(log, span, asked, *limits, allowance) for span, allowance in zip(spans, allowances)) \
        if len(spans) > 1 else (metrics,)
    return Execution(log=log, metrics=metrics, events=(), residual=residual, reference=ref,
                     curve=(spans[0][0], spans[-1][1]), warnings=toolpath.warnings, curves=tuple(spans),
                     contour_metrics=per_contour, trace=trace)
