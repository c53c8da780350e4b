"""Curvature-faithful fitting (issue 16): no arc much tighter than the input, no micro
segments, smooth seams, speed-aware caps and speed-limited stretches; on random smooth curves
from formulas, with tolerance and tangent continuity still holding."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from coatsim.geometry import Arc, load_curve, make_curve, segment_curve
from coatsim.geometry.envelope import curvature_profile, noise_mm

from geometry_helpers import assert_contract, tangent_breaks
from smooth_curves import smooth_closed, smooth_open

G1 = 1e-9
TOLS = st.sampled_from([0.05, 0.1, 0.5])
FEW = settings(max_examples=8, deadline=None, derandomize=True, database=None)


def arcs(poly):
    return [s for s in poly.segments if isinstance(s, Arc)]



def assert_faithful(seg, tol, tightest):
    """Every arc at least 0.8 x the input's tightest radius; no segment shorter than the
    default minimum (5 tol) but where the whole fit is one segment."""
    poly = seg.polysegment
    assert seg.stats()["limits_kept"] is True
    for s in arcs(poly):
        assert s.radius >= 0.8 * tightest, f"arc of radius {s.radius:.3f} mm on a curve whose tightest is {tightest:.3f}"
    if poly.n_segments > 1:
        assert min(s.length for s in poly.segments) >= 5 * tol * 0.98


# ---------------------------------------------------------------- random smooth curves


@FEW
@given(formula=smooth_closed, tol=TOLS)
def test_closed_smooth_curves_get_honest_arcs(formula, tol):
    seg = segment_curve(formula.curve(1200), tol)
    assert seg.polysegment.corners == ()
    assert_contract(seg, tol)
    assert_faithful(seg, tol, formula.tightest_radius())


@FEW
@given(formula=smooth_open, tol=TOLS)
def test_open_smooth_curves_get_honest_arcs(formula, tol):
    seg = segment_curve(formula.curve(1200), tol)
    assert seg.polysegment.corners == ()
    assert_contract(seg, tol)
    assert_faithful(seg, tol, formula.tightest_radius())
    poly, pts = seg.polysegment, seg.curve.points
    assert poly.start == tuple(pts[0]) and poly.end == tuple(pts[-1])


@FEW
@given(formula=smooth_closed, tol=TOLS)
def test_the_seam_of_a_closed_curve_is_no_tighter_than_the_rest(formula, tol):
    """No closing hook: the two segments at the seam keep the same radius bound and minimum
    length as all others, and the seam is tangent-continuous."""
    seg = segment_curve(formula.curve(1200), tol)
    poly = seg.polysegment
    first, last = poly.segments[0], poly.segments[-1]
    tightest = formula.tightest_radius()
    for s in (first, last):
        assert not isinstance(s, Arc) or s.radius >= 0.8 * tightest
        assert poly.n_segments == 1 or s.length >= 5 * tol * 0.98
    assert tangent_breaks(poly)[-1][1] <= G1


# ---------------------------------------------------------------- the cases of the issue


@pytest.mark.parametrize("tol", [0.05, 0.1, 0.5])
def test_the_epitrochoid_gets_no_micro_arcs(tol):
    """Issue 16: arcs of radius 3.6 / 1.7 / 0.64 mm, 0.1 mm long, on an epitrochoid; the
    built-in's tightest radius is 20 mm, at its inner dips."""
    seg = segment_curve(load_curve("builtin:epitrochoid"), tol)
    assert_contract(seg, tol)
    assert_faithful(seg, tol, 20.0)


def test_the_ellipse_seam_has_no_closing_hook():
    """Issue 16: builtin:ellipse:a=80,b=50 at 0.05 mm ended with a 0.138 mm arc of radius
    4.4 mm at its seam; the ellipse's tightest radius is b² / a = 31.25 mm."""
    seg = segment_curve(load_curve("builtin:ellipse:a=80,b=50"), 0.05)
    assert_contract(seg, 0.05)
    assert_faithful(seg, 0.05, 31.25)
    stats = seg.stats()
    assert stats["min_segment_mm"] >= 0.25 and stats["min_radius_mm"] >= 25.0
    assert stats["input_min_radius_mm"] == pytest.approx(31.25, rel=0.02)


def test_min_segment_is_a_parameter():
    seg = segment_curve(load_curve("builtin:sine"), 0.05, min_segment_mm=8.0)
    assert min(s.length for s in seg.polysegment.segments) >= 8.0 * 0.98
    assert_contract(seg, 0.05)


def test_a_min_segment_the_fit_cannot_keep_is_an_input_error():
    """Rather than the fillet fallback's short segments: the sine's peaks (radius 12.7 mm)
    need shorter arcs than 10 mm at 0.05 mm."""
    from coatsim.core.errors import InputError

    with pytest.raises(InputError, match=r"builtin:sine: .*min_segment_mm 10 mm"):
        segment_curve(load_curve("builtin:sine"), 0.05, min_segment_mm=10.0)


def test_bad_limits_are_input_errors():
    from coatsim.core.errors import InputError

    c = load_curve("builtin:sine:points=300")
    for kwargs, name in [({"min_segment_mm": -1.0}, "min_segment_mm"), ({"speed_mm_s": 0.0, "tool_accel_mm_s2": 5e3}, "speed_mm_s"),
                         ({"speed_mm_s": 100.0, "tool_accel_mm_s2": float("nan")}, "tool_accel_mm_s2"),
                         ({"speed_mm_s": 100.0}, "both or neither")]:
        with pytest.raises(InputError, match=name):
            segment_curve(c, 0.1, **kwargs)


# ---------------------------------------------------------------- speed and tool acceleration

ACCEL = 5000.0  # mm/s², the shipped cell's tool acceleration limit


@FEW
@given(formula=st.one_of(smooth_closed, smooth_open), tol=TOLS, margin=st.floats(1.05, 3.0))
def test_feasible_speed_gets_no_arc_below_v2_over_a(formula, tol, margin):
    """Where the input allows the speed (its tightest radius above v²/a), no arc is tighter
    than v²/a and nothing is speed-limited."""
    tightest = formula.tightest_radius()
    speed = math.sqrt(ACCEL * tightest / margin)
    seg = segment_curve(formula.curve(1200), tol, speed_mm_s=speed, tool_accel_mm_s2=ACCEL)
    assert_contract(seg, tol)
    limit = speed**2 / ACCEL
    assert all(s.radius >= limit * (1 - 1e-6) for s in arcs(seg.polysegment))
    assert seg.polysegment.speed_limited == ()
    assert seg.stats()["speed_mm_s"] == speed and seg.stats()["tool_accel_mm_s2"] == ACCEL


@FEW
@given(formula=st.one_of(smooth_closed, smooth_open), tol=TOLS, excess=st.floats(1.5, 4.0))
def test_infeasible_speed_is_reported_not_made_worse(formula, tol, excess):
    """Where the input needs a tighter turn than v²/a, its stretches are listed with the
    highest speed there, every arc tighter than v²/a lies in one, and none is much tighter
    than the input."""
    tightest = formula.tightest_radius()
    speed = math.sqrt(ACCEL * tightest * excess)
    seg = segment_curve(formula.curve(1200), tol, speed_mm_s=speed, tool_accel_mm_s2=ACCEL)
    assert_contract(seg, tol)
    assert_faithful(seg, tol, tightest)
    poly = seg.polysegment
    limited = poly.speed_limited
    assert limited, "the input needs a tighter turn than the speed allows: some stretch must be listed"
    s = 0.0
    for seg_ in poly.segments:
        if isinstance(seg_, Arc) and seg_.radius < speed**2 / ACCEL:
            inside = [v for a, b, v in limited if a <= s + 1e-9 and s + seg_.length <= b + 1e-9]
            assert inside and min(inside) <= math.sqrt(ACCEL * seg_.radius) * (1 + 1e-9)
        s += seg_.length
    assert all(0 <= a <= b <= poly.length + 1e-6 and 0 < v < speed for a, b, v in limited)


def test_corners_are_speed_limited_stretches_of_zero_length():
    seg = segment_curve(load_curve("builtin:d-shape"), 0.1, speed_mm_s=200.0, tool_accel_mm_s2=ACCEL)
    poly = seg.polysegment
    ends = np.cumsum([s.length for s in poly.segments])
    corners = [(ends[k], ends[k], 0.0) for k in poly.corners]
    assert all(any(abs(a - e) < 1e-9 and b == a and v == 0.0 for a, b, v in poly.speed_limited) for e, _, _ in corners)
    assert len(poly.speed_limited) == len(corners)  # the half circle (r 50 mm) allows 200 mm/s at 5 m/s²


# ---------------------------------------------------------------- the curvature estimate


@pytest.mark.parametrize("radius,points,closed", [(25.0, 3000, True), (3.0, 500, True), (200.0, 800, False)])
def test_curvature_of_a_circle_is_its_inverse_radius(radius, points, closed):
    t = np.linspace(0.0, 2 * math.pi if closed else 1.5, points)
    pts = radius * np.column_stack((np.cos(t), np.sin(t)))
    prof = curvature_profile(pts, closed, 0.05)
    np.testing.assert_allclose(prof.kappa, 1 / radius, rtol=2e-3)
    assert prof.tightest_radius_mm == pytest.approx(radius, rel=2e-3)


@pytest.mark.parametrize("noise", [0.002, 0.01, 0.03])
def test_digitising_noise_does_not_spike_the_curvature(noise):
    c = load_curve("builtin:ellipse:points=5000")
    pts = c.points + np.random.default_rng(1).normal(0.0, noise, c.points.shape)
    pts[-1] = pts[0]
    assert noise_mm(pts) == pytest.approx(noise, rel=0.5)
    prof = curvature_profile(pts, True, 0.05)
    assert 0.8 * 25.0 <= prof.tightest_radius_mm <= 1.25 * 25.0  # b² / a = 25 mm


def test_noise_estimate_of_clean_and_sparse_curves_is_small():
    assert noise_mm(load_curve("builtin:ellipse").points) < 1e-6
    assert noise_mm(load_curve("builtin:sine:points=200").points) < 0.05


def test_straight_input_has_no_tightest_radius():
    pts = np.column_stack((np.linspace(0, 100, 300), np.linspace(0, 40, 300)))
    assert curvature_profile(pts, False, 0.1).tightest_radius_mm == math.inf
    assert segment_curve(make_curve(pts, "line"), 0.1).stats()["input_min_radius_mm"] is None
