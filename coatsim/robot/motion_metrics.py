"""Motion metrics of one executed program, from the logged trajectory over the curve proper.

The curve proper is the progress interval of the spray-on moves (all Cartesian moves when none
sprays) without the lead-in and lead-out lengths named in the program header; a program of a
part has one such interval per contour (per unbroken run of spray-on moves). Its window in
time runs from the last log row not yet past its start to the first row at or past its end;
rest at either end of the window is not counted as a stop.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass
from typing import Sequence

import numpy as np

from coatsim.errors import ExecutionError
from coatsim.robot.trajectory_log import TrajectoryLog

END_TOLERANCE_MM = 0.1  # the curve proper counts as covered this close to its end

AT_SPEED = 0.95  # fraction of the programmed speed that counts as "at speed"
STOPPED = 0.05   # below this fraction of the programmed speed the tool counts as stopped
MOVING = 0.2     # ... and moving again only above this fraction (hysteresis)


@dataclass(frozen=True)
class MotionMetrics:
    """Figures of one run; names carry their units (see the README metrics table)."""

    programmed_speed_mm_s: float
    curve_length_mm: float
    cycle_time_s: float
    ideal_time_s: float
    total_time_s: float
    mean_speed_mm_s: float
    min_speed_mm_s: float
    speed_cv: float
    fraction_at_speed: float
    fraction_at_speed_feasible: float
    stops: int
    max_path_error_mm: float
    rms_path_error_mm: float
    max_joint_speed_ratio: float
    max_joint_accel_ratio: float
    max_ik_residual_mm: float
    max_ik_residual_deg: float

    def as_dict(self) -> dict[str, float | int]:
        return {k: (round(v, 6) if isinstance(v, float) else v) for k, v in asdict(self).items()}


def _stops(speed: np.ndarray, programmed: float) -> int:
    """Number of times the tool comes to rest inside the window.

    A stop is a run below STOPPED of the programmed speed; two runs are one stop unless the
    tool got above MOVING in between (a servo settling around zero); runs touching either
    end of the window do not count (a program that starts or ends its curve at rest).
    """
    slow, moving = speed < STOPPED * programmed, speed > MOVING * programmed
    edges = np.diff(np.concatenate(([0], slow.astype(np.int8), [0])))
    merged: list[list[int]] = []
    for a, b in zip(np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)):  # run = [a, b)
        if merged and not moving[merged[-1][1] : a].any():
            merged[-1][1] = int(b)
        else:
            merged.append([int(a), int(b)])
    return sum(1 for a, b in merged if a > 0 and b < len(speed))


def _window(log: TrajectoryLog, curve: tuple[float, float]) -> slice:
    """Log rows of one curve proper: from the last row not yet past its start (at rest
    there, if the tool stops) to the first row at or past its end."""
    a, b = curve
    i0 = max(int(np.searchsorted(np.maximum.accumulate(log.progress), a, side="right")) - 1, 0)
    # the servo may still trail the commanded end by a few hundredths of a millimetre
    reached = np.flatnonzero(log.progress[i0:] >= b - END_TOLERANCE_MM)
    if i0 >= len(log) or not len(reached):
        raise ExecutionError(f"the simulated tool never covered the curve proper ({a:.1f} to {b:.1f} mm of the path)")
    return slice(i0, i0 + int(reached[0]) + 1)


def motion_metrics(
    log: TrajectoryLog,
    curve: tuple[float, float] | Sequence[tuple[float, float]],
    speed_mm_s: float,
    path_curvature: np.ndarray,
    tool_accel_mm_s2: float,
    v_max: np.ndarray,
    a_max: np.ndarray,
    ik_residual: tuple[float, float],
) -> MotionMetrics:
    """Metrics over the curve proper ``curve`` = (start, end) progress in mm, or over several
    (the contours of a part: times, lengths and stops add up, speeds and path errors are
    taken over all their rows together, fractions are of their total length).

    ``path_curvature`` (n,) is the programmed curvature at each row's closest point; the
    "feasible" fraction counts only rows where speed^2 * curvature <= ``tool_accel_mm_s2``.
    """
    curves = [curve] if np.ndim(curve) == 1 else list(curve)
    windows = [_window(log, c) for c in curves]
    speeds = [log.speed[w] for w in windows]
    steps = [np.linalg.norm(np.diff(log.position[w], axis=0), axis=1) for w in windows]
    fast = np.concatenate([v[:-1] >= AT_SPEED * speed_mm_s for v in speeds])
    feasible = np.concatenate([(speed_mm_s**2 * path_curvature[w][:-1]) <= tool_accel_mm_s2 for w in windows])
    speed, step = np.concatenate(speeds), np.concatenate(steps)
    travelled = float(step.sum())
    dt = float(np.median(np.diff(log.t)))
    qd = np.gradient(log.q, dt, axis=0)
    qdd = np.gradient(qd, dt, axis=0)
    err = np.concatenate([log.path_error[w] for w in windows])
    mean = float(speed.mean())
    length = float(sum(b - a for a, b in curves))
    return MotionMetrics(
        programmed_speed_mm_s=float(speed_mm_s),
        curve_length_mm=length,
        cycle_time_s=float(sum(log.t[w.stop - 1] - log.t[w.start] for w in windows)),
        ideal_time_s=float(length / speed_mm_s),
        total_time_s=float(log.t[-1]),
        mean_speed_mm_s=mean,
        min_speed_mm_s=float(speed.min()),
        speed_cv=float(speed.std() / mean) if mean > 0 else 0.0,
        fraction_at_speed=float(step[fast].sum() / travelled) if travelled > 0 else 0.0,
        fraction_at_speed_feasible=float(step[fast & feasible].sum() / step[feasible].sum())
        if step[feasible].sum() > 0 else 0.0,
        stops=sum(_stops(v, speed_mm_s) for v in speeds),
        max_path_error_mm=float(err.max()),
        rms_path_error_mm=float(np.sqrt(np.mean(err**2))),
        max_joint_speed_ratio=float(np.max(np.abs(qd) / v_max)),
        max_joint_accel_ratio=float(np.max(np.abs(qdd) / a_max)),
        max_ik_residual_mm=float(ik_residual[0]),
        max_ik_residual_deg=float(ik_residual[1]),
    )
