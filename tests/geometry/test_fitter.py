"""The default fitter (method "optimal"): tolerance, tangent continuity, shared end points,
closure, segment counts against the bench references, exact shapes, invariance and noise."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from coatsim.core.errors import InputError
from coatsim.geometry import Arc, Line, Polysegment, chain, load_curve, make_curve, segment_curve
from coatsim.geometry.deviation import hausdorff

from geometry_helpers import (
    BENCH_CLOSED,
    BENCH_NAMES,
    arc_defects,
    bench_spec,
    brute_hausdorff,
    curve,
    junction_gaps,
    junction_points,
    reference_counts,
    segmented,
    tangent_breaks,
)

G1 = 1e-9  # rad: largest tangent break allowed at a junction that is not a listed corner


def rotation(angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s], [s, c]])


def assert_within_tolerance(seg, tol):
    pts = seg.curve.points
    poly = seg.polysegment
    assert seg.max_deviation_mm <= tol
    assert hausdorff(pts, poly).hausdorff <= tol
    step = tol / 25
    assert brute_hausdorff(pts, poly, step) <= tol + step / 2


def assert_g1_chain(poly):
    assert junction_gaps(poly) == [], "consecutive segments must share end points exactly"
    assert arc_defects(poly) == []
    assert list(poly.corners) == sorted(set(poly.corners))
    n_junctions = poly.n_segments - 1 + poly.closed
    assert all(0 <= k < n_junctions for k in poly.corners)
    for k, turn in tangent_breaks(poly):
        if k not in poly.corners:
            assert turn <= G1, f"junction {k} breaks the tangent by {turn:.3g} rad"
    assert all(s.length > 0 for s in poly.segments)


def assert_closed_or_open_ends(seg):
    poly, pts = seg.polysegment, seg.curve.points
    if seg.curve.closed:
        assert poly.closed
        assert poly.end == poly.start, f"closed chain ends {np.subtract(poly.end, poly.start)} from its start"
        if poly.n_segments - 1 not in poly.corners:
            assert tangent_breaks(poly)[-1][1] <= G1
    else:
        assert not poly.closed
        assert poly.start == tuple(pts[0]) and poly.end == tuple(pts[-1]), "open chain must keep the end points"


# ---------------------------------------------------------------- bench curves

DEFAULT_TOLS = (0.05, 0.5)
SLOW_TOLS = (0.01, 0.1)
BENCH_CASES = [(n, t) for n in BENCH_NAMES for t in DEFAULT_TOLS]


@pytest.fixture(scope="module")
def refs():
    return reference_counts()


@pytest.mark.parametrize("name,tol", BENCH_CASES)
def test_bench_within_tolerance(name, tol):
    assert_within_tolerance(segmented(bench_spec(name), tol), tol)


@pytest.mark.parametrize("name,tol", BENCH_CASES)
def test_bench_tangent_continuous_chain(name, tol):
    assert_g1_chain(segmented(bench_spec(name), tol).polysegment)


@pytest.mark.parametrize("name,tol", BENCH_CASES)
def test_bench_closed_curves_close_and_open_curves_keep_their_ends(name, tol):
    seg = segmented(bench_spec(name), tol)
    assert seg.curve.closed is BENCH_CLOSED[name]
    assert_closed_or_open_ends(seg)


@pytest.mark.parametrize("name,tol", BENCH_CASES)
def test_bench_segment_count_against_the_greedy_reference(name, tol, refs):
    greedy = refs["greedy"][name][tol]
    seg = segmented(bench_spec(name), tol)
    assert seg.polysegment.n_segments <= 2 * greedy
    st_ = seg.stats()
    assert st_["n_segments"] == seg.polysegment.n_segments == st_["n_arcs"] + st_["n_lines"]


def test_reference_table_is_complete(refs):
    assert set(refs["greedy"]) == set(BENCH_NAMES)
    assert all(len(v) == 4 for v in refs["greedy"].values())
    assert refs["paper"]["spiral"][0.1] == 69


@pytest.mark.parametrize("tol", DEFAULT_TOLS)
def test_naca_lists_its_trailing_edge_corner(tol):
    seg = segmented(bench_spec("naca0012"), tol)
    poly = seg.polysegment
    te = seg.curve.points[np.argmax(seg.curve.points[:, 0])]
    assert len(poly.corners) == 1
    k = poly.corners[0]
    assert np.allclose(poly.segments[k].end, te, atol=1e-9)
    assert dict(tangent_breaks(poly))[k] > math.radians(90)


@pytest.mark.slow
@pytest.mark.parametrize("name,tol", [(n, t) for n in BENCH_NAMES for t in SLOW_TOLS])
def test_bench_at_fine_and_medium_tolerances(name, tol, refs):
    seg = segmented(bench_spec(name), tol)
    assert_within_tolerance(seg, tol)
    assert_g1_chain(seg.polysegment)
    assert seg.polysegment.n_segments <= 2 * refs["greedy"][name][tol]
    assert_closed_or_open_ends(seg)


# ---------------------------------------------------------------- exact shapes

ROUNDRECT_SPECS = [pytest.param(bench_spec("roundrect"), id="bench-roundrect"),
                   pytest.param("builtin:rounded-rectangle", id="builtin")]


@pytest.mark.parametrize("spec", ROUNDRECT_SPECS)
@pytest.mark.parametrize("tol", [1e-3, 0.05, 0.5, 1.0])
def test_rounded_rectangle_is_exactly_four_lines_and_four_arcs(spec, tol):
    seg = segmented(spec, tol)
    poly = seg.polysegment
    assert poly.n_segments == 8 and poly.n_lines == 4 and poly.n_arcs == 4
    kinds = [s.kind for s in poly.segments]
    assert kinds in (["line", "arc"] * 4, ["arc", "line"] * 4)
    for s in poly.segments:
        if isinstance(s, Arc):
            assert s.radius == pytest.approx(10.0, abs=1e-6)
            assert s.sweep == pytest.approx(math.pi / 2, abs=1e-6)
    lines = sorted(s.length for s in poly.segments if isinstance(s, Line))
    np.testing.assert_allclose(lines, [60, 60, 130, 130], atol=1e-6)
    assert poly.corners == ()
    assert max(b for _, b in tangent_breaks(poly)) <= G1
    assert seg.max_deviation_mm <= tol
    assert hausdorff(seg.curve.points, poly).hausdorff <= tol


@pytest.mark.parametrize("sides", [3, 5, 8])
@pytest.mark.parametrize("tol", [0.05, 0.5])
def test_polygon_is_its_sides_with_every_corner_listed(sides, tol):
    seg = segmented(f"builtin:polygon:sides={sides}", tol)
    poly = seg.polysegment
    assert poly.n_segments == sides and poly.n_lines == sides
    assert poly.corners == tuple(range(sides))
    ang = math.pi / 2 + 2 * math.pi * np.arange(sides) / sides
    vertices = 60.0 * np.column_stack((np.cos(ang), np.sin(ang)))
    got = junction_points(poly)[:-1]
    for v in vertices:
        assert np.linalg.norm(got - v, axis=1).min() < 1e-9
    for _, turn in tangent_breaks(poly):
        assert turn == pytest.approx(2 * math.pi / sides, abs=1e-9)
    assert seg.max_deviation_mm <= 1e-9


@pytest.mark.parametrize("tol", [1e-3, 0.05, 0.5])
def test_d_shape_is_its_exact_primitives(tol):
    poly = segmented("builtin:d-shape", tol).polysegment
    assert [s.kind for s in poly.segments] == ["line", "arc", "line", "line"]
    arc = poly.segments[1]
    assert arc.radius == pytest.approx(50.0, abs=1e-6) and arc.sweep == pytest.approx(math.pi, abs=1e-6)
    np.testing.assert_allclose([poly.segments[k].length for k in (0, 2, 3)], [40, 40, 100], atol=1e-6)
    assert poly.corners == (2, 3)
    breaks = dict(tangent_breaks(poly))
    assert breaks[0] <= G1 and breaks[1] <= G1
    assert breaks[2] == pytest.approx(math.pi / 2, abs=1e-6) and breaks[3] == pytest.approx(math.pi / 2, abs=1e-6)


@pytest.mark.parametrize("tol", [0.05, 0.5])
def test_raster_is_its_exact_primitives(tol):
    poly = segmented("builtin:raster", tol).polysegment
    assert [s.kind for s in poly.segments] == ["line", "arc"] * 5 + ["line"]
    sweeps = [s.sweep for s in poly.segments if isinstance(s, Arc)]
    np.testing.assert_allclose(sweeps, [math.pi, -math.pi] * 2 + [math.pi], atol=1e-6)
    assert all(s.radius == pytest.approx(10.0, abs=1e-6) for s in poly.segments if isinstance(s, Arc))
    np.testing.assert_allclose([s.length for s in poly.segments if isinstance(s, Line)], [200.0] * 6, atol=1e-6)
    assert poly.corners == ()
    assert max(b for _, b in tangent_breaks(poly)) <= G1


@pytest.mark.parametrize(
    "spec", ["builtin:rounded-rectangle", bench_spec("roundrect"), "builtin:d-shape", "builtin:raster", "builtin:polygon"])
def test_exact_shapes_share_end_points_and_keep_the_input_ends(spec):
    """Regression: exact recovery once left the rounded rectangle's seam open by 3e-10 mm, a
    3e-14 mm gap at the d-shape's corner and the raster's end 3e-12 mm off the input's."""
    seg = segmented(spec, 0.5)
    assert_g1_chain(seg.polysegment)
    assert_closed_or_open_ends(seg)


# ---------------------------------------------------------------- invariance

INVARIANCE_CASES = {"ellipse": ("builtin:ellipse:points=1500", 0.1), "spiral": ("builtin:paper-spiral:points=1500", 0.5)}


def _moved(name, angle, shift, scale):
    spec, tol = INVARIANCE_CASES[name]
    base = curve(spec)
    moved = base.transformed(rotation(angle), np.asarray(shift), scale)
    return base, moved, tol


@settings(max_examples=5, deadline=None, derandomize=True)
@given(
    name=st.sampled_from(sorted(INVARIANCE_CASES)),
    angle=st.floats(-math.pi, math.pi),
    shift=st.tuples(st.floats(-2000, 2000), st.floats(-2000, 2000)),
    scale=st.floats(0.1, 10.0),
)
def test_rigid_motion_and_scale_keep_the_segment_count(name, angle, shift, scale):
    base, moved, tol = _moved(name, angle, shift, scale)
    ref = segmented(INVARIANCE_CASES[name][0], tol)
    seg = segment_curve(moved, tol * scale)
    assert seg.polysegment.n_segments == ref.polysegment.n_segments
    assert seg.max_deviation_mm <= tol * scale
    assert hausdorff(moved.points, seg.polysegment).hausdorff <= tol * scale
    assert_g1_chain(seg.polysegment)
    assert_closed_or_open_ends(seg)


@pytest.mark.xfail(strict=True, reason="the fitted chain is not equivariant: after a rotation + translation + "
                   "scale the segment count is the same but the junctions land elsewhere, by up to ~17 sigma "
                   "(ellipse, sigma 0.1) and ~99 sigma (spiral, sigma 0.5); float-level differences change the "
                   "greedy band fit's choices")
@pytest.mark.parametrize("name", sorted(INVARIANCE_CASES))
def test_rigid_motion_moves_the_junctions_with_the_curve(name):
    transforms = [(4.0, (310.0, -25.0), 0.35), (2.46, (-800.0, 120.0), 6.0), (0.53, (5.0, 5.0), 1.7)]
    ref = segmented(INVARIANCE_CASES[name][0], INVARIANCE_CASES[name][1])
    for angle, shift, scale in transforms:
        _, moved, tol = _moved(name, angle, shift, scale)
        seg = segment_curve(moved, tol * scale)
        expected = scale * junction_points(ref.polysegment) @ rotation(angle).T + np.asarray(shift)
        got = junction_points(seg.polysegment)
        assert got.shape == expected.shape
        assert np.abs(got - expected).max() <= 2 * tol * scale


# ---------------------------------------------------------------- noise


def _jittered(spec, sigma, seed):
    c = load_curve(spec)
    pts = c.points + np.random.default_rng(seed).normal(0.0, sigma, c.points.shape)
    if c.closed:
        pts[-1] = pts[0]
    return make_curve(pts, f"{spec} + noise", "yes" if c.closed else "no")


NOISE_CASES = [
    pytest.param("builtin:paper-spiral:points=5000", id="spiral"),
    pytest.param("builtin:ellipse:points=5000", id="ellipse"),
]


@pytest.mark.parametrize("spec", NOISE_CASES)
def test_small_noise_does_not_raise_the_count_much(spec):
    tol = 0.05
    clean = segmented(spec, tol).polysegment.n_segments
    for seed in (0, 1, 2):
        noisy = segment_curve(_jittered(spec, 0.005, seed), tol)
        assert noisy.max_deviation_mm <= tol
        assert noisy.polysegment.corners == ()
        assert_g1_chain(noisy.polysegment)
        assert noisy.polysegment.n_segments <= 1.2 * clean, f"seed {seed}: {noisy.polysegment.n_segments} vs {clean}"


# ---------------------------------------------------------------- other inputs


@pytest.mark.parametrize("spec,tol", [("builtin:cam", 0.05), ("builtin:epitrochoid", 0.1), ("builtin:clothoid", 0.05),
                                      ("builtin:naca:points=2000", 0.1), ("builtin:sine:points=800", 0.2)])
def test_other_builtins_meet_the_contract(spec, tol):
    seg = segmented(spec, tol)
    assert_within_tolerance(seg, tol)
    assert_g1_chain(seg.polysegment)
    assert_closed_or_open_ends(seg)


def test_a_straight_input_is_one_line():
    pts = np.column_stack((np.linspace(0, 100, 50), np.linspace(0, 30, 50)))
    poly = segment_curve(make_curve(pts, "straight"), 0.01).polysegment
    assert poly.n_segments == 1 and isinstance(poly.segments[0], Line)
    assert poly.start == (0.0, 0.0) and poly.end == (100.0, 30.0)


def test_deterministic():
    a = segment_curve(curve("builtin:sine:points=900"), 0.1).polysegment
    b = segment_curve(curve("builtin:sine:points=900"), 0.1).polysegment
    assert a == b


@pytest.mark.parametrize("tol", [0.0, -1.0, float("nan"), float("inf")])
def test_bad_tolerance(tol):
    with pytest.raises(InputError, match="tolerance_mm"):
        segment_curve(curve("builtin:sine:points=200"), tol)


# ---------------------------------------------------------------- sparse input


def filleted_polygon(points: np.ndarray, tol: float):
    """A G1 chain within ``tol`` of a closed polygon: every vertex rounded by an arc tangent
    to both edges (radius small enough that the arc stays within 0.9 tol of the vertex and
    that the tangent points stay inside the edges); lines in between."""
    v = points[:-1]
    n = len(v)
    edges = np.roll(v, -1, axis=0) - v  # edge i: v[i] -> v[i+1]
    length = np.linalg.norm(edges, axis=1)
    heading = np.arctan2(edges[:, 1], edges[:, 0])
    turn = np.array([math.remainder(heading[i] - heading[i - 1], 2 * math.pi) for i in range(n)])  # at v[i]
    half = np.abs(turn) / 2
    radius = np.minimum(0.45 * np.minimum(length, np.roll(length, 1)) / np.tan(half), 0.9 * tol / (1 / np.cos(half) - 1))
    cut = radius * np.tan(half)  # tangent length at each vertex
    kappas, lengths = [], []
    for i in range(n):
        j = (i + 1) % n
        kappas += [0.0, math.copysign(1 / radius[j], turn[j])]
        lengths += [length[i] - cut[i] - cut[j], radius[j] * abs(turn[j])]
    start = v[0] + cut[0] * edges[0] / length[0]
    segs = chain((float(start[0]), float(start[1])), float(heading[0]), kappas, lengths)
    return Polysegment(segs, closed=True)


SPARSE_ELLIPSE = "builtin:ellipse:points=30"


def test_a_sparse_ellipse_has_a_g1_solution():
    """The reference for the next test: a filleted polygon meets σ = 0.5 mm on the 29-gon."""
    c = curve(SPARSE_ELLIPSE)
    poly = filleted_polygon(c.points, 0.5)
    assert max(b for _, b in tangent_breaks(poly)[:-1]) <= 1e-9
    assert brute_hausdorff(c.points, poly, 0.005) <= 0.5


def test_a_sparse_ellipse_is_fitted():
    """Regression: 'the fitter could not reach 0.5 mm on a run of 30 points' on this 29-gon."""
    c = curve(SPARSE_ELLIPSE)
    seg = segment_curve(c, 0.5)
    assert brute_hausdorff(c.points, seg.polysegment, 0.005) <= 0.5 + 0.005


@pytest.mark.parametrize("spec,tol", [
    ("builtin:ellipse:points=23", 2.0),
    ("builtin:sine:points=20", 2.0),
    pytest.param("builtin:ellipse:points=30", 2.0, marks=pytest.mark.slow),
    pytest.param("builtin:sine:points=50", 0.5, marks=pytest.mark.slow),
])
def test_sparse_input_keeps_the_tolerance(spec, tol):
    """Regression: on builtin:ellipse:points=23 at 2 mm the fitter once reported 1.82 mm for a
    chain 2.77 mm from the input (an arc spanning one input edge was never measured)."""
    c = curve(spec)
    seg = segment_curve(c, tol)
    assert seg.max_deviation_mm <= tol
    assert brute_hausdorff(c.points, seg.polysegment, tol / 200) <= tol * 1.005
    assert_g1_chain(seg.polysegment)
    assert_closed_or_open_ends(seg)


SPARSE_POLYGONS = {
    "square": (np.array([[0, 0], [100, 0], [100, 100], [0, 100], [0, 0]], float), (0, 1, 2, 3)),
    "L": (np.array([[0, 0], [100, 0], [100, 50]], float), (0,)),
    "triangle": (np.array([[0, 0], [100, 0], [50, 80], [0, 0]], float), (0, 1, 2)),
}


@pytest.mark.parametrize("name", sorted(SPARSE_POLYGONS))
def test_polygon_given_by_its_vertices_only(name):
    """Regression: a polygon given by its vertices only was not split at its corners and the
    G1 fitter raised 'could not reach'."""
    pts, corners = SPARSE_POLYGONS[name]
    poly = segment_curve(make_curve(pts, name), 0.1).polysegment
    assert poly.n_lines == poly.n_segments == len(pts) - 1
    assert poly.corners == corners


def test_polygon_with_points_along_its_edges():
    pts = SPARSE_POLYGONS["square"][0]
    dense = np.vstack([a + np.linspace(0, 1, 10, endpoint=False)[:, None] * (b - a) for a, b in zip(pts[:-1], pts[1:])]
                      + [pts[:1]])
    poly = segment_curve(make_curve(dense, "square"), 0.1).polysegment
    assert poly.n_lines == poly.n_segments == 4 and poly.corners == (0, 1, 2, 3)


@pytest.mark.parametrize("tol", [0.05, 0.5])
def test_sparse_kinked_polyline_fits_or_raises_input_error(tol):
    """Regression: an AssertionError once escaped band_fit on this 4-point polyline."""
    pts = np.array([[0, 0], [50, 0], [60, 5], [100, 5]], float)
    try:
        seg = segment_curve(make_curve(pts, "kink"), tol)
    except InputError:
        return
    assert brute_hausdorff(pts, seg.polysegment, tol / 50) <= tol * 1.02
