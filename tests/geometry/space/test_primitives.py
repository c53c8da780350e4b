"""Line3 / Arc3: analytic cases, closed-form distances against dense sampling, placement."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from coatsim.geometry.primitives import Arc, Line, make_segment
from coatsim.geometry.space.pose import Pose
from coatsim.geometry.space.primitives import (
    Arc3, DegenerateArc, Line3, arc_from_corner, arc_from_tangent, arc_through, place,
)
from coatsim.geometry.space.rotations import rot_x

from strategies import points3, poses, unit_vectors

SETTINGS = settings(max_examples=150, deadline=None)


def dense_distance(seg, p: np.ndarray, n: int = 20001) -> np.ndarray:
    q = seg.points(np.linspace(0.0, seg.length, n))
    return np.min(np.linalg.norm(p[:, None, :] - q[None], axis=2), axis=1)


def test_quarter_arc_analytic():
    arc = Arc3([10, 0, 0], [0, 10, 0], [0, 0, 0], [0, 0, 1], 10.0, math.pi / 2)
    assert arc.length == pytest.approx(5 * math.pi)
    assert np.allclose(arc.via, [10 * math.sqrt(0.5)] * 2 + [0])
    assert np.allclose(arc.points([arc.length])[0], arc.end)
    assert np.allclose(arc.start_tangent, [0, 1, 0]) and np.allclose(arc.end_tangent, [-1, 0, 0])
    # above the centre: every point of the circle is equally far; beside the arc: the circle;
    # behind it: the nearer end
    assert arc.distance([0, 0, 5]) == pytest.approx(math.hypot(10, 5))
    assert arc.distance([20, 20, 3]) == pytest.approx(math.hypot(20 * math.sqrt(2) - 10, 3))
    assert arc.distance([-5, -1, 0]) == pytest.approx(math.dist([-5, -1, 0], [0, 10, 0]))
    assert arc.reversed().distance([20, 20, 3]) == pytest.approx(arc.distance([20, 20, 3]))
    line = Line3([0, 0, 0], [10, 0, 0])
    assert line.distance([5, 3, 4]) == pytest.approx(5.0) and line.distance([-3, 4, 0]) == pytest.approx(5.0)


@st.composite
def arcs(draw) -> Arc3:
    start = draw(points3(1))[0]
    tangent, bend = draw(unit_vectors()), draw(unit_vectors())
    normal = np.cross(tangent, bend)
    assume(np.linalg.norm(normal) > 0.1)
    normal /= np.linalg.norm(normal)
    radius = draw(st.floats(0.5, 300.0))
    sweep = draw(st.floats(0.01, 2 * math.pi))
    centre = start + radius * np.cross(normal, tangent)
    probe = Arc3(start, start, centre, normal, radius, sweep)
    return Arc3(start, probe.points([probe.length])[0], centre, normal, radius, sweep)


@SETTINGS
@given(arcs(), points3(6))
def test_arc_distance_is_exact(arc, p):
    p = arc.center + (p - arc.center) * (arc.radius / 200.0)  # probes around the arc's size
    d = arc.distance(p)
    dense = dense_distance(arc, p)
    step = arc.length / 20000
    assert np.all(d <= dense + 1e-9)  # never above a point of the arc
    assert np.all(dense - d <= step / 2 + 1e-9)  # and reached within the sampling step
    s = arc.nearest(p)[1]
    assert np.allclose(np.linalg.norm(arc.points(s) - p, axis=1), d, atol=1e-9 * (1 + arc.radius))


@SETTINGS
@given(arcs())
def test_arc_points_tangents_consistent(arc):
    s = np.linspace(0.0, arc.length, 9)
    p, t = arc.points(s), arc.tangents(s)
    assert np.allclose(np.linalg.norm(p - arc.center, axis=1), arc.radius, atol=1e-9 * (1 + arc.radius))
    assert np.allclose(np.linalg.norm(t, axis=1), 1.0) and np.allclose(np.einsum("ij,ij->i", t, p - arc.center), 0, atol=1e-7 * arc.radius)
    h = 1e-6 * arc.radius
    ahead = arc.points(s[:-1] + h)
    assert np.allclose((ahead - p[:-1]) / h, t[:-1], atol=1e-5)
    again = arc_through(arc.start, arc.via, arc.end) if arc.sweep < 2 * math.pi - 1e-3 else arc
    assert again.radius == pytest.approx(arc.radius, rel=1e-6) and again.sweep == pytest.approx(arc.sweep, rel=1e-6)
    back = arc_from_tangent(arc.start, 3.0 * arc.start_tangent, arc.end) if arc.sweep < 2 * math.pi - 1e-3 else arc
    assert np.allclose(back.center, arc.center, atol=1e-6 * (1 + arc.radius))


@SETTINGS
@given(poses(), poses(), st.floats(-6.0, 6.0).filter(lambda k: abs(k) > 1e-3), st.floats(1.0, 200.0),
       st.floats(0.0, 6.28))
def test_rigid_motion_commutes_with_placement(frame, motion, kappa, length, heading):
    """Placing a planar arc at a frame, then moving it = placing it at the moved frame."""
    assume(abs(kappa) / 100.0 * length < 2 * math.pi)  # an Arc3 turns at most once around
    seg = make_segment((3.0, -2.0), heading, kappa / 100.0, length)
    a = place(seg, frame).transformed(motion)
    b = place(seg, motion @ frame)
    for name in ("start", "end") + (("center", "normal") if isinstance(seg, Arc) else ()):
        assert np.allclose(getattr(a, name), getattr(b, name), atol=1e-8)
    probe = motion.apply(frame.apply(np.array([[1.0, 2.0, 3.0], [50.0, -4.0, 0.0]])))
    assert np.allclose(a.distance(probe), b.distance(probe), atol=1e-8)


@SETTINGS
@given(poses(), st.floats(-6.0, 6.0).filter(lambda k: abs(k) > 1e-3), st.floats(1.0, 200.0))
def test_placed_arc_is_the_planar_arc(frame, kappa, length):
    assume(abs(kappa) / 100.0 * length < 2 * math.pi)
    seg = make_segment((0.0, 0.0), 0.3, kappa / 100.0, length)
    arc = place(seg, frame)
    s = np.linspace(0.0, seg.length, 11)
    flat = np.column_stack((seg.points(s), np.zeros(len(s))))
    assert np.allclose(arc.points(s), frame.apply(flat), atol=1e-8)
    assert arc.sweep == pytest.approx(abs(seg.sweep)) and arc.length == pytest.approx(seg.length)


def test_line_placement_and_corner_arc():
    frame = Pose(rot_x(math.pi / 2), np.array([700.0, 0.0, 200.0]))
    line = place(Line((0.0, 0.0), (10.0, 0.0)), frame)
    assert np.allclose(line.end, [710, 0, 200]) and line.length == pytest.approx(10.0)
    arc = arc_from_corner([0, 0, 0], [10, 0, 0], [10, 10, 0])
    assert arc.radius == pytest.approx(10.0) and np.allclose(arc.center, [0, 10, 0])
    assert arc.sweep == pytest.approx(math.pi / 2) and np.allclose(arc.normal, [0, 0, 1])
    clockwise = place(Arc((10.0, 0.0), (0.0, -10.0), (0.0, 0.0), 10.0, -math.pi / 2), Pose.identity())
    assert np.allclose(clockwise.normal, [0, 0, -1]) and np.allclose(clockwise.via, [10 * math.sqrt(0.5), -10 * math.sqrt(0.5), 0])


def test_degenerate_arcs_are_refused():
    with pytest.raises(DegenerateArc, match="one line"):
        arc_through([0, 0, 0], [1, 1, 1], [2, 2, 2])
    with pytest.raises(DegenerateArc, match="not distinct"):
        arc_through([0, 0, 0], [0, 0, 0], [2, 2, 2])
    with pytest.raises(DegenerateArc, match="tangent"):
        arc_from_tangent([0, 0, 0], [1, 0, 0], [5, 0, 0])
    with pytest.raises(ValueError, match="unit"):
        Arc3([1, 0, 0], [0, 1, 0], [0, 0, 0], [0, 0, 2], 1.0, 1.0)
