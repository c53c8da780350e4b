"""The wanted axis at points of a fitted pass by where they lie along it
(coatsim.geometry.space.along): a path that comes back within the tolerance of itself keeps each
stretch's own axes; on a path that does not, the axes are those of the nearest input point."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings, strategies as st

from coatsim.geometry.space.along import AlongPass
from coatsim.geometry.space.primitives import Arc3, Line3


def _hairpin(gap_mm: float) -> tuple[np.ndarray, np.ndarray]:
    """Out along x at y = 0 with the axis straight down, a half turn, back at y = gap with the
    axis tilted 30 degrees."""
    out = np.column_stack((np.linspace(0.0, 100.0, 101), np.zeros(101), np.zeros(101)))
    turn = np.linspace(-math.pi / 2, math.pi / 2, 41)[1:-1]
    bend = np.column_stack((100.0 + gap_mm / 2 * np.cos(turn), gap_mm / 2 + gap_mm / 2 * np.sin(turn), np.zeros(39)))
    back = out[::-1] + [0.0, gap_mm, 0.0]
    points = np.vstack((out, bend, back))
    tilt = np.concatenate((np.zeros(101), np.linspace(0.0, math.radians(30.0), 39), np.full(101, math.radians(30.0))))
    return points, np.column_stack((np.sin(tilt), np.zeros_like(tilt), -np.cos(tilt)))


def test_a_path_that_comes_back_within_the_tolerance_keeps_each_stretchs_axes():
    """Input out at y = 0 and back at y = 0.6 mm (σ 0.5): a fitted path out at y = 0.45 and back
    at y = 0.15 is within σ of both, and each point of its way back lies nearer the input's way
    out (0.15 mm) than its own (0.45 mm). By its place along the pass it gets the axes of the
    way back, 30 degrees from those of the nearest input point."""
    points, axes = _hairpin(0.6)
    y_out, y_back = 0.45, 0.15
    centre = np.array([100.0, (y_out + y_back) / 2, 0.0])
    half = (y_out - y_back) / 2
    path = [Line3(np.array([0.0, y_out, 0.0]), np.array([100.0, y_out, 0.0])),
            Arc3(np.array([100.0, y_out, 0.0]), np.array([100.0, y_back, 0.0]), centre, np.array([0.0, 0.0, -1.0]),
                 half, math.pi),
            Line3(np.array([100.0, y_back, 0.0]), np.array([0.0, y_back, 0.0]))]
    wanted = AlongPass(path, points, axes, 0.5)
    x = np.linspace(5.0, 90.0, 30)
    back = wanted(np.column_stack((x, np.full(30, y_back), np.zeros(30))))
    out = wanted(np.column_stack((x, np.full(30, y_out), np.zeros(30))))
    assert np.allclose(back, axes[-1], atol=1e-9) and np.allclose(out, axes[0], atol=1e-9)


@settings(max_examples=25, deadline=None)
@given(st.integers(0, 2**32 - 1), st.floats(0.05, 1.0))
def test_on_a_path_that_does_not_come_back_the_axes_are_the_nearest_inputs(seed, tolerance):
    """A helix-like pass sampled unevenly, the fitted path its own chords shifted by up to a
    tenth of σ: the axis at each chord's middle is the input's interpolated at the matched
    place, within a hair of the one at the nearest input point."""
    rng = np.random.default_rng(seed)
    t = np.sort(rng.uniform(0.0, 4 * math.pi, 300))
    points = np.column_stack((80 * np.cos(t), 80 * np.sin(t), 10 * t))
    axes = np.column_stack((-np.cos(t), -np.sin(t), 0.2 * np.sin(3 * t)))
    axes /= np.linalg.norm(axes, axis=1)[:, None]
    shift = rng.uniform(-0.1, 0.1, 3) * tolerance
    chords = [Line3(a + shift, b + shift) for a, b in zip(points[:-1], points[1:])]
    wanted = AlongPass(chords, points, axes, tolerance)
    middle = np.array([c.via for c in chords])
    got = wanted(middle)
    expected = (axes[:-1] + axes[1:]) / np.linalg.norm(axes[:-1] + axes[1:], axis=1)[:, None]
    angle = np.degrees(np.arccos(np.clip(np.einsum("ij,ij->i", got, expected), -1.0, 1.0)))
    assert angle.max() < 0.5
