"""The planar fit with pinned end tangents: the chain leaves and arrives along the headings asked,
within the tolerance, or there is none (a corner in the run, a pin the run cannot follow)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from coatsim.geometry.deviation import hausdorff
from coatsim.geometry.pinned import fit_pinned
from coatsim.geometry.polysegment import Polysegment

OPTIONS = {"corner_deg": 20.0, "min_segment_mm": None, "speed_mm_s": None, "tool_accel_mm_s2": None}


def line_then_quarter() -> np.ndarray:
    """Along +x for 30 mm, then a quarter circle of radius 25 turning left to +y."""
    x = np.linspace(0.0, 30.0, 121)
    a = np.linspace(0.0, math.pi / 2, 200)[1:]
    return np.vstack((np.column_stack((x, 0 * x)), np.column_stack((30 + 25 * np.sin(a), 25 - 25 * np.cos(a)))))


@pytest.mark.parametrize("pins", [(0.0, math.pi / 2), (0.0, None), (None, math.pi / 2)])
def test_the_chain_keeps_its_pinned_headings(pins):
    pts = line_then_quarter()
    fit = fit_pinned(pts, 0.1, *pins, **OPTIONS)
    assert fit is not None and fit.deviation_mm <= 0.1
    assert hausdorff(pts, Polysegment(fit.segments)).hausdorff <= 0.1 + 1e-9
    if pins[0] is not None:
        assert abs(math.remainder(fit.segments[0].start_heading - pins[0], 2 * math.pi)) <= 1e-9
    if pins[1] is not None:
        assert abs(math.remainder(fit.segments[-1].end_heading - pins[1], 2 * math.pi)) <= 1e-9
    assert np.array_equal(fit.segments[0].start, pts[0]) and np.allclose(fit.segments[-1].end, pts[-1], atol=1e-9)
    assert [s.kind for s in fit.segments] == ["line", "arc"]


def test_no_chain_for_a_corner_or_a_pin_the_run_cannot_follow():
    corner = np.vstack((np.column_stack((np.linspace(0, 30, 60), np.zeros(60))),
                        np.column_stack((np.full(60, 30.0), np.linspace(0, 30, 61)[1:]))))
    assert fit_pinned(corner, 0.1, 0.0, math.pi / 2, **OPTIONS) is None
    assert fit_pinned(line_then_quarter(), 0.1, math.pi / 2, None, **OPTIONS) is None  # leaving at 90° to the run
    with pytest.raises(ValueError):
        fit_pinned(line_then_quarter(), 0.1, None, None, **OPTIONS)
