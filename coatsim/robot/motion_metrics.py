"""Motion metrics of one executed program, from the logged trajectory over the curve proper.

The curve proper is the progress interval of the spray-on moves (all Cartesian moves when none
sprays) without the lead-in and lead-out lengths named in the program header when the gun
covers them (header ``sprayed``; a closed contour is sprayed only along the curve); a program of
a part has one such interval per contour (per unbroken run of spray-on moves). Its window in
time runs from the last log row not yet past its start to the first row at or past its end;
rest at either end of the window is not counted as a stop.

``min_speed_ratio`` looks only where the curve allows the programmed speed: outside the
stretches the program header lists as limited by the curve itself (true corners, turns tighter
than v² / a; see :mod:`coatsim.path.speed_limits`), and outside the distance the tool needs
to brake to, or speed up from, each of them and the rest points at the start of the lead-in and
the end of the lead-out (RAMP_FACTOR x (v² - v_limit²) / 2a at the tool acceleration limit a;
around the seam of a closed curve). Every variant of a curve carries the same stretches, so the figure compares
them on the same ground.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass
from typing import Sequence

import numpy as np

from coatsim.core.errors import ExecutionError
from coatsim.robot.trajectory_log import TrajectoryLog

END_TOLERANCE_MM = 0.1  # the curve proper counts as covered this close to its end

AT_SPEED = 0.95  # fraction of the programmed speed that counts as "at speed"
STOPPED = 0.05   # below this fraction of the programmed speed the tool counts as stopped
MOVING = 0.2     # ... and moving again only above this fraction (hysteresis)
# The braking distance (v² - v_limit²) / 2a is the ideal ramp; the timing's acceleration polygon,
# the path sampling and the servo make the simulated one up to ~20 % longer: allow half again.
RAMP_FACTOR = 1.5


@dataclass(frozen=True)
class MotionMetrics:
    """Figures of one run; names carry their units (see the metric catalogue, coatsim.report.catalogue)."""

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
    min_speed_ratio: float | None
    stops: int
    max_path_error_mm: float
    rms_path_error_mm: float
    max_joint_speed_ratio: float
    max_joint_accel_ratio: float
    max_ik_residual_mm: float
    max_ik_residual_deg: float

    def as_dict(self) -> dict[str, float | int | None]:
        return {k: (round(v, 6) if isinstance(v, float) else v) for k, v in asdict(self).items()}


@dataclass(frozen=True)
class CurveAllowance:
    """What decides where the curve allows the programmed speed: the limited stretches
    (s0_mm, s1_mm, v_max_mm_s) along the curve proper, whether it closes on itself, and the
    lead-in and lead-out lengths (mm) from and to rest."""

    limits: tuple[tuple[float, float, float], ...] = ()
    closed: bool = False
    lead_in_mm: float = 0.0
    lead_out_mm: float = 0.0


def allowed_by_curve(s_mm: np.ndarray, length_mm: float, speed_mm_s: float, tool_accel_mm_s2: float,
                     allowance: CurveAllowance) -> np.ndarray:
    """Boolean mask of arc lengths ``s_mm`` (from the curve proper's start) where the curve
    allows ``speed_mm_s``: at least RAMP_FACTOR x the braking distance (v² - v_limit²) / 2a from every
    limited stretch (cyclically on a closed curve) and from the rest points beyond the leads."""
    s = np.asarray(s_mm, dtype=float)
    rests = [(-allowance.lead_in_mm, -allowance.lead_in_mm, 0.0, False),
             (length_mm + allowance.lead_out_mm, length_mm + allowance.lead_out_mm, 0.0, False)]
    ok = np.ones(len(s), dtype=bool)
    for s0, s1, v, cyclic in rests + [(*lim, allowance.closed) for lim in allowance.limits]:
        if v >= speed_mm_s:
            continue
        ramp = RAMP_FACTOR * (speed_mm_s**2 - v**2) / (2.0 * tool_accel_mm_s2)
        shifts = (-length_mm, 0.0, length_mm) if cyclic else (0.0,)
        gap = np.min([np.maximum(np.maximum(s0 - (s + k), (s + k) - s1), 0.0) for k in shifts], axis=0)
        ok &= gap >= ramp
    return ok


def _stops(speed: np.ndarray, programmed: float | np.ndarray) -> int:
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
    speed_mm_s: float | np.ndarray,
    path_curvature: np.ndarray,
    tool_accel_mm_s2: float,
    v_max: np.ndarray,
    a_max: np.ndarray,
    ik_residual: tuple[float, float],
    allowance: CurveAllowance | Sequence[CurveAllowance] = CurveAllowance(),
) -> MotionMetrics:
    """Metrics over the curve proper ``curve`` = (start, end) progress in mm, or over several
    (the contours of a part, each with its ``allowance``: times, lengths and stops add up,
    speeds and path errors are taken over all their rows together, fractions are of their
    total length).

    ``speed_mm_s``: the programmed speed, or the programmed speed at each row (n,) where it
    varies along the curve (the speed on the trace: every ratio is then to the row's own, the
    largest is reported). ``path_curvature`` (n,) is the programmed curvature at each row's closest point; the
    "feasible" fraction counts only rows where speed^2 * curvature <= ``tool_accel_mm_s2``.
    ``allowance`` says where the curve allows the programmed speed (for ``min_speed_ratio``).
    """
    curves = [curve] if np.ndim(curve) == 1 else list(curve)
    allowances = [allowance] * len(curves) if isinstance(allowance, CurveAllowance) else list(allowance)
    windows = [_window(log, c) for c in curves]
    asked = np.broadcast_to(np.asarray(speed_mm_s, dtype=float), (len(log),))  # programmed speed at each row
    top = float(max(asked[w].max() for w in windows))
    speeds = [log.speed[w] for w in windows]
    steps = [np.linalg.norm(np.diff(log.position[w], axis=0), axis=1) for w in windows]
    fast = np.concatenate([v[:-1] >= AT_SPEED * asked[w][:-1] for v, w in zip(speeds, windows)])
    feasible = np.concatenate([(asked[w][:-1] ** 2 * path_curvature[w][:-1]) <= tool_accel_mm_s2 for w in windows])
    allowed = np.concatenate([allowed_by_curve(log.progress[w] - a, b - a, top, tool_accel_mm_s2, al)
                              for w, (a, b), al in zip(windows, curves, allowances)])
    speed, step = np.concatenate(speeds), np.concatenate(steps)
    ratio = speed / np.concatenate([asked[w] for w in windows])
    travelled = float(step.sum())
    dt = float(np.median(np.diff(log.t)))
    qd = np.gradient(log.q, dt, axis=0)
    qdd = np.gradient(qd, dt, axis=0)
    err = np.concatenate([log.path_error[w] for w in windows])
    mean = float(speed.mean())
    length = float(sum(b - a for a, b in curves))
    return MotionMetrics(
        programmed_speed_mm_s=top,
        curve_length_mm=length,
        cycle_time_s=float(sum(log.t[w.stop - 1] - log.t[w.start] for w in windows)),
        ideal_time_s=float(length / top) if np.ndim(speed_mm_s) == 0 else _ideal_time(steps, [asked[w] for w in windows], length),
        total_time_s=float(log.t[-1]),
        mean_speed_mm_s=mean,
        min_speed_mm_s=float(speed.min()),
        speed_cv=float(speed.std() / mean) if mean > 0 else 0.0,
        fraction_at_speed=float(step[fast].sum() / travelled) if travelled > 0 else 0.0,
        fraction_at_speed_feasible=float(step[fast & feasible].sum() / step[feasible].sum())
        if step[feasible].sum() > 0 else 0.0,
        min_speed_ratio=float(ratio[allowed].min()) if allowed.any() else None,
        stops=sum(_stops(v, asked[w]) for v, w in zip(speeds, windows)),
        max_path_error_mm=float(err.max()),
        rms_path_error_mm=float(np.sqrt(np.mean(err**2))),
        max_joint_speed_ratio=float(np.max(np.abs(qd) / v_max)),
        max_joint_accel_ratio=float(np.max(np.abs(qdd) / a_max)),
        max_ik_residual_mm=float(ik_residual[0]),
        max_ik_residual_deg=float(ik_residual[1]),
    )


def _ideal_time(steps: list[np.ndarray], asked: list[np.ndarray], length_mm: float) -> float:
    """Seconds the curve takes at the speed asked at each row (the log's steps scaled to its length)."""
    step, pace = np.concatenate(steps), np.concatenate([a[:-1] for a in asked])
    return float((step / pace).sum() * length_mm / max(float(step.sum()), 1e-300))


def spot_speed(t: np.ndarray, position_mm: np.ndarray, axis: np.ndarray, standoff_mm: float) -> np.ndarray:
    """Speed (n,) mm/s of the spray spot TCP + standoff · axis: where the coat is made. With the
    gun on the normal of a convex section of radius R it is the tool speed times R / (R + h);
    on a concave one R / (R − h)."""
    return np.linalg.norm(np.gradient(position_mm + standoff_mm * axis, t, axis=0), axis=1)


@dataclass(frozen=True)
class TraceMetrics:
    """The spray spot's speed over the curve proper: the stand-off it is taken at (mm), the speed
    it should have (mm/s: the programmed trace speed, or the tool's when the speed is on the TCP),
    its mean and lowest, and its lowest and highest ratio to that speed where the curve allows
    the programmed speed (None where it nowhere does)."""

    standoff_mm: float
    target_mm_s: float
    mean_mm_s: float
    min_mm_s: float
    min_ratio: float | None
    max_ratio: float | None

    def as_dict(self) -> dict[str, float | None]:
        return {k: (round(v, 6) if isinstance(v, float) else v) for k, v in asdict(self).items()}


def trace_metrics(log: TrajectoryLog, curves: Sequence[tuple[float, float]], speed_mm_s: float, target_mm_s: float,
                  standoff_mm: float, tool_accel_mm_s2: float, allowances: Sequence[CurveAllowance]) -> TraceMetrics:
    """The spot speed's figures over the curve proper (see TraceMetrics); the rows the curve allows
    at speed are those of ``min_speed_ratio``."""
    windows = [_window(log, c) for c in curves]
    spot = np.concatenate([log.spot_speed[w] for w in windows])
    allowed = np.concatenate([allowed_by_curve(log.progress[w] - a, b - a, speed_mm_s, tool_accel_mm_s2, al)
                              for w, (a, b), al in zip(windows, curves, allowances)])
    ratio = spot[allowed] / target_mm_s
    return TraceMetrics(float(standoff_mm), float(target_mm_s), float(spot.mean()), float(spot.min()),
                        float(ratio.min()) if len(ratio) else None, float(ratio.max()) if len(ratio) else None)
