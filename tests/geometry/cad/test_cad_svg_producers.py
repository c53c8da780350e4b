"""SVG as drawing programs write it: skewed arcs, Illustrator symbols placed by <use>,
degenerate arcs, circles whose Close is round-off, and what must not be drawn."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from coatsim.geometry import Arc, Line
from coatsim.geometry.cad import read_drawing, segment_drawing

from cad_helpers import EXACT, max_distance, write_svg

TOL = 0.1
MM = 'width="200mm" height="200mm" viewBox="0 0 200 200"'  # one user unit = 1 mm


def _sheared_circle(cx: float, cy: float, r: float, skew_deg: float, n: int = 4000) -> np.ndarray:
    """A circle under skewX, in mm with y up, computed here directly."""
    phi = np.linspace(0.0, 2 * math.pi, n)
    x, y = cx + r * np.cos(phi), cy + r * np.sin(phi)
    return np.column_stack((x + math.tan(math.radians(skew_deg)) * y, -y))


@settings(max_examples=6, deadline=None)
@given(st.floats(5.0, 40.0), st.sampled_from([-30.0, 12.0, 20.0, 35.0]))
def test_a_skewed_circle_is_the_ellipse_the_skew_makes(tmp_path_factory, radius, skew):
    """svgelements' own transformed arcs are wrong under a skew (by millimetres): the reader
    maps the arc's points itself and fits the ellipse within σ."""
    folder = tmp_path_factory.mktemp("skew")
    d = f"M {100 + radius} 100 A {radius} {radius} 0 1 1 {100 - radius} 100 A {radius} {radius} 0 1 1 {100 + radius} 100 Z"
    path = write_svg(folder, f'<g transform="skewX({skew})"><path d="{d}"/></g>', attrs=MM)
    (contour,) = segment_drawing(path, TOL).contours
    assert contour.polysegment.closed
    assert max_distance(_sheared_circle(100, 100, radius, skew), contour.polysegment) <= TOL + 0.01


def test_a_circle_through_a_similarity_stays_one_native_arc(tmp_path):
    path = write_svg(tmp_path, '<g transform="rotate(30) scale(2) translate(5 0)"><circle cx="20" cy="20" r="5"/></g>', attrs=MM)
    (contour,) = segment_drawing(path, TOL).contours
    (arc,) = contour.polysegment.segments
    c = np.array([25.0, 20.0]) * 2
    rot = np.array([[math.cos(math.pi / 6), -math.sin(math.pi / 6)], [math.sin(math.pi / 6), math.cos(math.pi / 6)]])
    cx, cy = rot @ c
    assert isinstance(arc, Arc) and abs(arc.radius - 10) < EXACT and math.dist(arc.center, (cx, -cy)) < EXACT
    assert contour.max_deviation_mm == 0.0


def test_a_non_uniform_scale_makes_an_ellipse_not_an_arc(tmp_path):
    path = write_svg(tmp_path, '<g transform="scale(2 1)"><circle cx="50" cy="50" r="10"/></g>', attrs=MM)
    (contour,) = segment_drawing(path, TOL).contours
    phi = np.linspace(0, 2 * math.pi, 4000)
    truth = np.column_stack((100 + 20 * np.cos(phi), -(50 + 10 * np.sin(phi))))
    assert contour.polysegment.n_segments > 1
    assert max_distance(truth, contour.polysegment) <= TOL + 0.01


def test_symbol_is_drawn_only_where_used_with_its_viewbox(tmp_path):
    """Illustrator's <symbol>/<use>: the symbol itself is not drawn; its viewBox maps into
    the use's width and height at its x, y."""
    body = ('<symbol id="hole" viewBox="-10 -10 20 20"><circle cx="0" cy="0" r="5"/></symbol>'
            '<use xlink:href="#hole" x="40" y="40" width="20" height="20"/>'
            '<use href="#hole" x="80" y="40" width="40" height="40" transform="translate(10,0)"/>')
    path = write_svg(tmp_path, body, attrs=f'xmlns:xlink="http://www.w3.org/1999/xlink" {MM}')
    arcs = sorted((c.polysegment.segments[0] for c in segment_drawing(path, TOL).contours), key=lambda a: a.center[0])
    assert len(arcs) == 2
    assert math.dist(arcs[0].center, (50, -50)) < EXACT and abs(arcs[0].radius - 5) < EXACT
    assert math.dist(arcs[1].center, (110, -60)) < EXACT and abs(arcs[1].radius - 10) < EXACT


def test_symbol_without_viewbox_and_unused_symbols(tmp_path):
    body = ('<defs><symbol id="s"><rect x="0" y="0" width="10" height="5"/></symbol></defs>'
            '<symbol id="unused"><circle r="3"/></symbol><use href="#s" x="20" y="30"/>')
    path = write_svg(tmp_path, body, attrs=MM)
    (contour,) = segment_drawing(path, TOL).contours
    xs = sorted({round(s.start[0], 9) for s in contour.polysegment.segments})
    ys = sorted({round(s.start[1], 9) for s in contour.polysegment.segments})
    assert xs == [20, 30] and ys == [-35, -30]


def test_degenerate_arcs_are_lines_and_zero_close_is_not_noted(tmp_path):
    """An arc with a zero radius is the straight line SVG draws; a circle's Close (round-off
    long) is no piece and no note."""
    body = '<path d="M10 10 A 0 0 0 0 1 20 20 L 30 10"/><circle cx="100" cy="100" r="7"/><rect x="150" y="150" width="10" height="10"/>'
    path = write_svg(tmp_path, body, attrs=MM)
    part = segment_drawing(path, TOL)
    assert not any("zero-length" in n for n in part.notes)
    first = part.contours[0].polysegment
    assert [type(s) for s in first.segments] == [Line, Line] and first.segments[0].start == (10.0, -10.0)
    assert part.contours[1].n_pieces == 4  # the circle's four quarter arcs, no closing line
    assert part.contours[0].max_deviation_mm == 0.0


def test_hidden_defs_clip_marker_pattern_mask_are_not_drawn(tmp_path):
    body = ('<style>.hide{display:none} #gone {visibility:hidden}</style>'
            '<defs><path id="p1" d="M0 0 L100 50"/><clipPath id="c"><rect x="0" y="0" width="50" height="50"/></clipPath>'
            '<marker id="m"><circle cx="5" cy="5" r="4"/></marker><pattern id="pat" width="10" height="10"><rect width="5" height="5"/></pattern>'
            '<mask id="k"><rect width="100" height="50"/></mask></defs>'
            '<rect x="10" y="10" width="30" height="30" clip-path="url(#c)"/><circle cx="70" cy="25" r="10" class="hide"/>'
            '<circle cx="85" cy="25" r="5" id="gone"/><g display="none"><rect x="1" y="1" width="2" height="2"/></g>'
            '<text x="10" y="48">Part 42</text>')
    path = write_svg(tmp_path, body, attrs=MM)
    drawing = read_drawing(path)
    assert {p.source.split()[0] for p in drawing.pieces} == {"<rect>"}
    assert any("text" in n for n in drawing.notes) and any("hidden" in n for n in drawing.notes)


@pytest.mark.parametrize("d", ["M60-1.5.5.5l1e1 0L70.5 1e1z", "M 60,-1.5 L 0.5,0.5 l 10,0 L 70.5,10 z"])
def test_packed_numbers_read_as_spelled_out(tmp_path, d):
    path = write_svg(tmp_path, f'<path d="{d}"/>', attrs=MM)
    (contour,) = segment_drawing(path, TOL).contours
    assert [s.start for s in contour.polysegment.segments] == [(60.0, 1.5), (0.5, -0.5), (10.5, -0.5), (70.5, -10.0)]
