"""Motion metrics of one simulated run, measured on the curve proper.

The curve proper is the stretch of the programmed path between the end of the run-in and the
start of the run-out: the gun opens at the start of the run-in, so it spans
``[p_on + lead_in, p_on + lead_in + curve_length]`` in ``progress_mm``, where ``p_on`` is the
progress at the first sprayed row. Every statistic is weighted by the time each log row stands
for (zero-order hold: row k covers [t_k, t_k+1)), so it does not depend on the log's step.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from coatsim.errors import ExecutionError
from coatsim.robot.trajectory_log import TrajectoryLog

AT_SPEED_FRACTION = 0.9  # "at speed": at least this fraction of the programmed speed
STOP_FRACTION = 0.05  # "stopped": below this fraction of the programmed speed


@dataclass(frozen=True)
class CurveSpan:
    """Where the curve proper lies along ``progress_mm``."""

    start_mm: float
    end_mm: float


def curve_span(log: TrajectoryLog, lead_in_mm: float, curve_length_mm: float) -> CurveSpan:
    """The curve proper in progress coordinates (see the module docstring)."""
    if not log.spray.any():
        raise ExecutionError("the simulated run never switches the gun on; no curve to measure")
    p_on = float(log.progress[np.argmax(log.spray)])
    return CurveSpan(p_on + lead_in_mm, p_on + lead_in_mm + curve_length_mm)


def _episodes(flags: np.ndarray) -> int:
    """Number of runs of consecutive True values."""
    f = flags.astype(np.int8)
    return int(f[0] + np.count_nonzero(np.diff(f) == 1)) if len(f) else 0


def motion_metrics(log: TrajectoryLog, speed_mm_s: float, span: CurveSpan) -> dict[str, float | int]:
    """Cycle time, time on the curve, speed uniformity, stops and path error (catalogue names)."""
    t = log.t
    dt = np.append(np.diff(t), 0.0)
    tol = 1e-6 * max(1.0, span.end_mm)
    on_curve = log.spray & (log.progress >= span.start_mm - tol) & (log.progress <= span.end_mm + tol)
    if np.count_nonzero(on_curve) < 2:
        raise ExecutionError("the simulated run has fewer than two sprayed samples on the curve")
    w = dt[on_curve]
    v = log.speed[on_curve]
    curve_time = float(w.sum())
    mean = float(np.sum(w * v) / curve_time)
    std = float(np.sqrt(np.sum(w * (v - mean) ** 2) / curve_time))
    return {
        "cycle_time_s": float(t[-1] - t[0]),
        "curve_time_s": curve_time,
        "excess_time_s": curve_time - (span.end_mm - span.start_mm) / speed_mm_s,
        "fraction_at_speed": float(np.sum(w[v >= AT_SPEED_FRACTION * speed_mm_s]) / curve_time),
        "n_stops": _episodes(v < STOP_FRACTION * speed_mm_s),
        "speed_mean_mm_s": mean,
        "speed_min_mm_s": float(v.min()),
        "speed_cv": std / mean if mean > 0 else float("nan"),
        "max_path_error_mm": float(log.path_error[log.spray].max()),
    }
