"""The fitter with pinned end tangents (fit_run start_heading / end_heading): the chain
starts and ends on the given tangents, stays within the tolerance and G1 inside."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from coatsim.geometry import Polysegment
from coatsim.geometry.deviation import hausdorff
from coatsim.geometry.fit import fit_run
from coatsim.geometry.limits import fit_limits


def wave(amplitude: float, length: float, periods: float, n: int = 600) -> tuple[np.ndarray, float, float]:
    """A sine stretch and its exact start and end headings."""
    x = np.linspace(0.0, length, n)
    k = 2 * math.pi * periods / length
    y = amplitude * np.sin(k * x)
    slope = lambda u: math.atan(amplitude * k * math.cos(k * u))  # noqa: E731
    return np.column_stack((x, y)), slope(0.0), slope(length)


def check(pts: np.ndarray, tol: float, start: float | None, end: float | None):
    segs, dev = fit_run(pts, tol, False, fit_limits(pts, False, tol, None, None), start_heading=start, end_heading=end)
    poly = Polysegment(segs)
    assert dev <= tol and hausdorff(pts, poly).hausdorff <= tol
    assert segs[0].start == tuple(pts[0]) and segs[-1].end == tuple(pts[-1])
    if start is not None:
        assert abs(math.remainder(segs[0].start_heading - start, 2 * math.pi)) < 1e-9
    if end is not None:
        assert abs(math.remainder(segs[-1].end_heading - end, 2 * math.pi)) < 1e-9
    inner = poly.junction_breaks()
    assert (inner.max() if len(inner) else 0.0) < 1e-9
    return segs


@settings(max_examples=15, deadline=None)
@given(amplitude=st.floats(1.0, 12.0), length=st.floats(40.0, 150.0), periods=st.floats(0.3, 1.5),
       tol=st.sampled_from([0.02, 0.1]), both=st.booleans(), offset_deg=st.floats(-0.4, 0.4))
def test_pinned_tangents_are_kept_within_tolerance(amplitude, length, periods, tol, both, offset_deg):
    pts, h0, h1 = wave(amplitude, length, periods)
    off = math.radians(offset_deg)  # a neighbour's tangent a little off the curve's own
    check(pts, tol, h0 + off, h1 - off if both else None)


def test_pins_hold_where_the_unpinned_fit_would_turn_elsewhere():
    pts, h0, h1 = wave(8.0, 100.0, 0.75)
    free, _ = fit_run(pts, 0.1, False, fit_limits(pts, False, 0.1, None, None))
    pinned = check(pts, 0.1, h0, h1)
    assert len(pinned) <= len(free) + 2


def test_straight_run_with_matching_pins_is_one_line():
    pts = np.column_stack((np.linspace(0, 50, 20), np.zeros(20)))
    segs = check(pts, 0.1, 0.0, 0.0)
    assert len(segs) == 1


def test_end_heading_alone_is_refused():
    pts, _, h1 = wave(5.0, 80.0, 0.5)
    with pytest.raises(ValueError, match="end_heading needs start_heading"):
        fit_run(pts, 0.1, False, fit_limits(pts, False, 0.1, None, None), end_heading=h1)
