"""Drawings as plotter, CAM and older CAD programs write them: no header, rounding left in
bulges and heights, R12 spline-fit polylines, degenerate entities beside good ones, flowed text
and an SVG sized by one side."""

from __future__ import annotations

import math

import numpy as np
import pytest

from coatsim.core.errors import InputError
from coatsim.geometry.cad import read_drawing, segment_drawing

from cad_helpers import points_along, write_dxf, write_svg

TOL = 0.1


def polysegments(path):
    return [c.polysegment for c in segment_drawing(path, TOL).contours]


def extent(polys) -> np.ndarray:
    ends = np.array([p for poly in polys for s in poly.segments for p in (s.start, s.end)])
    return np.ptp(ends, axis=0)


def test_a_dxf_without_a_header_is_read_in_mm_not_in_ezdxf_s_template_metres(tmp_path):
    """ezdxf fills a missing HEADER from its template ($INSUNITS 6, metres): a 100 mm line came
    back 100 m long."""
    path = tmp_path / "plotter.dxf"
    path.write_text("0\nSECTION\n2\nENTITIES\n0\nLINE\n8\n0\n10\n0\n20\n0\n11\n100\n21\n0\n0\nENDSEC\n0\nEOF\n")
    drawing = read_drawing(path)
    assert drawing.units == "mm" and any("no $INSUNITS" in n for n in drawing.notes)
    assert polysegments(path)[0].segments[0].length == pytest.approx(100.0, abs=1e-9)


@pytest.mark.parametrize("bulge", [1e-12, 1e-9, 1e-7])
def test_a_rounding_bulge_on_a_straight_edge_is_a_line(tmp_path, bulge):
    """A bulge of 1e-12 is an arc 5e13 mm from the origin: the drawing was refused whole."""
    path = write_dxf(tmp_path, lambda msp, doc: msp.add_lwpolyline(
        [(0, 0, 0, 0, bulge), (100, 0, 0, 0, 0), (100, 60, 0, 0, 0), (0, 60, 0, 0, 0)], format="xyseb", close=True))
    (poly,) = polysegments(path)
    assert poly.closed and poly.n_arcs == 0 and poly.n_lines == 4
    assert extent([poly]) == pytest.approx([100.0, 60.0], abs=1e-9)


def test_a_real_bulge_stays_an_arc(tmp_path):
    path = write_dxf(tmp_path, lambda msp, doc: msp.add_lwpolyline(
        [(0, 0, 0, 0, 1e-3), (100, 0, 0, 0, 0), (100, 60, 0, 0, 0), (0, 60, 0, 0, 0)], format="xyseb", close=True))
    pieces = read_drawing(path).pieces
    assert any(getattr(getattr(p, "segment", None), "radius", 0) > 0 for p in pieces)


@pytest.mark.parametrize("params", [(0.0, 0.0), (1.0, 1.0)])
def test_an_ellipse_with_equal_start_and_end_parameters_is_whole(tmp_path, params):
    """Equal parameters crashed the reader (ezdxf flattens such an ellipse to nothing)."""
    def draw(msp, doc):
        msp.add_ellipse((0, 0), major_axis=(50, 0), ratio=0.5, start_param=params[0], end_param=params[1])

    (poly,) = polysegments(write_dxf(tmp_path, draw))
    a, b = 50.0, 25.0
    ramanujan = math.pi * (3 * (a + b) - math.sqrt((3 * a + b) * (a + 3 * b)))
    assert poly.closed and poly.length == pytest.approx(ramanujan, rel=1e-3)


def test_an_r12_spline_fit_polyline_is_its_b_spline_without_the_frame(tmp_path):
    """PEDIT Spline keeps the frame's control vertices (flag 16) beside the fit vertices (flag 8):
    ezdxf drew the frame as a second, closed contour."""
    def draw(msp, doc):
        poly = msp.add_polyline2d([], dxfattribs={"flags": 4, "smooth_type": 6})
        frame = [(0, 0), (20, 40), (60, 40), (80, 0)]
        fit = [(0, 0), (18.125, 22.5), (40, 30), (61.875, 22.5), (80, 0)]
        poly.append_vertices(frame, dxfattribs={"flags": 16})
        poly.append_vertices(fit, dxfattribs={"flags": 8})

    (poly,) = polysegments(write_dxf(tmp_path, draw, version="R12"))
    assert not poly.closed and poly.n_segments <= 4
    samples = points_along(poly)
    for fit in [(18.125, 22.5), (40, 30), (61.875, 22.5)]:  # the frame's cubic Bézier at t = 1/4, 1/2, 3/4
        assert np.linalg.norm(samples - fit, axis=1).min() < TOL


def test_heights_that_differ_by_rounding_are_one_plane(tmp_path):
    """z of 2.3e-6 on one corner made the lines 'tilted' and the drawing was refused."""
    def draw(msp, doc):
        z = [0.0, 2.3e-6, -1.1e-6, 4e-7]
        corners = [(0, 0), (100, 0), (100, 50), (0, 50)]
        for k in range(4):
            a, b = corners[k], corners[(k + 1) % 4]
            msp.add_line((*a, z[k]), (*b, z[(k + 1) % 4]))

    (poly,) = polysegments(write_dxf(tmp_path, draw))
    assert poly.closed and poly.n_lines == 4


def test_a_degenerate_spline_beside_good_geometry_is_left_out_with_a_note(tmp_path):
    def draw(msp, doc):
        msp.add_lwpolyline([(0, 0), (100, 0), (100, 60), (0, 60)], close=True)
        msp.add_spline(fit_points=[(5, 5), (5, 5), (5, 5)])

    path = write_dxf(tmp_path, draw)
    assert any("left out 1 entities" in n and "SPLINE" in n for n in read_drawing(path).notes)
    assert len(polysegments(path)) == 1


def test_a_drawing_of_only_a_degenerate_spline_is_refused_naming_it(tmp_path):
    path = write_dxf(tmp_path, lambda msp, doc: msp.add_spline(fit_points=[(5, 5), (5, 5), (5, 5)]))
    with pytest.raises(InputError, match="no geometry to spray: SPLINE"):
        read_drawing(path)


@pytest.mark.parametrize("attrs, side_mm", [('width="200mm" viewBox="0 0 100 50"', 40.0),
                                            ('height="1in" viewBox="0 0 100 50"', 20 * 25.4 / 50)])
def test_an_svg_sized_by_one_side_takes_the_other_from_its_viewbox(tmp_path, attrs, side_mm):
    """width="200mm" over a 100 x 50 viewBox: 2 mm a unit (a 20-unit square came back 5.3 mm)."""
    path = write_svg(tmp_path, '<rect x="10" y="10" width="20" height="20"/>', attrs=attrs)
    assert extent(polysegments(path)) == pytest.approx([side_mm, side_mm], rel=1e-9)


def test_flowed_text_and_its_frame_are_not_contours(tmp_path):
    body = ('<rect x="10" y="10" width="30" height="30"/><flowRoot><flowRegion><rect width="40" height="20" '
            'x="50" y="10"/></flowRegion><flowPara>Part 12</flowPara></flowRoot>')
    path = write_svg(tmp_path, body)
    assert len(polysegments(path)) == 1
    assert any("flowRoot" in n for n in read_drawing(path).notes)


def _circle_through(a, b, c) -> tuple[tuple[float, float], float]:
    (ax, ay), (bx, by), (cx, cy) = a, b, c
    d = 2 * (ax * (by - cy) + bx * (cy - ay) + cx * (ay - by))
    ux = ((ax**2 + ay**2) * (by - cy) + (bx**2 + by**2) * (cy - ay) + (cx**2 + cy**2) * (ay - by)) / d
    uy = ((ax**2 + ay**2) * (cx - bx) + (bx**2 + by**2) * (ax - cx) + (cx**2 + cy**2) * (bx - ax)) / d
    return (ux, uy), math.hypot(ax - ux, ay - uy)


@pytest.mark.parametrize("decimals", [2, 3])
def test_a_cam_arc_fit_rounded_to_decimals_is_one_tangent_contour(tmp_path, decimals):
    """A CAM program's outline of an 80 x 40 ellipse in 72 ARCs through three of its points each,
    centres and radii rounded: ends 0.015 mm apart, tangents 0.01-0.3 deg apart. One near-miss
    join moving an arc's centre was taken for moving the drawing and undid all 70 (70 open
    contours); kept as drawn, every join was a corner (72 stops)."""
    def draw(msp, doc):
        point = lambda t: (100 + 40 * math.cos(t), 50 + 20 * math.sin(t))  # noqa: E731
        for k in range(72):
            t0, t1 = 2 * math.pi * k / 72, 2 * math.pi * (k + 1) / 72
            (cx, cy), r = _circle_through(point(t0), point((t0 + t1) / 2), point(t1))
            a0 = math.degrees(math.atan2(point(t0)[1] - cy, point(t0)[0] - cx)) % 360
            a1 = math.degrees(math.atan2(point(t1)[1] - cy, point(t1)[0] - cx)) % 360
            msp.add_arc((round(cx, decimals), round(cy, decimals)), round(r, decimals), round(a0, decimals),
                        round(a1, decimals))

    part = segment_drawing(write_dxf(tmp_path, draw), TOL)
    (contour,) = part.contours
    poly = contour.polysegment
    assert poly.closed and not poly.corners and poly.n_segments <= 14
    assert contour.max_deviation_mm <= TOL
    assert np.ptp(points_along(poly), axis=0) == pytest.approx([80.0, 40.0], abs=2 * TOL)  # drawn arcs bulge too


def test_a_path_closed_short_of_its_start_by_rounding_has_no_micro_segment(tmp_path):
    """The last edge of a rounded rectangle ends 0.004 mm short of its start; Z draws that gap as
    a line, which came back as a 0.004 mm segment between two corners."""
    d = "M15,10h50a5,5 0 0 1 5,5v20a5,5 0 0 1-5,5h-50a5,5 0 0 1-5-5v-19.996a5,5 0 0 1 5-5z"
    path = write_svg(tmp_path, f'<path d="{d}"/>')
    (contour,) = segment_drawing(path, TOL).contours
    poly = contour.polysegment
    assert poly.closed and not poly.corners and min(s.length for s in poly.segments) > 0.5
    assert contour.max_deviation_mm <= TOL
    assert any("dropped 1 pieces" in n for n in segment_drawing(path, TOL).notes)


def test_a_step_below_the_tolerance_between_collinear_edges_goes_within_it(tmp_path):
    """A 0.03 mm step between two collinear edges at σ 0.1 is bridged (its edges meet tangentially
    across it); the contour keeps its four corners and stays within σ of the drawing."""
    d = "M0,0 h50 v0.03 h50 v40 h-100 z"
    (contour,) = segment_drawing(write_svg(tmp_path, f'<path d="{d}"/>'), TOL).contours
    assert contour.polysegment.n_segments == 4 and len(contour.polysegment.corners) == 4
    assert contour.max_deviation_mm <= TOL


def test_an_outline_drawn_twice_once_rounded_is_sprayed_once(tmp_path):
    """The same rectangle as exact LINEs and again rounded to 0.01 mm: two contours, sprayed twice,
    without a word; two lines 0.004 mm apart were chained into an out-and-back 'closed' contour."""
    def draw(msp, doc):
        corners = [(10, 10), (90, 10), (90, 60), (10, 60)]
        for shift in ((0.0, 0.0), (0.0031, 0.0042)):
            for a, b in zip(corners, corners[1:] + corners[:1]):
                msp.add_line((a[0] + shift[0], a[1] + shift[1]), (b[0] + shift[0], b[1] + shift[1]))
        msp.add_line((0, 100), (100, 100))
        msp.add_line((0, 100.004), (100, 100.004))

    part = segment_drawing(write_dxf(tmp_path, draw), TOL)
    assert sorted((c.polysegment.closed, c.polysegment.n_segments) for c in part.contours) == [(False, 1), (True, 4)]
    assert any("dropped 5 duplicate pieces" in n for n in part.notes)


def test_a_spline_in_a_contour_with_rounded_joins_is_read(tmp_path):
    """A slot whose arc's angles are rounded (tangent to 0.004 deg) closed by a spline: a free-form
    piece in a contour with rounded native joins (an internal error once)."""
    def draw(msp, doc):
        msp.add_line((0.0, -12.5), (80.0, -12.5))
        msp.add_arc((80.0, 0.0), 12.5, round(-90.0 + 0.004, 2) + 0.003, round(90.0 - 0.003, 2))
        msp.add_line((80.0, 12.5), (0.0, 12.5))
        msp.add_spline([(0.0, 12.5), (-16.0, 12.5), (-16.0, -12.5), (0.0, -12.5)])

    (contour,) = segment_drawing(write_dxf(tmp_path, draw), TOL).contours
    assert contour.polysegment.closed and contour.max_deviation_mm <= TOL


@pytest.mark.parametrize("head, attrs, told", [
    ("", 'width="200" height="100" viewBox="0 0 200 100"', "96 px per inch"),
    ("<!-- Generator: Adobe Illustrator 24.0.1, SVG Export Plug-In -->\n", 'width="200px" height="100px" viewBox="0 0 200 100"',
     "72 per inch"),
    ("", 'inkscape:version="0.91 r13725" width="200" height="100"', "90 per inch"),
    ("", 'width="200mm" height="100mm" viewBox="0 0 200 100"', None),
    ("", 'width="2in" height="1in" viewBox="0 0 200 100"', None)])
def test_a_drawing_sized_in_px_says_at_what_scale_it_is_read(tmp_path, head, attrs, told):
    """Illustrator's px are 72 to the inch, old Inkscape's 90, CSS's 96: a drawing in px was read at
    96 without a word, 75 % or 94 % of the size meant."""
    path = write_svg(tmp_path, '<rect x="10" y="10" width="20" height="20"/>', attrs=attrs)
    if head:
        path.write_text(head + path.read_text())
    notes = [n for n in read_drawing(path).notes if "px" in n]
    assert (told is None and not notes) or (told is not None and len(notes) == 1 and told in notes[0])


def test_a_clipped_shape_is_read_whole_and_said_so(tmp_path):
    body = ('<clipPath id="c"><rect x="0" y="0" width="50" height="100"/></clipPath>'
            '<circle cx="50" cy="50" r="30" clip-path="url(#c)"/>')
    drawing = read_drawing(write_svg(tmp_path, body))
    assert any("1 clip paths not applied" in n for n in drawing.notes)


def test_a_switch_draws_its_first_child_that_needs_no_extension(tmp_path):
    """Both children of a <switch> were read, one circle over another; Illustrator puts its own
    data first, under requiredExtensions."""
    body = ('<switch><foreignObject requiredExtensions="http://ns.adobe.com/AdobeIllustrator/10.0/" width="1" '
            'height="1"/><circle cx="20" cy="70" r="5" systemLanguage="en"/><circle cx="20" cy="70" r="8"/></switch>')
    (poly,) = polysegments(write_svg(tmp_path, body))
    assert poly.closed and poly.length == pytest.approx(2 * math.pi * 5, rel=1e-9)
