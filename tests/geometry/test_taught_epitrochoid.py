"""A taught epitrochoid (three lobes with a shallow dimple between each two) comes back as a
few arcs, not as its own lines: the dimple's vertex turns against its neighbours, so the
windowed curvature reads it as the loop's calmest point, and a loop fitted from there may not
close; other seams do (segment._other_seams). Few segments (not the polygon's own lines),
within σ, no arc much tighter than the polygon's own three-point circle."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import Phase, example, given, settings
from hypothesis import strategies as st

from coatsim.geometry import Arc, make_curve, segment_curve
from coatsim.geometry.sparse import own_radius

from geometry_helpers import assert_contract

FEW = settings(max_examples=1, deadline=None, derandomize=True, database=None,
               phases=[Phase.explicit, Phase.generate])  # a fit is a few seconds: no shrinking


def taught_epitrochoid(moves: int, d: float, uneven: bool, share: float, seed: int,
                       jitter: float = 0.2, samples: int = 20_001) -> tuple[np.ndarray, float]:
    """A closed polygon (last point = first) of ``moves`` vertices along the epitrochoid
    R 30, r 10, ``d`` (spaced evenly or unevenly along its length, jittered by ``jitter`` σ) and
    σ, ``share`` of the polygon's chordal deviation from the curve."""
    rng = np.random.default_rng(seed)
    t = np.linspace(0.0, 2 * math.pi, samples)
    curve = np.column_stack((40 * np.cos(t) - d * np.cos(4 * t), 40 * np.sin(t) - d * np.sin(4 * t)))
    s = np.concatenate(([0.0], np.cumsum(np.linalg.norm(np.diff(curve, axis=0), axis=1))))
    step = rng.uniform(0.4, 1.6, moves) if uneven else np.ones(moves)
    knots = np.concatenate(([0.0], np.cumsum(step))) / step.sum() * s[-1]
    poly = np.column_stack((np.interp(knots, s, curve[:, 0]), np.interp(knots, s, curve[:, 1])))
    sag = 0.0
    for a, b, lo, hi in zip(poly[:-1], poly[1:], knots[:-1], knots[1:]):
        edge = b - a
        inner = curve[(s >= lo) & (s <= hi)] - a
        sag = max(sag, float(np.abs(inner @ np.array([-edge[1], edge[0]])).max(initial=0.0)) / np.hypot(*edge))
    tol = share * sag
    poly[:-1] += rng.normal(0.0, jitter * tol, (moves, 2))
    poly[-1] = poly[0]
    return poly, tol


@FEW
@example(moves=20, d=5.0, uneven=False, share=0.7, seed=2)
@given(moves=st.integers(20, 24), d=st.floats(4.0, 6.0), uneven=st.booleans(), share=st.floats(0.7, 1.0),
       seed=st.integers(0, 2**16))
def test_a_taught_epitrochoid_comes_back_as_few_gentle_arcs(moves, d, uneven, share, seed):
    pts, tol = taught_epitrochoid(moves, d, uneven, share, seed)
    seg = segment_curve(make_curve(pts, "taught epitrochoid", "yes"), tol)
    assert_contract(seg, tol)
    poly = seg.polysegment
    assert poly.n_segments <= 0.45 * moves, f"{poly.n_segments} segments for {moves} moves"
    radii = [s.radius for s in poly.segments if isinstance(s, Arc)]
    assert min(radii) >= 0.7 * own_radius(pts, True), f"r {min(radii):.3g} mm, own {own_radius(pts, True):.3g} mm"


def test_a_clean_epitrochoid_back_as_its_lines_is_fitted_again_at_the_best_aim():
    """30 clean vertices at 0.7 of their chordal deviation: the fit came back as its lines; fitted
    again from 0.6 σ it kept 27 segments, 21 vertices as corners, and a note saying a tolerance
    below the one given rounds them. From 0.95 σ it is 9 to 11 arcs (the fit is chaotic in the last digits)."""
    pts, tol = taught_epitrochoid(30, 4.0, False, 0.7, 0, jitter=0.0, samples=40_001)
    seg = segment_curve(make_curve(pts, "taught epitrochoid", "yes"), tol)
    assert_contract(seg, tol)
    assert seg.polysegment.n_segments <= 12 and not seg.polysegment.corners and not seg.notes
