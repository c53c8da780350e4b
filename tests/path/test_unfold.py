"""Spray axes that keep the tool advancing (coatsim.path.unfold): on the normal over a section
concave tighter than the stand-off the tool centre point would stall or run backwards; the axes
turn only as fast as keeps it advancing, and nowhere else differ from the normals."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from coatsim.path.unfold import MIN_ADVANCE, _lagging, unfolded_axes


def _profile(x: np.ndarray, waves: list[tuple[float, float, float]]) -> tuple[np.ndarray, np.ndarray]:
    """Points of the curve z = sum a sin(x / w + phase) in the xz plane and their spray axes
    (minus the unit normals)."""
    z = sum(a * np.sin(x / w + p) for a, w, p in waves)
    dz = sum(a / w * np.cos(x / w + p) for a, w, p in waves)
    normals = np.column_stack((-dz, np.zeros_like(x), np.ones_like(x)))
    normals /= np.linalg.norm(normals, axis=1)[:, None]
    return np.column_stack((x, np.zeros_like(x), z)), -normals


def _advance(points: np.ndarray, axes: np.ndarray, standoff_mm: float) -> np.ndarray:
    step = np.diff(points, axis=0)
    return np.einsum("ij,ij->i", np.diff(points - standoff_mm * axes, axis=0), step) / np.einsum("ij,ij->i", step, step)


def _tilt_deg(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return np.degrees(np.arctan2(np.linalg.norm(np.cross(a, b), axis=1), np.einsum("ij,ij->i", a, b)))


@settings(max_examples=40, deadline=None)
@given(waves=st.lists(st.tuples(st.floats(1.0, 30.0), st.floats(8.0, 80.0), st.floats(0.0, 6.3)), min_size=1,
                      max_size=3),
       standoff=st.floats(20.0, 200.0), count=st.integers(50, 800), jitter=st.floats(0.0, 0.45), seed=st.integers(0, 99))
def test_the_tool_advances_on_every_step_and_the_axes_leave_the_normals_only_where_it_would_not(
        waves, standoff, count, jitter, seed):
    x = np.linspace(0.0, 300.0, count)
    x[1:-1] += jitter * (x[1] - x[0]) * np.random.default_rng(seed).uniform(-1, 1, count - 2)
    points, axes = _profile(x, waves)
    out = unfolded_axes(points, axes, standoff)
    assert np.allclose(np.linalg.norm(out, axis=1), 1.0)
    given_advance = _advance(points, axes, standoff)
    if given_advance.min() >= MIN_ADVANCE or given_advance.max() <= -MIN_ADVANCE:  # no cusp: a fan stays too
        assert np.array_equal(out, axes)
        return
    assert _advance(points, out, standoff).min() >= MIN_ADVANCE * (1 - 1e-9)
    # no further off the normal than an axis that only lags behind it
    assert _tilt_deg(out, axes).max() <= _tilt_deg(_lagging(points, axes, standoff), axes).max() + 1e-6


def test_over_a_circular_trough_the_axis_lags_by_the_turn_it_cannot_make():
    """A trough of radius 60 mm between flats, 100 mm stand-off: on the normal the tool would run
    backwards at 2/3 of the spot's speed. An axis lagging the normal by δ may turn at most
    (1 - 5 %) / (100 cos δ) rad per mm against the surface's 1 / 60: the lag that builds up over
    the trough is the integral of the difference; the mean of lagging and leading about halves it."""
    r, h, half_turn = 60.0, 100.0, math.radians(40.0)
    arc = np.linspace(-half_turn, half_turn, 801)
    flat = np.linspace(5.0, 200.0, 400)
    bottom = np.column_stack((r * np.sin(arc), np.zeros_like(arc), r - r * np.cos(arc)))
    ends = [bottom[0] + np.outer(-flat[::-1], [math.cos(half_turn), 0.0, -math.sin(half_turn)]),
            bottom[-1] + np.outer(flat, [math.cos(half_turn), 0.0, math.sin(half_turn)])]
    points = np.vstack((ends[0], bottom, ends[1]))
    normal = np.vstack((np.tile([math.sin(half_turn), 0.0, math.cos(half_turn)], (400, 1)),
                        np.column_stack((-np.sin(arc), np.zeros_like(arc), np.cos(arc))),
                        np.tile([-math.sin(half_turn), 0.0, math.cos(half_turn)], (400, 1))))
    lag, ds = 0.0, 1e-3  # the lag grows at 1/r - (1 - MIN_ADVANCE) / (h cos lag) per mm along the trough
    for _ in range(int(round(2 * half_turn * r / ds))):
        lag = max(0.0, lag + ds * (1 / r - (1 - MIN_ADVANCE) / (h * math.cos(lag))))
    lag = math.degrees(lag)
    assert _tilt_deg(_lagging(points, -normal, h), -normal).max() == pytest.approx(lag, rel=0.01)
    out = unfolded_axes(points, -normal, h)
    assert 0.45 * lag <= _tilt_deg(out, -normal).max() <= 0.6 * lag  # the mean, lagging where it folds a hair
    assert _advance(points, out, h).min() >= MIN_ADVANCE * (1 - 1e-9)


def test_a_pass_wholly_inside_a_trough_tighter_than_the_stand_off_stays_on_the_normal():
    """30 mm along a fillet of radius 18 mm under a 100 mm stand-off: the tool runs back at 4.6
    times the spot's speed all along (a fan about the centre of curvature), with no cusp; tilting
    it to advance would leave the normal by tens of degrees at the pass's end."""
    angle = np.linspace(-0.8, 0.8, 60)
    points = np.column_stack((18 * np.sin(angle), np.zeros_like(angle), 18 - 18 * np.cos(angle)))
    axes = np.column_stack((np.sin(angle), np.zeros_like(angle), -np.cos(angle)))
    assert _advance(points, axes, 100.0).max() < -3.5
    assert np.array_equal(unfolded_axes(points, axes, 100.0), axes)
