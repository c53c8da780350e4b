"""Sparse, noisy passes the tube fit cannot follow: the biarc fallback keeps the honesty rule
(no arc tighter than the curve near it, nor than the speed allows where the input does) and
uses lines meeting at listed corners where no honest arc fits, within σ, certified."""

from __future__ import annotations

import numpy as np
import pytest

from coatsim.geometry.space.curve import make_space_curve
from coatsim.geometry.space.families import FAMILIES
from coatsim.geometry.space.primitives import Arc3
from coatsim.geometry.space.segment import _limits, segment_space_curve
from coatsim.geometry.space.tube_fit import fit_tube_run

from test_segment3d import brute_hausdorff

RADIUS_MM = 60.0  # the pass follows a circle of this radius (rising slowly)
SPEED_MM_S, ACCEL_MM_S2 = 500.0, 5000.0  # v² / a = 50 mm


def sparse_noisy_pass(seed: int = 3) -> np.ndarray:
    """A TCP pass like those of a coarse mesh's raster: it doubles back 0.385 mm at its first
    point, then runs on edges of 0.02 to 9.3 mm (a sparse stretch) into 0.5 mm ones, with
    0.02 mm of noise; the old fallback put a 0.007 mm arc in it at σ 0.1."""
    edges = np.concatenate(([3.8, 5.2, 7.6, 9.3, 4.5, 5.6, 1.5, 3.3, 0.3, 1.2, 0.36, 0.05, 0.02, 0.06, 0.27],
                            np.full(50, 0.5)))
    s = np.concatenate(([0.0], np.cumsum(edges)))
    phi = s / RADIUS_MM
    path = np.column_stack((RADIUS_MM * np.sin(phi), RADIUS_MM * (1 - np.cos(phi)), 0.15 * s))
    ahead = path[0] + [0.385, 0.0, 0.0]
    points = np.vstack((ahead, path))
    return points + np.random.default_rng(seed).normal(0.0, 0.02, points.shape)


@pytest.mark.parametrize("tol", [0.05, 0.1])
@pytest.mark.parametrize("speed", [None, SPEED_MM_S])
def test_sparse_noisy_pass_gets_no_arc_tighter_than_allowed(tol, speed):
    points = sparse_noisy_pass()
    seg = segment_space_curve(make_space_curve(points, "sparse pass"), tol, speed_mm_s=speed,
                              tool_accel_mm_s2=None if speed is None else ACCEL_MM_S2)
    radii = [s.radius for s in seg.chain.segments if isinstance(s, Arc3)]
    assert seg.limits_kept is True
    # the input turns on a 60 mm circle; its noisy cluster of close points reads as a turn of
    # about 13 mm radius at the tightest (the curvature envelope the limits follow), never 10
    assert min(radii) >= 10.0
    assert seg.max_deviation_mm <= tol
    assert brute_hausdorff(points, seg.chain, tol / 20) <= tol * (1 + 1e-3) + tol / 20
    breaks = seg.chain.junction_breaks()
    smooth = [k for k in range(len(breaks)) if k not in seg.chain.corners]
    assert np.all(breaks[smooth] < 1e-9)


def test_added_corners_are_said():
    """Where lines stand in for arcs, the corners are counted and the summary says why."""
    seg = segment_space_curve(make_space_curve(sparse_noisy_pass(), "sparse pass"), 0.1)
    assert seg.added_corners >= 1
    assert seg.added_corners <= len(seg.chain.corners)
    assert "where no arc within the limits follows the input" in seg.summary()


def test_the_tube_fit_tries_no_count_above_the_one_it_is_given():
    """The biarc chain's count bounds the tube fit's search (on sharp or noisy runs most of
    it went to counts no better than the biarcs): a helix the tube fits with 14 pieces at σ
    0.1 mm, searched from no more than 5, is left to the biarcs; from 14 or more it is found."""
    points = FAMILIES["helix"](1500)
    limits, window = _limits(points, False, 0.1, None, None)
    assert fit_tube_run(points, 0.1, limits, window, at_most=5) is None
    for at_most in (14, None):
        fitted = fit_tube_run(points, 0.1, limits, window, at_most=at_most)
        assert fitted is not None and len(fitted.segments) == 14 and fitted.deviation_mm <= 0.1
