"""Time-optimal timing of one rest-to-rest piece with toppra.

Constraints: joint speed and acceleration limits of the cell (``PLANNING_FRACTION`` of them), the programmed tool speed (a
first-order bound on the path speed, not a post-hoc scale) and, on Cartesian pieces, the tool
acceleration limit applied to the combined tangential and centripetal acceleration. The path is
a cubic spline through the IK samples, parametrised by the TCP arc length (m); gridpoints are the
samples; the piecewise-constant path acceleration between gridpoints (toppra's
``ParametrizeConstAccel``) is integrated exactly, and where the sampled command still exceeds a
joint bound between gridpoints, those intervals are refined until it does not.

A program with exact stops has hundreds of short pieces, so the per-piece overhead counts: the
joint-limit constraints are built once per cell (toppra formats every limit into a string when
one is built), the tool-acceleration facets once per limit, the seidel solver is chosen without
probing for the other solvers on every piece, one spline serves every derivative, and the
sampling is vectorised. toppra itself is imported only when a piece is timed
(:mod:`coatsim.robot.timing_toppra`): importing this module costs no plotting library.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import mujoco
import numpy as np

from coatsim.core.numeric import TINY, steps_over
from coatsim.core.budgets import check_budget
from coatsim.core.errors import ExecutionError
from coatsim.robot.cell import MM, Cell

if TYPE_CHECKING:  # toppra (and the matplotlib it imports) loads when a piece is timed
    from coatsim.robot.timing_toppra import Spline
# The planner commands at most this fraction of each joint's speed and acceleration limit: a
# margin for what the servo must correct beyond the model (a part touched, a payload not in it),
# so that the simulated arm stays within the limits, not only its command.
PLANNING_FRACTION = 0.95
# toppra bounds the joint accelerations at the gridpoints; between them q'(s) sdd + q''(s) sd^2
# can exceed the bound where q''(s) changes fast (a tool that turns with a path whose curvature
# jumps). Intervals where the sampled command exceeds the bound are halved and the piece
# re-timed, at most this many times.
_MAX_REFINEMENTS = 8
_EXCESS = 1e-3  # relative excess of the command over the planning bound that triggers refinement


@dataclass(frozen=True, eq=False)
class TimedPiece:
    """A piece sampled on the simulation grid: t (m,) s from the piece start (the last entry is
    the duration), q, qd, qdd (m, 6), and the path parameter s (m,) with its rate sd (m,)
    (TCP arc length in mm and mm/s for Cartesian pieces, the move fraction for joint pieces)."""

    t: np.ndarray
    q: np.ndarray
    qd: np.ndarray
    qdd: np.ndarray
    s: np.ndarray
    sd: np.ndarray

    @property
    def duration(self) -> float:
        return float(self.t[-1])


def _sample(path: Spline, gridpoints: np.ndarray, sd: np.ndarray, dt: float, s_scale: float, label: str,
            max_steps: float | None) -> TimedPiece:
    """Evaluate the piecewise-constant path acceleration between gridpoints (toppra's
    ParametrizeConstAccel, vectorised) on the time grid k*dt; at most ``max_steps`` steps
    (checked before they are allocated)."""
    ds = np.diff(gridpoints)
    x = sd**2
    accel = 0.5 * (x[1:] - x[:-1]) / ds
    with np.errstate(divide="ignore"):  # a stretch at zero speed takes forever (rejected below)
        knots = np.concatenate(([0.0], np.cumsum(2 * ds / (sd[:-1] + sd[1:]))))
    duration = float(knots[-1])
    if not math.isfinite(duration):
        raise ExecutionError("timing: a path piece has no room to move (zero speed along it); sample it more finely")
    check_budget(f"{label}: simulation steps of {dt * 1e3:g} ms ({duration:.4g} s of motion under the joint limits)",
                 duration / dt, "sim_steps", "raise the programmed SPEED or shorten the program",
                 left=max_steps)
    m = steps_over(duration, dt)
    t = np.minimum(np.arange(m + 1) * dt, duration)
    k = np.minimum(np.searchsorted(knots, t, side="right") - 1, len(accel) - 1)
    h = t - knots[k]
    s = gridpoints[k] + h * sd[k] + 0.5 * h**2 * accel[k]
    v = sd[k] + h * accel[k]
    dq = path(s, 1)
    return TimedPiece(t=t, q=path(s), qd=dq * v[:, None], qdd=path(s, 2) * (v**2)[:, None] + dq * accel[k][:, None],
                      s=s * s_scale, sd=v * s_scale)


def _over_bound(cell: Cell, piece: TimedPiece) -> np.ndarray:
    """Rows whose commanded joint speed or acceleration exceeds the planning bound."""
    limit = PLANNING_FRACTION * (1 + _EXCESS)
    return np.any(np.abs(piece.qd) > limit * cell.v_max, axis=1) | np.any(np.abs(piece.qdd) > limit * cell.a_max, axis=1)


def _timed(cell: Cell, path: Spline, extra: list, grid: np.ndarray, s_scale: float, label: str,
           max_steps: float | None) -> TimedPiece:
    """Parametrise and sample, halving the grid intervals where the command exceeds a joint bound."""
    from coatsim.robot.timing_toppra import parametrize

    for _ in range(_MAX_REFINEMENTS):
        grid_out, sd = parametrize(cell, path, extra, grid, label, PLANNING_FRACTION)
        piece = _sample(path, grid_out, sd, cell.timestep, s_scale, label, max_steps)
        bad = _over_bound(cell, piece)
        if not bad.any():
            return piece
        k = np.searchsorted(grid_out, piece.s[bad] / s_scale, side="right") - 1
        k = np.unique(np.clip(np.concatenate((k - 1, k, k + 1)), 0, len(grid_out) - 2))
        grid = np.union1d(grid_out, (grid_out[k] + grid_out[k + 1]) / 2)
    return _sample(path, *parametrize(cell, path, extra, grid, label, PLANNING_FRACTION), cell.timestep, s_scale, label, max_steps)


def time_cartesian(cell: Cell, s_mm: np.ndarray, q: np.ndarray, speed_mm_s: np.ndarray,
                   curvature_per_mm: np.ndarray, label: str, max_steps: float | None = None) -> TimedPiece:
    """Time a Cartesian piece given its IK samples q (n, 6) at TCP arc lengths s_mm (n,)."""
    from coatsim.robot.timing_toppra import PathSpeedBound, Spline, ToolAcceleration

    s = s_mm * MM
    extra = [PathSpeedBound(s, speed_mm_s * MM), ToolAcceleration(s, curvature_per_mm / MM, cell.tool_accel_mm_s2 * MM)]
    return _timed(cell, Spline(s, q), extra, s, 1.0 / MM, label, max_steps)


# Below this joint travel (rad) a move is timed by a bang-bang profile: toppra's solver fails
# on such short paths (measured: 2e-7 to 1e-5 rad), and the TCP speed limit cannot bind there.
TINY_JOINT_MOVE_RAD = 1e-4


def _bang_bang(cell: Cell, q0: np.ndarray, q1: np.ndarray) -> TimedPiece:
    """Constant acceleration then deceleration, as fast as the joint limits allow."""
    dq = q1 - q0
    duration = max(float(np.max(2.0 * np.sqrt(np.abs(dq) / cell.a_max))), float(np.max(2.0 * np.abs(dq) / cell.v_max)),
                   cell.timestep)
    m = steps_over(duration, cell.timestep)
    t = np.minimum(np.arange(m + 1) * cell.timestep, duration)
    x = t / duration
    first = x <= 0.5
    s = np.where(first, 2.0 * x**2, 1.0 - 2.0 * (1.0 - x) ** 2)
    sd = np.where(first, 4.0 * x, 4.0 * (1.0 - x)) / duration
    sdd = np.where(first, 4.0, -4.0) / duration**2
    sdd[-1] = 0.0
    return TimedPiece(t=t, q=q0 + s[:, None] * dq, qd=sd[:, None] * dq, qdd=sdd[:, None] * dq, s=s, sd=sd)


def time_joint(cell: Cell, q0: np.ndarray, q1: np.ndarray, speed_mm_s: float, label: str,
               n_grid: int = 60, max_steps: float | None = None) -> TimedPiece:
    """Time a joint-interpolated move q0 -> q1; the TCP speed stays within ``speed_mm_s``."""
    if float(np.max(np.abs(q1 - q0))) < TINY_JOINT_MOVE_RAD:
        return _bang_bang(cell, np.asarray(q0, float), np.asarray(q1, float))
    from coatsim.robot.timing_toppra import PathSpeedBound, Spline

    u = np.linspace(0.0, 1.0, n_grid)
    qs = q0 + u[:, None] * (q1 - q0)
    data = mujoco.MjData(cell.model)
    tcp = np.array([cell.forward(data, qk)[0] for qk in qs]) * MM
    dp_du = np.linalg.norm(np.gradient(tcp, u, axis=0), axis=1)
    bound = (speed_mm_s * MM) / np.maximum(dp_du, TINY)
    return _timed(cell, Spline(u, qs), [PathSpeedBound(u, bound)], u, 1.0, label, max_steps)
