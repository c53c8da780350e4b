"""Straight stretches of a taught path come back as lines: a rounded rectangle taught with a
few points per corner and collinear points along its sides, clean or with a little jitter,
gets its long sides as lines (not as arcs of metres of radius bowing across the tolerance),
its corners as arcs no tighter than the taught corner, within σ of vertices and edges."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import Phase, assume, example, given, settings
from hypothesis import strategies as st

from coatsim.geometry import Arc, Line, make_curve, segment_curve
from coatsim.geometry.sparse import unroundable

from geometry_helpers import assert_contract

FEW = settings(max_examples=5, deadline=None, derandomize=True, database=None,
               phases=[Phase.explicit, Phase.generate])  # a failing fit is slow to shrink


def rounded_rectangle(width: float, height: float, radius: float, per_corner: int, per_side: int) -> np.ndarray:
    """A closed polygon (last point = first): ``per_corner`` points on each quarter circle of
    ``radius`` and ``per_side`` evenly spaced points on each straight side between them."""
    centres = [(width / 2 - radius, height / 2 - radius), (radius - width / 2, height / 2 - radius),
               (radius - width / 2, radius - height / 2), (width / 2 - radius, radius - height / 2)]
    points = []
    for k, (x, y) in enumerate(centres):
        turn = np.linspace(k * math.pi / 2, (k + 1) * math.pi / 2, per_corner)
        corner = np.column_stack((x + radius * np.cos(turn), y + radius * np.sin(turn)))
        nx, ny = centres[(k + 1) % 4]
        side_end = np.array((nx + radius * math.cos(turn[-1]), ny + radius * math.sin(turn[-1])))
        u = np.linspace(0.0, 1.0, per_side + 2)[1:-1, None]
        points += [corner, corner[-1] + u * (side_end - corner[-1])]
    body = np.vstack(points)
    return np.vstack((body, body[:1]))


@FEW
@example(per_corner=4, per_side=1, radius=10.0, tol=0.2, jitter=0.0, seed=0)
@example(per_corner=6, per_side=3, radius=10.0, tol=0.5, jitter=0.0, seed=0)
@given(per_corner=st.integers(3, 6), per_side=st.integers(1, 4), radius=st.floats(5.0, 25.0),
       tol=st.floats(0.1, 1.0), jitter=st.sampled_from([0.0, 0.1]), seed=st.integers(0, 2**16))
def test_the_straight_sides_of_a_taught_rectangle_come_back_as_lines(per_corner, per_side, radius, tol, jitter, seed):
    pts = rounded_rectangle(200.0, 100.0, radius, per_corner, per_side)
    pts[:-1] += np.random.default_rng(seed).normal(0.0, jitter * tol, pts[:-1].shape)
    pts[-1] = pts[0]
    assume(len(unroundable(pts, True, tol)[0]) == 0)  # σ rounds every taught corner (else they are corners)
    seg = segment_curve(make_curve(pts, "rounded rectangle", "yes"), tol)
    assert_contract(seg, tol)
    segments = seg.polysegment.segments
    long = 0.6 * (100.0 - 2 * radius)  # (a side less the ends its corner arcs take)
    sides = [s for s in segments if s.length > long]
    assert sum(isinstance(s, Line) for s in sides) >= 3, \
        [f"{type(s).__name__} {s.length:.1f} mm" + (f" r {s.radius:.4g}" if isinstance(s, Arc) else "") for s in sides]
    for s in segments:
        if isinstance(s, Arc):
            assert s.radius < 50 * radius, f"an arc of {s.length:.1f} mm and radius {s.radius:.4g} mm"


def test_a_rectangle_taught_with_one_point_per_side_keeps_every_side_straight_at_a_tight_tolerance():
    pts = rounded_rectangle(200.0, 100.0, 5.0, 6, 1)
    seg = segment_curve(make_curve(pts, "rounded rectangle", "yes"), 0.3)
    assert_contract(seg, 0.3)
    arcs = [s for s in seg.polysegment.segments if isinstance(s, Arc)]
    assert max(s.radius for s in arcs) < 50 * 5.0, [f"r {s.radius:.4g} mm" for s in arcs]
    assert seg.polysegment.n_segments == 8  # it was 10: the last side a tilted line and an arc of 290 mm
