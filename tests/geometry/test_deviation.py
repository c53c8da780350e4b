"""The exact two-sided Hausdorff distance (coatsim.geometry.deviation) against analytic cases,
brute-force dense sampling, and rigid motions."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial import cKDTree

from coatsim.geometry import Arc, Line, Polysegment, chain
from coatsim.geometry.deviation import distance_to_polysegment, hausdorff

from geometry_helpers import brute_hausdorff, dense_polyline, dense_polysegment, distance_to_polyline, junction_points


def rotation(angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s], [s, c]])


def arc_through(center, radius, a0, sweep) -> Arc:
    cx, cy = center
    start = (cx + radius * math.cos(a0), cy + radius * math.sin(a0))
    end = (cx + radius * math.cos(a0 + sweep), cy + radius * math.sin(a0 + sweep))
    return Arc(start, end, (float(cx), float(cy)), float(radius), float(sweep))


# ---------------------------------------------------------------- analytic cases


@settings(max_examples=80, deadline=None)
@given(
    radius=st.floats(0.5, 2000.0),
    sweep=st.floats(0.05, 6.0),
    ccw=st.booleans(),
    n_edges=st.integers(1, 300),
    a0=st.floats(-math.pi, math.pi),
    center=st.tuples(st.floats(-500, 500), st.floats(-500, 500)),
)
def test_inscribed_polyline_vs_its_arc_is_the_sagitta(radius, sweep, ccw, n_edges, a0, center):
    """Vertices on the circle, equal steps h along it (each under half a turn): both directed
    deviations = R (1 - cos(h / 2R))."""
    n_edges = max(n_edges, math.ceil(sweep / 3.0))
    sweep = sweep if ccw else -sweep
    arc = arc_through(center, radius, a0, sweep)
    ang = a0 + np.linspace(0.0, sweep, n_edges + 1)
    pts = np.asarray(center) + radius * np.column_stack((np.cos(ang), np.sin(ang)))
    pts[0], pts[-1] = arc.start, arc.end
    h = abs(sweep) * radius / n_edges
    sagitta = radius * (1 - math.cos(h / (2 * radius)))
    dev = hausdorff(pts, Polysegment((arc,)))
    tol = 1e-9 * radius + 1e-12
    assert dev.hausdorff == pytest.approx(sagitta, abs=tol)
    assert dev.input_to_output == pytest.approx(sagitta, abs=tol)
    assert dev.output_to_input == pytest.approx(sagitta, abs=tol)


def test_sagitta_fixed_example():
    arc = arc_through((10.0, -5.0), 40.0, 0.3, math.pi / 2)
    ang = 0.3 + np.linspace(0, math.pi / 2, 21)
    pts = np.array([10.0, -5.0]) + 40.0 * np.column_stack((np.cos(ang), np.sin(ang)))
    h = 40.0 * (math.pi / 2) / 20
    assert hausdorff(pts, Polysegment((arc,))).hausdorff == pytest.approx(40.0 * (1 - math.cos(h / 80.0)), rel=1e-9)


@settings(max_examples=60, deadline=None)
@given(
    offset=st.floats(1e-4, 50.0),
    length=st.floats(1.0, 500.0),
    n=st.integers(2, 50),
    angle=st.floats(-math.pi, math.pi),
    shift=st.tuples(st.floats(-1e3, 1e3), st.floats(-1e3, 1e3)),
)
def test_straight_line_offset_by_d(offset, length, n, angle, shift):
    xs = np.linspace(0.0, length, n)
    rot, off = rotation(angle), np.asarray(shift)
    pts = np.column_stack((xs, np.zeros(n))) @ rot.T + off
    a, b = np.array([0.0, offset]) @ rot.T + off, np.array([length, offset]) @ rot.T + off
    dev = hausdorff(pts, Polysegment((Line(tuple(a), tuple(b)),)))
    assert dev.hausdorff == pytest.approx(offset, rel=1e-9, abs=1e-9)
    assert dev.input_to_output == pytest.approx(offset, rel=1e-9, abs=1e-9)
    assert dev.output_to_input == pytest.approx(offset, rel=1e-9, abs=1e-9)


def test_line_longer_than_the_polyline():
    pts = np.column_stack((np.linspace(0.0, 100.0, 11), np.zeros(11)))
    line = Line((-3.0, 4.0), (100.0, 4.0))  # overhangs by 3 at an offset of 4
    dev = hausdorff(pts, Polysegment((line,)))
    assert dev.output_to_input == pytest.approx(5.0, rel=1e-12)
    assert dev.input_to_output == pytest.approx(4.0, rel=1e-12)
    assert dev.hausdorff == pytest.approx(5.0, rel=1e-12)


def test_arc_bulging_outside_a_chord_polyline():
    """A single chord under a half circle: the farthest points are the chord's middle
    (one way) and the arc's apex (the other)."""
    arc = arc_through((0.0, 0.0), 10.0, 0.0, math.pi)  # (10, 0) -> (-10, 0) over the top
    pts = np.array([[10.0, 0.0], [-10.0, 0.0]])
    dev = hausdorff(pts, Polysegment((arc,)))
    assert dev.input_to_output == pytest.approx(10.0, rel=1e-12)
    assert dev.output_to_input == pytest.approx(10.0, rel=1e-12)


SAMPLE_CHAIN = chain((5.0, -3.0), 0.4, [0.0, 1 / 25, 0.0, -1 / 12, 1 / 60], [30.0, 40.0, 15.0, 20.0, 50.0])


@pytest.mark.parametrize("step", [4.0, 2.0, 1.0, 0.5, 0.25, 0.1])
def test_polysegment_vs_its_own_samples_is_the_largest_sagitta(step):
    poly = Polysegment(SAMPLE_CHAIN)
    pts, _ = poly.sample(step)
    expected = 0.0
    for seg in poly.segments:
        if isinstance(seg, Arc):
            h = seg.length / math.ceil(seg.length / step)
            expected = max(expected, seg.radius * (1 - math.cos(h / (2 * seg.radius))))
    dev = hausdorff(pts, poly)
    assert dev.hausdorff == pytest.approx(expected, rel=1e-7, abs=1e-12)
    assert dev.hausdorff <= step**2 / (8 * 12) * (1 + 1e-6)  # tends to 0 like step² / 8R_min


# ---------------------------------------------------------------- brute force


@st.composite
def g1_chains(draw, max_segments: int = 4, max_kappa: float = 0.5, max_turn: float = 3.0 * 4):
    """G1 line/arc chains; ``max_turn`` bounds the total turning (rad)."""
    n = draw(st.integers(1, max_segments))
    kappas, lengths = [], []
    turn_left = max_turn
    for _ in range(n):
        kind = draw(st.sampled_from([0, 1, -1]))
        kappa = kind * draw(st.floats(0.02, max_kappa))
        length = draw(st.floats(2.0, 25.0))
        if kappa:
            length = min(length, min(3.0, max(turn_left, 0.05)) / abs(kappa))  # sweeps up to ~170°
            turn_left -= abs(kappa) * length
        kappas.append(kappa)
        lengths.append(length)
    start = (draw(st.floats(-100, 100)), draw(st.floats(-100, 100)))
    return Polysegment(chain(start, draw(st.floats(-math.pi, math.pi)), kappas, lengths))


@settings(max_examples=40, deadline=None)
@given(poly=g1_chains(), seed=st.integers(0, 2**32 - 1), n_query=st.integers(1, 200))
def test_distance_to_polysegment_matches_dense_sampling(poly, seed, n_query):
    rng = np.random.default_rng(seed)
    pts_on = poly.sample(0.5)[0]
    lo, hi = pts_on.min(axis=0) - 10, pts_on.max(axis=0) + 10
    query = rng.uniform(lo, hi, (n_query, 2))
    query[: min(5, n_query)] = pts_on[rng.integers(0, len(pts_on), min(5, n_query))]  # points on the curve
    step = 1e-3
    dense = dense_polysegment(poly, step)
    brute = cKDTree(dense).query(query)[0]
    d, idx, foot = distance_to_polysegment(query, poly)
    assert np.all(d <= brute + 1e-9)  # the exact distance is never above a sampled one
    assert np.all(brute <= d + step / 2 + 1e-9)  # and the samples are within step / 2 of the curve
    np.testing.assert_allclose(np.linalg.norm(query - foot, axis=1), d, atol=1e-9)
    assert cKDTree(dense).query(foot)[0].max() <= step / 2 + 1e-9  # the foot lies on the curve
    for j in np.unique(idx):  # the reported segment is one at that distance
        seg_d, _, _ = distance_to_polysegment(query[idx == j], Polysegment((poly.segments[j],)))
        np.testing.assert_allclose(seg_d, d[idx == j], atol=1e-9)


@st.composite
def noisy_samples(draw):
    """The fitter's regime: a G1 chain that does not fold back on itself (radii >= 5 mm, at most
    half a turn in all), sampled with at least ``per`` edges on its shortest segment and moved
    by noise well below the radii. Sparse polylines are covered by the tests at the end."""
    poly = draw(g1_chains(max_kappa=0.2, max_turn=math.pi))
    per = draw(st.integers(3, 12))
    noise = draw(st.floats(0.0, 0.1))
    seed = draw(st.integers(0, 2**32 - 1))
    pts = poly.sample(min(s.length for s in poly.segments) / per)[0]
    pts = pts + np.random.default_rng(seed).normal(0.0, noise, pts.shape)
    return poly, pts


@settings(max_examples=40, deadline=None)
@given(noisy_samples())
def test_hausdorff_matches_dense_sampling(case):
    poly, pts = case
    step = 1e-3
    brute = brute_hausdorff(pts, poly, step)
    dev = hausdorff(pts, poly)
    assert dev.hausdorff >= brute - step / 2 - 1e-9, "under-reports the deviation"
    assert dev.hausdorff <= brute + step / 2 + 1e-9, "over-reports the deviation"
    # Each directed part is an attained distance: never above the two-sided value, and the
    # polyline -> polysegment part is at least the distance of every vertex.
    assert max(dev.input_to_output, dev.output_to_input) == dev.hausdorff
    assert dev.input_to_output >= distance_to_polysegment(pts, poly)[0].max() - 1e-12


@st.composite
def folded_noisy_samples(draw):
    """Harder: radii down to 2 mm, chains that fold back on themselves, noise up to 0.3 mm."""
    poly = draw(g1_chains())
    per = draw(st.integers(3, 12))
    noise = draw(st.floats(0.0, 0.3))
    seed = draw(st.integers(0, 2**32 - 1))
    pts = poly.sample(min(s.length for s in poly.segments) / per)[0]
    return poly, pts + np.random.default_rng(seed).normal(0.0, noise, pts.shape)


@settings(max_examples=30, deadline=None)
@given(folded_noisy_samples())
def test_hausdorff_matches_dense_sampling_on_folded_noisy_chains(case):
    """Regression: a 15 % under-report was once found here (switch points between distant
    parts of a folded chain)."""
    poly, pts = case
    step = 1e-3
    brute = brute_hausdorff(pts, poly, step)
    assert hausdorff(pts, poly).hausdorff == pytest.approx(brute, abs=step / 2 + 1e-9)


@settings(max_examples=40, deadline=None)
@given(
    noisy_samples(),
    st.floats(-math.pi, math.pi),
    st.tuples(st.floats(-5e3, 5e3), st.floats(-5e3, 5e3)),
    st.floats(0.05, 20.0),
    st.booleans(),
)
def test_invariant_under_rigid_motion_and_scaling(case, angle, shift, scale, mirror):
    poly, pts = case
    mat = rotation(angle) @ (np.diag([1.0, -1.0]) if mirror else np.eye(2))
    moved_pts = scale * pts @ mat.T + np.asarray(shift)
    moved = poly.transformed(mat, shift, scale)
    before = hausdorff(pts, poly)
    after = hausdorff(moved_pts, moved)
    atol = 1e-9 * scale * (1 + np.abs(pts).max()) + 1e-9 * np.abs(shift).max()
    assert after.hausdorff == pytest.approx(scale * before.hausdorff, abs=atol + 1e-9 * scale * before.hausdorff)


def test_polyline_order_and_direction_do_not_matter():
    poly = Polysegment(SAMPLE_CHAIN)
    pts = poly.sample(1.7)[0] + np.random.default_rng(3).normal(0, 0.05, (len(poly.sample(1.7)[0]), 2))
    reversed_poly = Polysegment(tuple(s.reversed() for s in reversed(poly.segments)))
    a = hausdorff(pts, poly).hausdorff
    assert hausdorff(pts[::-1], poly).hausdorff == pytest.approx(a, abs=1e-12)
    assert hausdorff(pts, reversed_poly).hausdorff == pytest.approx(a, abs=1e-12)


# ---------------------------------------------------------------- regressions and findings

TENT = Polysegment((Line((-1.0, 0.0), (0.0, 1.0)), Line((0.0, 1.0), (1.0, 0.0))), corners=(0,))
TENT_INPUT = np.array([[-1.0, 0.0], [1.0, 0.0], [0.0, 1.0]])


def test_hausdorff_sees_maxima_between_candidate_points():
    """Regression: maxima where the nearest feature switches (a polyline edge passing under a
    polysegment corner) were once missed: 0 reported where the distance is 1/sqrt(2)."""
    brute = brute_hausdorff(TENT_INPUT, TENT, 1e-3)
    assert brute == pytest.approx(math.sqrt(0.5), abs=1e-3)
    assert hausdorff(TENT_INPUT, TENT).hausdorff == pytest.approx(brute, abs=1e-3)


def test_directed_parts_on_the_tent():
    """Regression: the polysegment -> polyline part once missed the switch point on the tent
    (0.5625 reported, 2 - sqrt 2 true): the bisector of the polyline's vertex crosses the far leg."""
    dev = hausdorff(TENT_INPUT, TENT)
    a = dense_polyline(TENT_INPUT, 1e-3)
    b = dense_polysegment(TENT, 1e-3)
    true_in = distance_to_polysegment(a, TENT)[0].max()
    true_out = distance_to_polyline(b, TENT_INPUT).max()
    assert dev.input_to_output == pytest.approx(true_in, abs=1e-3)
    assert dev.output_to_input == pytest.approx(true_out, abs=1e-3)


def _beside_the_arc():
    poly = Polysegment(chain((0.0, 0.0), 0.5, [0.0, -0.1, 0.0], [10.0, 10.0, 10.0]))  # R 10 arc turning 1 rad
    line0, line2 = poly.segments[0], poly.segments[2]
    a = np.add(line0.start, 0.95 * np.subtract(line0.end, line0.start))
    b = np.add(line2.start, 0.05 * np.subtract(line2.end, line2.start))
    return poly, np.array([poly.start, a, b, poly.end])


def _at_the_junctions():
    poly = Polysegment(chain((0.0, 0.0), 0.0, [0.0, 0.25, 0.0], [2.0, 2.0, 2.0]))  # R 4 arc turning 0.5 rad
    return poly, junction_points(poly)


@pytest.mark.parametrize("build", [_beside_the_arc, _at_the_junctions], ids=["beside", "junctions"])
def test_sparse_polyline_around_an_arc(build):
    """Regression: when no input vertex had an arc as its nearest segment, the arc's sagitta
    points were never tried (0.24 reported for 1.46 mm; 0 for 0.124 mm)."""
    poly, pts = build()
    brute = brute_hausdorff(pts, poly, 1e-3)
    assert brute > 0.1
    assert hausdorff(pts, poly).hausdorff == pytest.approx(brute, abs=1e-3)


@settings(max_examples=30, deadline=None)
@given(poly=g1_chains(max_segments=3), seed=st.integers(0, 2**32 - 1))
def test_sparse_polylines_through_the_junctions(poly, seed):
    """Polylines coarser than the chain: a few points per chain, junctions included, moved by
    up to 0.2 mm; the deviation must still match dense sampling. Regression: the distance from
    the chain can peak where the polyline's nearest feature switches (its medial axis); points
    sampled along the segments once under-reported it (2.7255 for 2.7301 mm)."""
    pts = junction_points(poly)
    pts = pts + np.random.default_rng(seed).uniform(-0.2, 0.2, pts.shape)
    step = 1e-3
    brute = brute_hausdorff(pts, poly, step)
    assert hausdorff(pts, poly).hausdorff == pytest.approx(brute, abs=step / 2 + 1e-9)


# ---------------------------------------------------------------- many input styles, large N


@st.composite
def polylines_near(draw):
    """Polylines written in many styles around a G1 chain: its samples at random arc lengths
    (any density, sparse to dense), moved by noise, thinned, reversed, or shifted wholesale."""
    poly = draw(g1_chains())
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    n = draw(st.sampled_from([3, 7, 30, 200, 2000]))
    dense = poly.sample(poly.length / 4000)[0]
    idx = np.sort(rng.choice(len(dense), size=min(n, len(dense)), replace=False))
    pts = dense[np.unique(np.r_[0, idx, len(dense) - 1])]
    pts = pts + rng.normal(0.0, draw(st.sampled_from([0.0, 1e-3, 0.05, 0.3])), pts.shape)
    pts = pts + np.asarray(draw(st.sampled_from([(0.0, 0.0), (0.3, -0.2), (4.0, 1.0)])))
    if draw(st.booleans()):
        pts = pts[::-1]
    return poly, pts


@settings(max_examples=30, deadline=None)
@given(polylines_near())
def test_hausdorff_matches_dense_sampling_in_many_styles(case):
    poly, pts = case
    step = 2e-3
    brute = brute_hausdorff(pts, poly, step)
    dev = hausdorff(pts, poly)
    assert dev.hausdorff == pytest.approx(brute, abs=step / 2 + 1e-9)
    assert dev.input_to_output >= distance_to_polysegment(pts, poly)[0].max() - 1e-12


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 2**32 - 1), st.floats(1e-9, 1e-4), st.floats(-0.5, 0.5))
def test_nearly_straight_arcs_of_huge_radius_are_measured_exactly(seed, sweep, offset):
    """An arc of radius up to 1e14 mm is a line to within its sagitta: the distance of
    points beside it must be exact to 1e-9 mm (centre-based formulas lose every digit)."""
    length = 100.0
    arc = Polysegment(chain((3.0, -2.0), 0.7, [sweep / length], [length]))
    seg = arc.segments[0]
    assert isinstance(seg, Arc) and seg.radius >= 1e6
    rng = np.random.default_rng(seed)
    s = np.sort(rng.uniform(0.0, length, 50))
    on = seg.points(s)
    normal = np.column_stack((-np.sin(0.7 + sweep * s / length), np.cos(0.7 + sweep * s / length)))
    beside = on + offset * normal
    d, _, foot = distance_to_polysegment(beside, arc)
    np.testing.assert_allclose(d, abs(offset), atol=1e-9)
    np.testing.assert_allclose(foot, on, atol=1e-8)


def _long_noisy_chain(n: int, seed: int = 5, noise: float = 0.01):
    poly = Polysegment(chain((0.0, 0.0), 0.3, [0.0, 1 / 40, 0.0, -1 / 25, 1 / 90, 0.0],
                             [60.0, 70.0, 25.0, 50.0, 120.0, 40.0]))
    pts, _ = poly.sample(poly.length / (n - 1))
    return poly, pts + np.random.default_rng(seed).normal(0.0, noise, pts.shape)


@pytest.mark.parametrize("n,seed", [(20_000, 3), pytest.param(50_000, 1, marks=pytest.mark.slow)])
def test_directed_parts_on_a_dense_noisy_polyline(n, seed):
    """Points with 0.01 mm noise around 365 mm of chain: the polysegment -> polyline part
    peaks in a gap of the scribble, between edges far apart along the polyline (once
    under-reported by 6 %: 0.0186 for >= 0.0198 mm at 50 000 points)."""
    poly, pts = _long_noisy_chain(n, seed)
    step = 2e-4
    dev = hausdorff(pts, poly)
    a, b = dense_polyline(pts, step), dense_polysegment(poly, step)
    assert dev.input_to_output == pytest.approx(cKDTree(b).query(a)[0].max(), abs=step / 2 + 1e-9)
    assert dev.output_to_input == pytest.approx(cKDTree(a).query(b)[0].max(), abs=step / 2 + 1e-9)


@pytest.mark.slow
def test_hausdorff_at_200k_points_matches_dense_sampling():
    """The fitter's large-input regime: 200 000 noisy points (edges of 2 µm, about the
    noise); both directed parts against dense sampling at 0.2 µm."""
    poly, pts = _long_noisy_chain(200_000, noise=0.002)
    step = 2e-4
    dev = hausdorff(pts, poly)
    a, b = dense_polyline(pts, step), dense_polysegment(poly, step)
    true_in = cKDTree(b).query(a)[0].max()
    true_out = cKDTree(a).query(b)[0].max()
    assert dev.input_to_output == pytest.approx(true_in, abs=step / 2 + 1e-9)
    assert dev.output_to_input == pytest.approx(true_out, abs=step / 2 + 1e-9)
    # every vertex's exact distance is at most the reported maximum, and one reaches it
    vertex = distance_to_polysegment(pts, poly)[0]
    assert vertex.max() <= dev.input_to_output + 1e-12


@pytest.mark.filterwarnings("error")
@pytest.mark.parametrize("pts", [
    [[0, 0], [0, 0], [5, 0.1], [5, 0.1], [10, 0.2], [30, 5]],  # repeated vertices
    [[0, 0], [20, 0], [0, 0], [20, 0]],  # back and forth over itself
    [[100, 100], [100, 100.0000001]],  # far away, one tiny edge
], ids=["repeated", "back-and-forth", "far"])
def test_degenerate_polylines_match_dense_sampling_without_warnings(pts):
    poly = Polysegment(chain((0.0, 0.0), 0.0, [0.0, 0.1, 0.0], [10.0, 10.0, 10.0]))
    pts = np.asarray(pts, dtype=float)
    dev = hausdorff(pts, poly)
    a, b = dense_polyline(pts, 1e-3), dense_polysegment(poly, 1e-3)
    assert dev.input_to_output == pytest.approx(cKDTree(b).query(a)[0].max(), abs=5e-4)
    assert dev.output_to_input == pytest.approx(cKDTree(a).query(b)[0].max(), abs=5e-4)
