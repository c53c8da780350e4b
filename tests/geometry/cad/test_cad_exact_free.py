"""Free-form pieces that exactly are lines or circular arcs (Béziers with their handles on
the chord, NURBS circles with knots and weights) come back as native lines and arcs."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings, strategies as st

from coatsim.geometry import Arc, Line
from coatsim.geometry.cad import read_drawing, segment_drawing
from coatsim.geometry.cad.pieces import FreePiece, NativePiece

from cad_helpers import EXACT, write_dxf, write_svg

TOL = 0.1
MM = 'width="200mm" height="200mm" viewBox="0 0 200 200"'


@settings(max_examples=15, deadline=None)
@given(st.floats(0.0, 1.0), st.floats(0.0, 1.0), st.floats(-80, 80), st.floats(-80, 80))
def test_bezier_with_handles_on_the_chord_is_a_line(tmp_path_factory, u, v, dx, dy):
    if math.hypot(dx, dy) < 1.0:
        return
    a, b = np.array([100.0, 100.0]), np.array([100.0 + dx, 100.0 + dy])
    h1, h2 = a + min(u, v) * (b - a), a + max(u, v) * (b - a)
    d = "M {} {} C {} {} {} {} {} {}".format(*(repr(float(c)) for c in (*a, *h1, *h2, *b)))
    path = write_svg(tmp_path_factory.mktemp("line"), f'<path d="{d}"/>', attrs=MM)
    (piece,) = read_drawing(path, flatten_mm=0.005).pieces
    assert isinstance(piece, NativePiece) and isinstance(piece.segment, Line)
    assert math.dist(piece.start, (a[0], -a[1])) < EXACT and math.dist(piece.end, (b[0], -b[1])) < EXACT


def test_bezier_overshooting_its_end_is_not_a_line(tmp_path):
    """Handles beyond the end: the curve runs past it and comes back, which a line does not."""
    path = write_svg(tmp_path, '<path d="M 10 10 C 40 10 60 10 30 10"/>', attrs=MM)
    (piece,) = read_drawing(path, flatten_mm=0.005).pieces
    assert isinstance(piece, FreePiece)


def test_bezier_near_a_circle_stays_free_form(tmp_path):
    k = 0.5522847498 * 20  # the usual cubic approximation of a quarter circle: not exact
    path = write_svg(tmp_path, f'<path d="M 120 100 C 120 {100 + k} {100 + k} 120 100 120"/>', attrs=MM)
    (piece,) = read_drawing(path, flatten_mm=0.005).pieces
    assert isinstance(piece, FreePiece)


def test_nurbs_circle_with_knots_and_weights_is_one_exact_arc(tmp_path):
    def draw(msp, doc):
        r, cx, cy, w = 20.0, 150.0, 10.0, math.sqrt(0.5)
        cps = [(cx + r, cy), (cx + r, cy + r), (cx, cy + r), (cx - r, cy + r), (cx - r, cy), (cx - r, cy - r),
               (cx, cy - r), (cx + r, cy - r), (cx + r, cy)]
        msp.add_rational_spline(cps, [1, w, 1, w, 1, w, 1, w, 1], degree=2,
                                knots=[0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1])

    (contour,) = segment_drawing(write_dxf(tmp_path, draw), TOL).contours
    (arc,) = contour.polysegment.segments
    assert isinstance(arc, Arc) and math.dist(arc.center, (150, 10)) < EXACT and abs(arc.radius - 20) < EXACT
    assert abs(abs(arc.sweep) - 2 * math.pi) < 1e-9 and contour.polysegment.closed
    assert contour.max_deviation_mm < EXACT


def test_rational_quarter_arc_spline_joins_lines_exactly(tmp_path):
    """A slot whose rounded ends are rational splines (as some exporters write arcs)."""
    def draw(msp, doc):
        w = math.sqrt(0.5)
        msp.add_line((0, 0), (40, 0))
        msp.add_rational_spline([(40, 0), (50, 0), (50, 10)], [1, w, 1], degree=2)
        msp.add_rational_spline([(50, 10), (50, 20), (40, 20)], [1, w, 1], degree=2)
        msp.add_line((40, 20), (0, 20))
        msp.add_line((0, 20), (0, 0))

    (contour,) = segment_drawing(write_dxf(tmp_path, draw), TOL).contours
    kinds = [type(s) for s in contour.polysegment.segments]
    assert kinds.count(Arc) == 1 and kinds.count(Line) == 3  # the two quarter arcs merge into one half circle
    assert contour.max_deviation_mm < EXACT


def test_closed_fit_point_spline_is_smooth_across_its_seam(tmp_path):
    """A closed SPLINE given by fit points only (AutoCAD, Fusion) is periodic: no corner where
    it closes, and it passes through every fit point."""
    fit = [(0, 0), (30, -10), (60, 0), (60, 30), (30, 40), (0, 30)]

    def draw(msp, doc):
        msp.add_spline(fit_points=fit).closed = True

    (contour,) = segment_drawing(write_dxf(tmp_path, draw), TOL).contours
    poly = contour.polysegment
    assert poly.closed and poly.corners == ()
    from cad_helpers import points_along

    dense = points_along(poly, 0.01)
    for p in fit:
        assert np.linalg.norm(dense - p, axis=1).min() <= TOL
