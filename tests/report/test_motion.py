"""Motion metrics on synthetic logs with known answers."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from coatsim.errors import ExecutionError
from coatsim.report.motion import CurveSpan, curve_span, motion_metrics
from coatsim.robot.trajectory_log import TrajectoryLog


def make_log(t: np.ndarray, progress: np.ndarray, spray: np.ndarray | None = None) -> TrajectoryLog:
    n = len(t)
    speed = np.gradient(progress, t)
    pos = np.column_stack((progress, np.zeros(n), np.zeros(n)))
    return TrajectoryLog(t=t, position=pos, axis=np.tile([0, 0, -1.0], (n, 1)), speed=speed,
                         spray=np.ones(n, bool) if spray is None else spray, progress=progress,
                         path_error=np.full(n, 0.01), q=np.zeros((n, 6)))


def test_constant_speed_run_is_entirely_at_speed() -> None:
    t = np.linspace(0.0, 2.0, 2001)
    log = make_log(t, 100.0 * t)
    span = curve_span(log, lead_in_mm=20.0, curve_length_mm=150.0)
    assert (span.start_mm, span.end_mm) == (20.0, 170.0)
    m = motion_metrics(log, 100.0, span)
    assert m["curve_time_s"] == pytest.approx(1.5, abs=2e-3)
    assert m["excess_time_s"] == pytest.approx(0.0, abs=2e-3)
    assert m["fraction_at_speed"] == 1.0
    assert m["n_stops"] == 0
    assert m["speed_mean_mm_s"] == pytest.approx(100.0)
    assert m["speed_cv"] == pytest.approx(0.0, abs=1e-9)
    assert m["cycle_time_s"] == 2.0
    assert m["max_path_error_mm"] == 0.01


def test_dwells_are_counted_and_cost_their_time() -> None:
    # 100 mm/s with two 0.25 s dwells at 50 mm and 100 mm of progress
    t = np.arange(0.0, 2.5 + 1e-9, 0.001)
    moving = np.clip(t, 0, 0.5) + np.clip(t - 0.75, 0, 0.5) + np.clip(t - 1.5, 0, 1.0)
    log = make_log(t, 100.0 * moving)
    m = motion_metrics(log, 100.0, CurveSpan(10.0, 190.0))
    assert m["n_stops"] == 2
    assert m["excess_time_s"] == pytest.approx(0.5, abs=5e-3)
    assert m["fraction_at_speed"] == pytest.approx(1.8 / 2.3, abs=5e-3)
    assert m["speed_min_mm_s"] == pytest.approx(0.0, abs=1e-9)


def test_run_that_never_sprays_cannot_be_measured() -> None:
    t = np.linspace(0.0, 1.0, 11)
    with pytest.raises(ExecutionError, match="never switches the gun on"):
        curve_span(make_log(t, t, np.zeros(11, bool)), 0.0, 1.0)


@settings(max_examples=30, deadline=None)
@given(scale=st.floats(0.2, 5.0), speed=st.floats(50.0, 500.0))
def test_time_scaling_scales_times_and_keeps_fractions(scale: float, speed: float) -> None:
    t = np.linspace(0.0, 1.0, 1001)
    progress = speed * (t - 0.3 * np.sin(2 * np.pi * t) / (2 * np.pi))
    a = motion_metrics(make_log(t, progress), speed, CurveSpan(5.0, speed * 0.9))
    b = motion_metrics(make_log(t * scale, progress), speed / scale, CurveSpan(5.0, speed * 0.9))
    assert b["curve_time_s"] == pytest.approx(a["curve_time_s"] * scale)
    assert b["fraction_at_speed"] == pytest.approx(a["fraction_at_speed"])
    assert b["speed_cv"] == pytest.approx(a["speed_cv"])
    assert b["n_stops"] == a["n_stops"]
