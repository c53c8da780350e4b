"""Straight stretches of a planar curve come back as lines, and a bend between two of them as one
arc tangent to both, where the input is not exactly lines and circles (coatsim.geometry.lined):
a rounded rectangle whose corners are a hair off circular came back as fifteen arcs, its sides
of radius 5–90 m."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from coatsim.geometry import Arc, Line, load_curve, make_curve, segment_curve

from geometry_helpers import assert_contract


def kinds(seg) -> str:
    return "".join(s.kind[0] for s in seg.polysegment.segments)


def stretched(points: np.ndarray, sx: float, angle: float = 0.0, offset=(0.0, 0.0)) -> np.ndarray:
    """The points scaled by ``sx`` along x (lines stay lines, arcs turn elliptical), turned by
    ``angle`` and moved by ``offset``."""
    c, s = math.cos(angle), math.sin(angle)
    return (points * [sx, 1.0]) @ np.array([[c, s], [-s, c]]) + np.asarray(offset)


@pytest.mark.parametrize("sx", [1.0001, 1.003, 1.01])
@pytest.mark.parametrize("tol", [0.05, 0.1, 0.5])
def test_a_rounded_rectangle_with_corners_off_circular_is_four_lines_and_four_arcs(sx, tol):
    rect = load_curve("builtin:rounded-rectangle")  # 150 x 80 mm, corners r 10
    seg = segment_curve(make_curve(stretched(rect.points, sx), "rect", "yes"), tol)
    assert_contract(seg, tol)
    assert sorted(kinds(seg)) == sorted("lalalala") and seg.polysegment.corners == ()
    segs = seg.polysegment.segments
    assert all(a.kind != b.kind for a, b in zip(segs, segs[1:] + segs[:1]))  # lines and arcs alternate
    assert sorted(s.length for s in segs if isinstance(s, Line)) == pytest.approx([60, 60, 130, 130], abs=2.5)
    assert all(s.radius == pytest.approx(10 * sx, rel=0.02) for s in segs if isinstance(s, Arc))


@settings(max_examples=8, deadline=None)
@given(angle=st.floats(0.0, 2 * math.pi), x=st.floats(-500, 500), y=st.floats(-500, 500))
def test_the_lines_do_not_depend_on_where_the_rectangle_lies(angle, x, y):
    rect = load_curve("builtin:rounded-rectangle")
    seg = segment_curve(make_curve(stretched(rect.points, 1.002, angle, (x, y)), "rect", "yes"), 0.1)
    assert_contract(seg, 0.1)
    assert seg.polysegment.n_lines == 4 and seg.polysegment.n_arcs == 4


def stadium(half_side: float, radius: float, ends: float, points: int = 3000) -> np.ndarray:
    """A closed stadium: two straight sides 2·half_side long joined by half circles of
    ``radius`` stretched by ``ends`` along the sides (1: exact circles)."""
    side, bend = 2 * half_side, math.pi * radius
    s = np.linspace(0.0, 2 * (side + bend), points)
    out = np.empty((points, 2))
    for k, v in enumerate(s):
        leg, at = divmod(v, side + bend)
        sign = 1.0 if leg == 0 else -1.0
        if at < side:
            out[k] = (sign * (at - half_side), -sign * radius)
        else:
            phi = (at - side) / radius - math.pi / 2
            out[k] = (sign * (half_side + ends * radius * math.cos(phi)), sign * radius * math.sin(phi))
    out[-1] = out[0]
    return out


@pytest.mark.parametrize("tol", [0.05, 0.1, 0.2, 0.5])
def test_a_stadium_with_elliptical_ends_keeps_its_straight_sides(tol):
    """At σ 0.2 and 0.5 the chain with lines needs one segment more than the one without (its
    ends pinned to the lines' directions) and is taken: a straight side costs at most its line."""
    seg = segment_curve(make_curve(stadium(60.0, 20.0, 1.05), "stadium", "yes"), tol)
    assert_contract(seg, tol)
    lines = [s for s in seg.polysegment.segments if isinstance(s, Line)]
    assert len(lines) == 2 and all(s.length == pytest.approx(120, abs=3) for s in lines)


def planar_route(seed: int, stretch: float) -> tuple[np.ndarray, int]:
    """An open route in the plane: 2–4 straight legs of 80–200 mm, bends of r 10–50 mm turning
    30–150° either way, points every 0.1 mm, scaled by ``stretch`` along x."""
    rng = np.random.default_rng(seed)
    legs = int(rng.integers(2, 5))
    heading, here, out = rng.uniform(0, 2 * math.pi), np.zeros(2), []
    for k in range(legs):
        length = rng.uniform(80, 200)
        u = np.array([math.cos(heading), math.sin(heading)])
        t = np.arange(0.0, length, 0.1)
        out.append(here + t[:, None] * u)
        here = here + length * u
        if k < legs - 1:
            turn = rng.uniform(math.radians(30), math.radians(150)) * rng.choice([-1.0, 1.0])
            radius = rng.uniform(10, 50)
            side = math.copysign(1.0, turn)
            centre = here + radius * side * np.array([-u[1], u[0]])
            a0 = heading - side * math.pi / 2
            phi = a0 + side * np.arange(0.0, abs(turn) * radius, 0.1) / radius
            out.append(centre + radius * np.column_stack((np.cos(phi), np.sin(phi))))
            heading += turn
            here = centre + radius * np.array([math.cos(a0 + turn), math.sin(a0 + turn)])
    return np.vstack(out + [here[None]]) * [stretch, 1.0], legs


@pytest.mark.parametrize("seed", range(8))
def test_random_planar_routes_give_a_line_per_leg_and_an_arc_per_bend(seed):
    points, legs = planar_route(seed, 1.003)
    seg = segment_curve(make_curve(points, "route", "no"), 0.1)
    assert_contract(seg, 0.1)
    assert kinds(seg) == "la" * (legs - 1) + "l" and seg.polysegment.corners == ()


def test_an_open_slot_with_an_elliptical_end_keeps_both_lines():
    """At σ 0.5 (lines, one arc, lines: as many segments as three long arcs); at σ 0.05 and 0.1
    the elliptical end pinned to both lines needs two more arcs than the chain without lines,
    which is kept."""
    u_shape = np.vstack((np.column_stack((np.arange(0, 100, 0.1), np.zeros(1000))),
                         [(100 + 30.6 * math.sin(a), 30 - 30 * math.cos(a)) for a in np.linspace(0, math.pi, 900)],
                         np.column_stack((np.arange(100, 0, -0.1), np.full(1000, 60.0)))))
    seg = segment_curve(make_curve(u_shape, "slot", "no"), 0.5)
    assert_contract(seg, 0.5)
    assert kinds(seg) == "lal"
