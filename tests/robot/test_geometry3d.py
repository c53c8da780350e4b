import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from coatsim.geometry.space.primitives import DegenerateArc, Line3, arc_through
from coatsim.robot.sampling import plan_pieces

from robot_helpers import square

coord = st.floats(-500, 500, allow_nan=False)


def test_arc_through_quarter_circle():
    arc = arc_through([100, 0, 5], [100 * math.cos(0.3), 100 * math.sin(0.3), 5], [0, 100, 5])
    assert np.allclose(arc.center, [0, 0, 5]) and math.isclose(arc.radius, 100)
    assert math.isclose(arc.sweep, math.pi / 2) and math.isclose(arc.length, 50 * math.pi)
    assert np.allclose(arc.points(np.array([arc.length]))[0], [0, 100, 5])
    d, s = arc.nearest(np.array([[200.0, 200.0, 5.0], [0.0, 0.0, 8.0], [-50.0, -1.0, 5.0]]))
    assert np.allclose(d[0], 200 * math.sqrt(2) - 100) and math.isclose(s[0], arc.length / 2)
    # behind the arc the nearer end point is the closest point
    assert math.isclose(d[2], min(math.dist((-50, -1), (0, 100)), math.dist((-50, -1), (100, 0))))


def test_collinear_points_define_no_arc():
    for points in (([0, 0, 0], [1, 1, 1], [2, 2, 2]), ([0, 0, 0], [1, 0, 0], [0, 0, 0])):
        with pytest.raises(DegenerateArc):
            arc_through(*points)


@settings(max_examples=200, deadline=None)
@given(st.tuples(coord, coord, coord), st.tuples(coord, coord, coord), st.tuples(coord, coord, coord))
def test_arc_through_passes_through_its_three_points(a, b, c):
    try:
        arc = arc_through(a, b, c)
    except DegenerateArc:
        return
    if arc.radius > 1e5:
        return
    ends = arc.points(np.array([0.0, arc.length]))
    assert np.allclose(ends, [a, c], atol=1e-6 * max(1.0, arc.radius))
    d, s = arc.nearest(np.array([b], dtype=float))
    assert d[0] < 1e-6 * max(1.0, arc.radius)
    assert 0 <= s[0] <= arc.length


@settings(max_examples=100, deadline=None)
@given(st.tuples(coord, coord, coord), st.tuples(coord, coord, coord), st.floats(0, 1))
def test_line_closest_point_is_exact(a, b, f):
    seg = Line3(a, b)
    p = np.asarray(a) + f * (np.asarray(b) - np.asarray(a))
    d, s = seg.nearest(p[None])
    assert d[0] < 1e-9 * max(1.0, seg.length)
    assert math.isclose(s[0], f * seg.length, abs_tol=1e-9 * max(1.0, seg.length))


def test_exact_stop_square_is_four_rest_to_rest_pieces():
    pieces = plan_pieces(square(stop=True), 1.0)
    assert [type(p).__name__ for p in pieces] == ["JointPiece"] + ["CartesianPiece"] * 4
    for p in pieces[1:]:
        assert math.isclose(p.length, 200.0) and np.max(np.diff(p.s)) <= 1.0 + 1e-9


def test_blended_square_rounds_corners_within_accuracy():
    acc = 5.0
    (_, piece) = plan_pieces(square(stop=False, accuracy=acc), 1.0)
    corners = np.array([[800, -100, 300], [800, 100, 300], [600, 100, 300]], dtype=float)
    for c in corners:
        near = np.linalg.norm(piece.position - c, axis=1)
        assert near.min() > 0.5  # the corner itself is cut ...
        assert near.min() < acc  # ... within the accuracy radius
    # blends are tangent-continuous: heading change between samples stays small
    t = piece.tangent
    assert np.min(np.sum(t[1:] * t[:-1], axis=1)) > math.cos(math.radians(15))
    assert np.max(np.diff(piece.s)) <= 1.0 + 1e-9
