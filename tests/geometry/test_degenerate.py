"""Degenerate fits (issue 14, item 4): a tolerance at or above the curve's size, no arc below
the numerical floor or sweeping a full turn, programs written from a huge tolerance, and
cusp-rich inputs (their cusps become corners first, so they finish quickly)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from coatsim.geometry import Arc, Line, load_curve, make_curve, read_polysegment_json, segment_curve
from coatsim.core.errors import InputError
from coatsim.geometry.deviation import hausdorff

from geometry_helpers import brute_hausdorff, tangent_breaks

G1 = 1e-9
SMALL = np.array([[0, 0], [10, 0], [20, 5], [30, 0], [40, 2]], float)


def assert_sane(seg, tol):
    """Within tolerance, G1 at every junction that is not a corner, no arc below the
    numerical floor or turning more than a full circle (a whole turn only as a closed chain's one arc)."""
    poly, pts = seg.polysegment, seg.curve.points
    assert seg.max_deviation_mm <= tol and hausdorff(pts, poly).hausdorff <= tol
    for k, turn in tangent_breaks(poly):
        assert k in poly.corners or turn <= G1
    extent = float(np.linalg.norm(np.ptp(pts, axis=0)))
    for s in poly.segments:
        assert s.length > 0
        if isinstance(s, Arc):
            assert s.radius >= 1e-9 * extent and abs(s.sweep) <= 2 * math.pi
            assert abs(s.sweep) < 2 * math.pi or (poly.closed and poly.n_segments == 1)


# ---------------------------------------------------------------- tolerance >= the curve's size


@pytest.mark.parametrize("tol", [50.0, 1e3, 1e6])
def test_an_open_curve_within_a_huge_tolerance_is_one_line(tol):
    seg = segment_curve(make_curve(SMALL, "small"), tol)
    poly = seg.polysegment
    assert poly.segments == (Line((0.0, 0.0), (40.0, 2.0)),)
    assert_sane(seg, tol)


@pytest.mark.parametrize("spec", ["builtin:ellipse", "builtin:naca", "builtin:cam", "builtin:epitrochoid",
                                  "builtin:d-shape", "builtin:polygon", "builtin:rounded-rectangle"])
@pytest.mark.parametrize("tol", [300.0, 1e6])
def test_a_closed_curve_within_a_huge_tolerance_is_one_circle(spec, tol):
    """Regression: arcs of radius 1e-3 mm sweeping 2e4 rad (naca, cam, epitrochoid at 1e6),
    a 158 degree break at a non-corner (epitrochoid at 300)."""
    c = load_curve(spec)
    seg = segment_curve(c, tol)
    poly = seg.polysegment
    assert poly.closed and poly.n_segments == 1 and poly.corners == ()
    (a,) = poly.segments
    assert isinstance(a, Arc) and abs(a.sweep) == 2 * math.pi
    assert poly.start == tuple(c.points[0]) and poly.end == poly.start
    assert_sane(seg, tol)
    assert brute_hausdorff(c.points, poly, 0.5) <= tol


@pytest.mark.parametrize("spec", ["builtin:sine", "builtin:paper-spiral", "builtin:naca", "builtin:cam",
                                  "builtin:epitrochoid", "builtin:clothoid", "builtin:d-shape", "builtin:raster",
                                  "builtin:ellipse", "builtin:rounded-rectangle"])
@pytest.mark.parametrize("tol", [10.0, 30.0, 100.0])
def test_large_tolerances_give_sane_chains(spec, tol):
    seg = segment_curve(load_curve(spec + ":points=1500" if spec != "builtin:raster" else spec), tol)
    assert_sane(seg, tol)


@pytest.mark.parametrize("spec", ["builtin:rounded-rectangle", "builtin:raster"])
def test_a_large_tolerance_keeps_exact_shapes_exact(spec):
    """Corners are only looked for after exact recovery: at 30 mm the rounded rectangle's
    10 mm fillets once became corners."""
    exact = segment_curve(load_curve(spec), 0.1).polysegment
    big = segment_curve(load_curve(spec), 30.0).polysegment
    assert big.segments == exact.segments and big.corners == ()


def test_huge_tolerance_json_is_accepted_by_program(tmp_path, run_cli):
    """Regression: `segment --tol 1e6` wrote a JSON that `program` rejected."""
    for spec in ("builtin:ellipse", "builtin:sine"):
        out = tmp_path / "huge.json"
        code, _, err = run_cli(["segment", spec, "--tol", "1e6", "-o", str(out)])
        assert code == 0, err
        doc = json.loads(out.read_text())
        assert all(abs(s["sweep"]) <= 2 * math.pi for s in doc["segments"] if s["kind"] == "arc")
        read_polysegment_json(out)
        code, _, err = run_cli(["program", str(out), "-o", str(tmp_path / "huge.as")])
        assert code == 0, err
        assert (tmp_path / "huge.as").read_text().startswith(".PROGRAM")
        code, _, err = run_cli(["check-program", str(tmp_path / "huge.as")])
        assert code == 0, err


# ---------------------------------------------------------------- cusps


def back_and_forth(points: int, laps: float = 1.0) -> np.ndarray:
    """0 -> 100 -> 0 mm along x (``laps`` out-and-back trips), ``points`` points."""
    t = np.linspace(0.0, 2 * laps, points)
    return np.column_stack((100.0 * (1.0 - np.abs(np.mod(t, 2.0) - 1.0)), np.zeros(points)))


@pytest.mark.parametrize("points", [1001, 201])
@pytest.mark.parametrize("closed", ["auto", "no"])
def test_the_dense_back_and_forth_line_is_two_lines(points, closed):
    """Regression: 1001 points took over 120 s at 0.1 mm (201 points: 27 s and 203
    segments); the corner was found one vertex before the cusp."""
    seg = segment_curve(make_curve(back_and_forth(points), "back and forth", closed), 0.1)
    poly = seg.polysegment
    assert poly.n_segments == 2 and poly.n_lines == 2
    assert poly.segments[0].end == (100.0, 0.0)
    assert 0 in poly.corners
    assert seg.max_deviation_mm <= 1e-12


@pytest.mark.parametrize("tol", [0.1, 1.0])
def test_a_noisy_back_and_forth_line_finds_both_cusps(tol):
    """Regression: with 0.001 mm noise the seam's cusp (x = 0) was placed on a noise vertex
    next to it, and the fit of the run around the real cusp fell back to 859 fillets."""
    pts = back_and_forth(1001)
    pts[:, 1] = np.random.default_rng(0).normal(0.0, 1e-3, len(pts))
    pts[-1] = pts[0]
    poly = segment_curve(make_curve(pts, "noisy"), tol).polysegment
    assert poly.n_segments == 2 and poly.n_lines == 2 and len(poly.corners) == 2


@pytest.mark.parametrize("laps", [2.5, 5.0])
def test_many_reversals_are_corners(laps):
    poly = segment_curve(make_curve(back_and_forth(2001, laps), "reversals", "no"), 0.1).polysegment
    assert poly.n_lines == poly.n_segments == round(2 * laps) and len(poly.corners) == round(2 * laps) - 1


@pytest.mark.parametrize("cusps,tol", [(4, 0.1), (5, 0.1), (4, 1.0)])
def test_curves_with_cusps_have_them_as_corners(cusps, tol):
    """An astroid (4 cusps) or a hypocycloid with 5: smooth between cusps, sharp at them."""
    t = np.linspace(0.0, 2 * math.pi, 3000)
    if cusps == 4:
        pts = 50.0 * np.column_stack((np.cos(t) ** 3, np.sin(t) ** 3))
    else:
        pts = np.column_stack((40 * np.cos(t) + 10 * np.cos(4 * t), 40 * np.sin(t) - 10 * np.sin(4 * t)))
    seg = segment_curve(make_curve(pts, "cusps"), tol)
    assert len(seg.polysegment.corners) == cusps
    assert_sane(seg, tol)


@pytest.mark.parametrize("n,tol", [(36, 0.2), (12, 2.0), (200, 0.01)])
def test_an_open_polygon_that_ends_where_it_starts_on_a_circle_is_split_below_a_full_turn(n, tol):
    """The process path of a program that traces a circle point by point (an open curve whose
    last point is its first) was recovered as one exact arc of 2π and refused."""
    k = np.arange(n + 1) * 2 * math.pi / n
    pts = np.c_[600 + 40 * np.cos(k), 40 * np.sin(k)]
    seg = segment_curve(make_curve(pts, "circle", "no"), tol)
    arcs = [s for s in seg.polysegment.segments if isinstance(s, Arc)]
    assert arcs and all(abs(a.sweep) < 2 * math.pi - 1e-6 for a in arcs)
    assert seg.max_deviation_mm <= tol and brute_hausdorff(pts, seg.polysegment, tol / 20) <= tol * 1.05


# ---------------------------------------------------------------- tolerances past float64, sparse kinks


@pytest.mark.parametrize("tol", [1e-300, 1e-12, 1e-10])
def test_a_tolerance_finer_than_float64_resolves_is_refused(tol):
    """Regression: 1e-300 mm searched for 28 s, printed overflow warnings and then failed."""
    with pytest.raises(InputError, match=r"tolerance_mm .* below what float64 resolves .* give at least"):
        segment_curve(load_curve("builtin:ellipse"), tol)


def test_the_float64_floor_scales_with_the_coordinates():
    """The same tolerance is fine near the origin and refused 500 km away."""
    pts = np.column_stack((np.linspace(0.0, 100.0, 50), np.zeros(50)))
    assert segment_curve(make_curve(pts, "near"), 1e-6).polysegment.n_segments == 1
    with pytest.raises(InputError, match="tolerance_mm"):
        segment_curve(make_curve(pts + 5e8, "far"), 1e-6)


def test_the_cli_refuses_a_tolerance_below_the_float64_floor_in_one_line(run_cli):
    code, out, err = run_cli(["segment", "builtin:ellipse", "--tol", "1e-300"])
    assert code == 2 and out == ""
    assert err.count("\n") == 1 and err.startswith("coatsim: error: builtin:ellipse: --tol 1e-300 is below")
    assert "Warning" not in err


def test_a_huge_tolerance_on_a_closed_curve_is_one_circle():
    seg = segment_curve(load_curve("builtin:ellipse"), 1e300)
    assert seg.polysegment.n_segments == 1 and seg.polysegment.n_arcs == 1
    assert_sane(seg, 1e300)


def count_refinements(monkeypatch) -> list[int]:
    """A counter of the fitter's refinement attempts (calls of refine_chain)."""
    from coatsim.geometry import fit

    calls = [0]
    original = fit.refine_chain

    def counted(*args, **kwargs):
        calls[0] += 1
        return original(*args, **kwargs)

    monkeypatch.setattr(fit, "refine_chain", counted)
    return calls


def test_a_sparse_steep_sine_fits_its_flanks_without_fillets(monkeypatch):
    """Regression: a sine of wavelength 3 mm and amplitude 20 mm sampled every 1.75 mm (the
    peaks are kinks) took 69 s: the curvature estimate smoothed the kinks next to the peaks
    away, so each flank exhausted every try and fell back to fillets (505 segments, some
    1e-9 mm long). The kinks now admit the curvature they force."""
    calls = count_refinements(monkeypatch)
    seg = segment_curve(load_curve("builtin:sine:wavelength=3,length=30,points=450"), 0.1)
    assert_sane(seg, 0.1)
    runs = len(seg.polysegment.corners) + 1
    assert seg.limits_kept
    assert seg.polysegment.n_segments <= 2 * runs
    assert min(s.length for s in seg.polysegment.segments) >= 0.25
    assert calls[0] <= 4 * runs


def test_a_flat_ellipse_of_a_kilometre_falls_back_to_few_fillets():
    """Regression: a = 1e9 mm, b = 20 mm: the ends are kinks at its 1.3e6 mm edges; the fit
    fell back to a fillet at each of the 3000 vertices, collinear ones too (3001 segments).
    The fillets now round the vertices of the input simplified within σ/2."""
    seg = segment_curve(load_curve("builtin:ellipse:a=1e9,b=20"), 0.1)
    assert_sane(seg, 0.1)
    assert seg.polysegment.n_segments <= 200


@pytest.mark.parametrize("aspect", [1.002, 1.01, 1.1])
def test_an_ellipse_is_not_taken_for_a_circle(aspect):
    """Arcs are one circle only where their centres and radii agree within σ/10 and the one arc
    keeps the points within σ: a slightly flattened circle (semi-axes 50 and 50·aspect, its
    radius of curvature 50/aspect² .. 50·aspect) at σ 0.05 keeps the arcs it needs."""
    t = np.linspace(0.0, 2 * math.pi, 2001)
    pts = np.column_stack((50 * aspect * np.cos(t), 50 * np.sin(t)))
    pts[-1] = pts[0]
    seg = segment_curve(make_curve(pts, "ellipse", "yes"), 0.05)
    assert_sane(seg, 0.05)
    assert seg.polysegment.n_segments > 1 and brute_hausdorff(pts, seg.polysegment, 0.005) <= 0.0505


@pytest.mark.parametrize("tol", [0.05, 0.5])
def test_a_circle_taken_as_one_arc_is_within_sigma_of_its_points(tol):
    """The one arc of a sampled, jittered circle is certified again: every point within σ."""
    rng = np.random.default_rng(11)
    t = np.sort(rng.uniform(0.0, 2 * math.pi, 1500))
    pts = np.column_stack((20 + 35 * np.cos(t), -7 + 35 * np.sin(t))) + rng.normal(scale=tol / 20, size=(1500, 2))
    pts = np.vstack((pts, pts[:1]))
    seg = segment_curve(make_curve(pts, "circle", "yes"), tol)
    (arc,) = seg.polysegment.segments
    assert isinstance(arc, Arc) and abs(arc.sweep) == 2 * math.pi and arc.start == arc.end
    assert arc.radius == pytest.approx(35, abs=tol) and math.dist(arc.center, (20, -7)) <= tol
    assert brute_hausdorff(pts, seg.polysegment, tol / 20) <= tol * 1.02
