"""Taught polygons with features next to long edges or close points: a line meeting a taught
fillet is rounded (its long edge's circle through three vertices is not what the chain must
keep to), a cusp taught with two close points is a corner and the lobes beside it are
rounded (the caps at a run's end follow the polygon's own turning), and a star's tips stay
corners as σ grows past half their shorter edge, so more tolerance never gives many more
segments nor a fallback fit."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import Phase, example, given, settings
from hypothesis import strategies as st

from coatsim.geometry import Arc, make_curve, segment_curve

from geometry_helpers import assert_contract

FEW = settings(max_examples=4, deadline=None, derandomize=True, database=None,
               phases=[Phase.explicit, Phase.generate])  # a failing fit is slow to shrink
TAU = 2 * math.pi


def _rounded_rectangle(width: float, height: float, radius: float, per_fillet: int) -> tuple[np.ndarray, float]:
    """A rectangle with fillets of ``radius``, each 90° fillet taught with ``per_fillet``
    points (its ends where the sides meet it), the sides single moves; the last point
    repeats the first. Also the distance of the true shape from it (the fillet chords'
    sagitta)."""
    cx, cy = width / 2 - radius, height / 2 - radius
    pts = []
    for k, (x, y) in enumerate(((cx, cy), (-cx, cy), (-cx, -cy), (cx, -cy))):
        t = k * math.pi / 2 + np.linspace(0.0, math.pi / 2, per_fillet)
        pts.append(np.column_stack((x + radius * np.cos(t), y + radius * np.sin(t))))
    pts = np.vstack(pts + [pts[0][:1]])
    return pts, radius * (1 - math.cos(math.pi / 4 / (per_fillet - 1)))


@FEW
@example(radius=15.0, per_fillet=5, share=0.5 / 0.2883)  # the field's 200 x 100 mm, 15 mm fillets at σ 0.5
@example(radius=15.0, per_fillet=5, share=1.0)
@given(radius=st.floats(8.0, 30.0), per_fillet=st.integers(4, 7), share=st.floats(1.0, 4.0))
def test_a_rectangle_taught_with_its_fillets_is_rounded_where_the_sides_meet_them(radius, per_fillet, share):
    """The true shape (4 lines, 4 arcs, tangent) is within the fillet chords' sagitta of the
    taught polygon: at σ at least that, no vertex is a corner, no note, and no arc is
    tighter than the fillet's own circle allows (the caps' 1.25)."""
    pts, distance = _rounded_rectangle(200.0, 100.0, radius, per_fillet)
    tol = share * distance
    seg = segment_curve(make_curve(pts, "rounded rectangle", "yes"), tol)
    assert_contract(seg, tol)
    poly = seg.polysegment
    assert not poly.corners and not seg.notes, seg.notes
    assert poly.n_segments <= 3 * (len(pts) - 1) // 4
    radii = [s.radius for s in poly.segments if isinstance(s, Arc)]
    assert min(radii) >= radius / 1.25, f"r {min(radii):.4g} mm, the fillet's {radius:g} mm"


def _cardioid(scale: float, count: int) -> np.ndarray:
    """A cardioid r = a (1 + cos t) for t = 0.3 .. 2π − 0.3, ``count`` points evenly in t
    (close together at the cusp, t = π, which lies between two of them)."""
    t = np.linspace(0.3, TAU - 0.3, count)
    r = scale * (1 + np.cos(t))
    return np.column_stack((650 + r * np.cos(t), r * np.sin(t)))


@pytest.mark.parametrize("scale, count, tol", [(47.0, 40, 0.3), (47.0, 40, 1.0), (60.0, 36, 0.5), (35.0, 44, 0.3)])
def test_a_cardioid_taught_through_its_cusp_has_its_lobes_rounded(scale, count, tol):
    """The two points next to the cusp are a corner (a chain within σ cannot tell them
    apart, and together they turn back); the lobes either side come back as a few arcs,
    not as their own lines, with corners only right at the cusp."""
    pts = _cardioid(scale, count)
    seg = segment_curve(make_curve(pts, "cardioid", "no"), tol)
    assert_contract(seg, tol)
    poly = seg.polysegment
    assert not seg.notes, seg.notes
    assert poly.n_arcs >= 2 and poly.n_segments <= (count - 1) / 3
    ends = np.array([s.end for s in poly.segments])
    cusp = np.array([650.0, 0.0])
    assert poly.corners and all(np.linalg.norm(ends[k] - cusp) < 3 * tol + 0.1 for k in poly.corners)


def _star(count: int, lobe: float, phase: float) -> tuple[np.ndarray, float]:
    """A 5-lobed hypotrochoid (R − r = 40 mm, r = 10 mm, pen ``lobe`` mm off its centre)
    taught with ``count`` points evenly in its parameter from ``phase``, closed; and the
    polygon's tightest circle through three consecutive vertices (mm)."""
    t = phase + np.linspace(0.0, TAU, count + 1)
    pts = np.column_stack((40 * np.cos(t) + lobe * np.cos(4 * t), 40 * np.sin(t) - lobe * np.sin(4 * t)))
    pts[-1] = pts[0]
    a, b, c = np.roll(pts[:-1], 1, axis=0), pts[:-1], np.roll(pts[:-1], -1, axis=0)
    u, v = b - a, c - a
    cross = np.abs(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0])
    sides = np.linalg.norm(u, axis=1) * np.linalg.norm(c - b, axis=1) * np.linalg.norm(v, axis=1)
    return pts, float((sides / (2 * cross)).min())


@settings(max_examples=3, deadline=None, derandomize=True, database=None, phases=[Phase.explicit, Phase.generate])
@example(count=24, lobe=8.0, phase=0.0)
@given(count=st.sampled_from([20, 24, 28]), lobe=st.floats(6.0, 10.0), phase=st.floats(0.0, 0.2))
def test_a_taught_star_gets_no_more_segments_at_a_larger_tolerance(count, lobe, phase):
    """σ from 2 mm up to half the star's typical edge: each larger σ gives at most two
    segments more than a smaller one, the caps always hold (no fallback fit) and no arc is
    tighter than the polygon's own turning allows (its three-vertex circles, the caps' 1.25)."""
    pts, own = _star(count, lobe, phase)
    curve = make_curve(pts, "star", "yes")
    edge = float(np.median(np.linalg.norm(np.diff(pts, axis=0), axis=1)))
    fewest = math.inf
    for tol in np.linspace(2.0, edge / 2, 7):
        seg = segment_curve(curve, float(tol))
        assert_contract(seg, float(tol))
        assert seg.limits_kept is not False, f"σ {tol:.3f}: fallback fit"
        n = seg.polysegment.n_segments
        assert n <= fewest + 2, f"σ {tol:.3f}: {n} segments, {fewest} at a smaller σ"
        fewest = min(fewest, n)
        radii = [s.radius for s in seg.polysegment.segments if isinstance(s, Arc)]
        assert not radii or min(radii) >= own / 1.25, f"σ {tol:.3f}: r {min(radii):.4g} mm, own {own:.4g} mm"
