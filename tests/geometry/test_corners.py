"""True corners of dense input: a sharp vertex is one at every sampling and tolerance; a tight
bend the sampling resolves, beside a line, is none (it depended on σ against the spacing)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from coatsim.geometry import make_curve, segment_curve
from coatsim.geometry.corners import corners_and_notes
from coatsim.geometry.space.local import detect_corners3


def _resampled(points: np.ndarray, spacing: float) -> np.ndarray:
    s = np.concatenate(([0.0], np.cumsum(np.linalg.norm(np.diff(points, axis=0), axis=1))))
    at = np.linspace(0.0, s[-1], max(int(round(s[-1] / spacing)), 2) + 1)
    return np.column_stack((np.interp(at, s, points[:, 0]), np.interp(at, s, points[:, 1])))


def serpentine(passes: int, length: float, pitch: float, bulge: float) -> np.ndarray:
    """Passes along x joined by semi-elliptical turn-arounds (semi-axes ``bulge`` along x, pitch/2
    along y, tangent to the passes), densely."""
    t = np.linspace(0.0, math.pi, 2001)
    parts = []
    for i in range(passes):
        y = i * pitch
        x0, x1 = (0.0, length) if i % 2 == 0 else (length, 0.0)
        parts.append(np.column_stack((np.linspace(x0, x1, 2001), np.full(2001, y))))
        if i < passes - 1:
            side = 1.0 if i % 2 == 0 else -1.0
            parts.append(np.column_stack((x1 + side * bulge * np.sin(t), y + pitch / 2 * (1 - np.cos(t)))))
    return np.vstack(parts)


def tightest(bulge: float, pitch: float) -> float:
    """The tightest radius of a turn-around: where it meets a pass, or at its tip."""
    return min(bulge ** 2 / (pitch / 2), (pitch / 2) ** 2 / bulge)


@settings(max_examples=40, deadline=None)
@given(bulge=st.floats(3.0, 10.0), pitch=st.floats(10.0, 30.0), share=st.floats(0.03, 1.0 / 3.0),
       below=st.floats(0.05, 0.95))
def test_a_tight_turn_around_the_sampling_resolves_is_no_corner(bulge, pitch, share, below):
    """σ below three spacings (the spacing sets the corner test's window): no corner."""
    radius = tightest(bulge, pitch)
    spacing = min(share * radius, 1.0)  # each vertex turns at most 1/3 rad (19°)
    tolerance = below * 3 * spacing
    pts = _resampled(serpentine(3, 100.0, pitch, bulge), spacing)
    corners, _ = corners_and_notes(pts, False, 20.0, tolerance)
    assert corners.tolist() == []


@settings(max_examples=40, deadline=None)
@given(turn_deg=st.floats(25.0, 150.0), share=st.floats(0.05, 1.9), tolerance=st.floats(0.02, 1.0),
       rounded=st.booleans())
def test_a_sharp_vertex_of_dense_points_is_a_corner(turn_deg, share, tolerance, rounded):
    """Two legs of 60 mm meeting at a vertex turning ``turn_deg``, or the turn split over two
    vertices one spacing apart (a corner rounded by a CAD export), sampled at ``share`` of σ
    (dense: below 2σ; sparser points are taught vertices, coatsim.geometry.sparse)."""
    spacing, a = share * tolerance, math.radians(turn_deg)
    legs = [np.array([[-60.0, 0.0], [0.0, 0.0]])]
    if rounded:
        mid = np.array([spacing * math.cos(a / 2), spacing * math.sin(a / 2)])
        legs.append(np.array([[0.0, 0.0], mid]))
        legs.append(mid + np.array([[0.0, 0.0], [60.0 * math.cos(a), 60.0 * math.sin(a)]]))
    else:
        legs.append(np.array([[0.0, 0.0], [60.0 * math.cos(a), 60.0 * math.sin(a)]]))
    pts = np.vstack([_resampled(leg, spacing)[:-1] for leg in legs] + [legs[-1][-1:]])
    pts = pts[np.r_[True, np.any(np.diff(pts, axis=0) != 0, axis=1)]]
    corners, _ = corners_and_notes(pts, False, 20.0, tolerance)
    assert len(corners) == 1
    assert np.linalg.norm(pts[corners[0]]) <= spacing + 1e-9


@pytest.mark.parametrize("tolerance", [0.5, 1.0])
def test_a_serpentine_with_elliptical_turns_is_tangent_continuous(tolerance):
    """Sampled every 0.5 mm (radius 3.6 mm where a turn meets a pass) at σ 0.5 and 1: it came
    back as lines and one arc per turn with eight corners (stops) between them."""
    curve = make_curve(_resampled(serpentine(5, 100.0, 20.0, 6.0), 0.5), "serpentine", "no")
    seg = segment_curve(curve, tolerance)
    poly = seg.polysegment
    assert poly.corners == () and poly.max_tangent_break() <= 1e-9 and seg.max_deviation_mm <= tolerance


def test_where_sigma_sets_the_window_a_tight_bend_is_a_corner():
    """At σ 2 (above three spacings) the turn-arounds' ends, radius 3.6 mm, are corners at this
    tolerance (a sharp corner lies within σ of such a bend), as an airfoil's leading edge is at
    σ 30: the fit of a run that doubles back within σ would need an arc of no radius."""
    pts = _resampled(serpentine(5, 100.0, 20.0, 6.0), 0.5)
    assert len(corners_and_notes(pts, False, 20.0, 2.0)[0]) == 8


def _on_cylinder(points: np.ndarray, radius: float) -> np.ndarray:
    """Plane points wrapped onto a cylinder about the y axis (x measured along its surface)."""
    a = points[:, 0] / radius
    return np.column_stack((radius * np.sin(a), points[:, 1], radius * (1 - np.cos(a))))


@settings(max_examples=30, deadline=None)
@given(bulge=st.floats(3.0, 10.0), pitch=st.floats(10.0, 30.0), share=st.floats(0.03, 1.0 / 3.0),
       below=st.floats(0.05, 0.95), cylinder=st.floats(60.0, 300.0))
def test_in_space_a_tight_turn_around_the_sampling_resolves_is_no_corner(bulge, pitch, share, below, cylinder):
    spacing = min(share * tightest(bulge, pitch), 1.0)
    tolerance = below * 3 * spacing
    pts = _on_cylinder(_resampled(serpentine(3, 100.0, pitch, bulge), spacing), cylinder)
    assert detect_corners3(pts, False, 20.0, tolerance).tolist() == []


@settings(max_examples=30, deadline=None)
@given(turn_deg=st.floats(25.0, 150.0), share=st.floats(0.05, 1.9), tolerance=st.floats(0.02, 1.0),
       seed=st.integers(0, 2**16))
def test_in_space_a_sharp_vertex_of_dense_points_is_a_corner(turn_deg, share, tolerance, seed):
    spacing, a = share * tolerance, math.radians(turn_deg)
    legs = [np.array([[-60.0, 0.0], [0.0, 0.0]]), np.array([[0.0, 0.0], [60.0 * math.cos(a), 60.0 * math.sin(a)]])]
    flat = np.vstack([_resampled(leg, spacing)[:-1] for leg in legs] + [legs[-1][-1:]])
    q, _ = np.linalg.qr(np.random.default_rng(seed).normal(size=(3, 3)))
    pts = np.column_stack((flat, np.zeros(len(flat)))) @ q.T
    corners = detect_corners3(pts, False, 20.0, tolerance)
    assert len(corners) == 1 and np.linalg.norm(pts[corners[0]]) <= spacing + 1e-9
