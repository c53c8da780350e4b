"""SVG drawings written by hand: every path command, the basic shapes, nested transforms,
viewBox and units, Inkscape layers, Béziers within σ, and broken files."""

from __future__ import annotations

import math

import numpy as np
import pytest

from coatsim.core.errors import InputError
from coatsim.geometry import Arc, Line
from coatsim.geometry.cad import read_drawing, segment_drawing
from coatsim.geometry.cad.svg_reader import MM_PER_USER_UNIT, path_data_error

from cad_helpers import EXACT, g1_breaks, max_distance, same_segment, write_svg

TOL = 0.1
MM = 'width="200mm" height="100mm" viewBox="0 0 200 100"'  # one user unit = 1 mm


def segments_of(path, **kwargs):
    return [c.polysegment for c in segment_drawing(path, TOL, **kwargs).contours]


def test_absolute_and_relative_commands_give_the_same_contour(tmp_path):
    absolute = ("M 10 10 L 30 10 H 50 V 30 A 10 10 0 0 1 50 50 C 50 60 40 70 30 70 S 10 60 10 50 "
                "Q 0 40 10 30 T 10 10 Z")
    relative = ("m 10 10 l 20 0 h 20 v 20 a 10 10 0 0 1 0 20 c 0 10 -10 20 -20 20 s -20 -10 -20 -20 "
                "q -10 -10 0 -20 t 0 -20 z")
    a = segments_of(write_svg(tmp_path, f'<path id="abs" d="{absolute}"/>', "a.svg", MM))
    b = segments_of(write_svg(tmp_path, f'<path id="rel" d="{relative}"/>', "b.svg", MM))
    assert len(a) == len(b) == 1
    assert a[0].closed and b[0].closed
    assert all(same_segment(x, y, 1e-9) for x, y in zip(a[0].segments, b[0].segments))
    drawing = read_drawing(tmp_path / "a.svg")
    kinds = [type(p).__name__ for p in drawing.pieces if p.length > 0]
    assert kinds.count("NativePiece") == 4 and kinds.count("FreePiece") == 4  # L H V A; C S Q T (Z closes onto the start)


def test_arc_command_is_a_native_arc_with_y_up(tmp_path):
    path = write_svg(tmp_path, '<path d="M 10 50 A 20 20 0 0 1 50 50"/>', attrs=MM)
    arc = segments_of(path)[0].segments[0]
    assert isinstance(arc, Arc)
    assert math.dist(arc.center, (30, -50)) < EXACT and abs(arc.radius - 20) < EXACT
    assert abs(arc.sweep + math.pi) < 1e-12  # clockwise in y-up coordinates, over the top
    top = arc.points(np.array([arc.length / 2]))[0]
    assert math.dist(top, (30, -30)) < 1e-9


def test_bezier_between_lines_is_g1_to_them(tmp_path):
    path = write_svg(tmp_path, '<path d="M 0 0 L 10 0 C 20 0 30 10 30 20 L 30 40 Q 30 50 40 50"/>', attrs=MM)
    (poly,) = segments_of(path)
    assert poly.corners == () and max(g1_breaks(poly)) < 1e-9
    assert same_segment(poly.segments[0], Line((0.0, 0.0), (10.0, 0.0)))


def test_rounded_rect_is_four_lines_and_four_arcs(tmp_path):
    poly = segments_of(write_svg(tmp_path, '<rect x="10" y="10" width="80" height="40" rx="5"/>', attrs=MM))[0]
    assert poly.closed and poly.n_lines == 4 and poly.n_arcs == 4 and poly.corners == ()
    assert all(isinstance(s, Arc) and abs(s.radius - 5) < EXACT for s in poly.segments if isinstance(s, Arc))
    xs = [p[0] for s in poly.segments for p in (s.start, s.end)]
    ys = [p[1] for s in poly.segments for p in (s.start, s.end)]
    assert min(xs) == pytest.approx(10) and max(xs) == pytest.approx(90)
    assert min(ys) == pytest.approx(-50) and max(ys) == pytest.approx(-10)
    assert max(g1_breaks(poly)) < 1e-9


def test_basic_shapes(tmp_path):
    body = """
    <circle cx="20" cy="20" r="10"/>
    <ellipse cx="60" cy="20" rx="15" ry="5"/>
    <line x1="100" y1="10" x2="120" y2="10"/>
    <polyline points="100,30 120,30 120,40"/>
    <polygon points="140,10 160,10 150,25"/>
    <rect x="170" y="10" width="20" height="10"/>"""
    polys = segments_of(write_svg(tmp_path, body, attrs=MM))
    circle, ellipse, line, polyline, polygon, rect = polys
    assert circle.closed and circle.n_arcs >= 1 and all(abs(s.radius - 10) < EXACT for s in circle.segments)
    assert ellipse.closed and ellipse.corners == ()
    assert line.n_segments == 1 and same_segment(line.segments[0], Line((100.0, -10.0), (120.0, -10.0)))
    assert not polyline.closed and polyline.n_segments == 2 and len(polyline.corners) == 1
    assert polygon.closed and polygon.n_segments == 3 and len(polygon.corners) == 3
    assert rect.closed and rect.n_segments == 4 and len(rect.corners) == 4


def test_use_of_symbols_and_paths(tmp_path):
    body = """<defs><symbol id="hole"><circle cx="5" cy="5" r="4"/></symbol>
      <path id="tick" d="M 0 0 L 10 0"/></defs>
    <use xlink:href="#hole" x="10" y="10"/>
    <use href="#hole" transform="translate(50,10) scale(2)"/>
    <use xlink:href="#tick" x="100" y="50"/>"""
    attrs = MM + ' xmlns:xlink="http://www.w3.org/1999/xlink"'
    polys = segments_of(write_svg(tmp_path, body, attrs=attrs))
    assert len(polys) == 3
    small, large, tick = polys
    assert math.dist(small.segments[0].center, (15.0, -15.0)) < 1e-9 and abs(small.segments[0].radius - 4) < 1e-9
    assert math.dist(large.segments[0].center, (60.0, -20.0)) < 1e-9 and abs(large.segments[0].radius - 8) < 1e-9
    assert same_segment(tick.segments[0], Line((100.0, -50.0), (110.0, -50.0)), 1e-9)


def test_nested_transforms_and_viewbox_in_mm(tmp_path):
    body = """<g transform="translate(20,10)"><g transform="rotate(90)"><g transform="scale(2)">
      <line x1="0" y1="0" x2="10" y2="0"/></g></g></g>"""
    # 100 mm wide for 200 user units: one user unit is 0.5 mm
    path = write_svg(tmp_path, body, attrs='width="100mm" height="50mm" viewBox="0 0 200 100"')
    line = segments_of(path)[0].segments[0]
    assert same_segment(line, Line((10.0, -5.0), (10.0, -15.0)), 1e-9)


@pytest.mark.parametrize(("attrs", "mm_per_unit"), [
    ('width="4in" height="2in" viewBox="0 0 4 2"', 25.4),
    ('width="400" height="200"', MM_PER_USER_UNIT),
    ('width="10cm" height="5cm" viewBox="0 0 100 50"', 1.0),
    ('width="96px" height="96px" viewBox="0 0 1 1"', 25.4),
])
def test_document_units(tmp_path, attrs, mm_per_unit):
    line = segments_of(write_svg(tmp_path, '<line x1="0" y1="0" x2="1" y2="0"/>', attrs=attrs))[0].segments[0]
    assert line.length == pytest.approx(mm_per_unit, rel=1e-12)


def test_pieces_in_separate_elements_chain_in_either_direction(tmp_path):
    body = """
    <line x1="10" y1="10" x2="50" y2="10"/>
    <line x1="50" y1="30" x2="50" y2="10"/>
    <path d="M 10 30 L 50 30"/>
    <polyline points="10,10 10,30"/>"""
    polys = segments_of(write_svg(tmp_path, body, attrs=MM))
    assert len(polys) == 1 and polys[0].closed and polys[0].n_segments == 4 and len(polys[0].corners) == 4


def test_outlines_touching_at_a_corner_stay_apart(tmp_path):
    # two rectangles sharing a corner and a bow tie drawn through its own centre: each shape
    # is one closed contour of its own edges, not a figure eight through the shared point
    body = """
    <rect x="10" y="10" width="40" height="40"/>
    <rect x="50" y="50" width="40" height="40"/>
    <path d="M 100 10 L 130 40 L 160 10 L 160 70 L 130 40 L 100 70 Z"/>"""
    polys = segments_of(write_svg(tmp_path, body, attrs=MM))
    assert [(p.closed, p.n_segments, len(p.corners)) for p in polys] == [(True, 4, 4), (True, 4, 4), (True, 6, 6)]


def test_inkscape_layers(tmp_path):
    body = """
    <g inkscape:groupmode="layer" inkscape:label="Cut" id="layer1">
      <circle cx="20" cy="20" r="10"/>
      <g inkscape:groupmode="layer" inkscape:label="Holes"><circle cx="20" cy="20" r="3"/></g>
    </g>
    <g inkscape:groupmode="layer" inkscape:label="Marks"><line x1="50" y1="0" x2="60" y2="0"/></g>
    <g inkscape:groupmode="layer" inkscape:label="Hidden" style="display:none"><circle cx="80" cy="20" r="5"/></g>
    <circle cx="150" cy="20" r="4" visibility="hidden"/>"""
    path = write_svg(tmp_path, body, attrs=MM)
    assert len(segments_of(path)) == 3
    cut = segments_of(path, layers=["Cut"])
    assert sorted(round(p.segments[0].radius) for p in cut) == [3, 10]
    assert [round(p.segments[0].radius) for p in segments_of(path, layers=["holes"])] == [3]
    assert [p.n_lines for p in segments_of(path, layers=["Marks"])] == [1]
    with pytest.raises(InputError, match=r"layer 'Wood' \(--layer\): no such layer"):
        segment_drawing(path, TOL, layers=["Wood"])
    with pytest.raises(InputError, match=r"layer 'Hidden' \(--layer\) is hidden in the drawing"):
        segment_drawing(path, TOL, layers=["Hidden"])
    assert any("hidden layers (Hidden)" in n for n in segment_drawing(path, TOL).notes)


@pytest.mark.parametrize("hide", ['style="DISPLAY: None"', 'display="NONE"', 'style="fill:none;display:none"',
                                  'class="off"', 'visibility="hidden"'])
def test_hidden_shapes_are_left_out_in_any_letter_case_with_a_note(tmp_path, hide):
    body = f"""<style>.off {{display:none}}</style>
    <g {hide}><rect x="10" y="10" width="40" height="40"/></g>
    <circle cx="150" cy="50" r="20" fill="none" stroke="black"/>"""
    drawing = segment_drawing(write_svg(tmp_path, body, attrs=MM), TOL)
    assert [c.polysegment.n_arcs for c in drawing.contours] == [1]
    if "class" not in hide:  # a style sheet's hiding is applied, not counted
        assert any("left out 1 hidden elements" in n for n in drawing.notes)


def test_shapes_neither_filled_nor_stroked_are_left_out_unless_all_are(tmp_path):
    frame = '<rect id="frame" x="0" y="0" width="200" height="100" style="fill:none;stroke:none"/>'
    shapes = [frame, '<rect x="5" y="5" width="20" height="20" fill="none" stroke="#f00" stroke-width="0"/>',
              '<rect x="5" y="5" width="20" height="20" fill="transparent" stroke="none"/>']
    drawn = '<circle cx="150" cy="50" r="20" fill="none" stroke="black"/><rect x="60" y="10" width="9" height="9"/>'
    drawing = segment_drawing(write_svg(tmp_path, "".join(shapes) + drawn, attrs=MM), TOL)
    assert sorted(c.polysegment.n_arcs for c in drawing.contours) == [0, 1]  # the circle and the filled square
    assert any("left out 3 shapes drawn with neither fill nor stroke" in n and "frame" in n for n in drawing.notes)
    alone = segment_drawing(write_svg(tmp_path, frame, name="frame.svg", attrs=MM), TOL)
    assert len(alone.contours) == 1 and any("all 1 read" in n for n in alone.notes)


def test_uses_of_another_file_or_a_missing_id_are_named(tmp_path):
    refs = '<use xlink:href="parts.svg#bracket"/><use href="#nothing"/>'
    attrs = MM + ' xmlns:xlink="http://www.w3.org/1999/xlink"'
    drawing = segment_drawing(write_svg(tmp_path, refs + '<circle cx="50" cy="50" r="20"/>', attrs=attrs), TOL)
    assert len(drawing.contours) == 1
    assert any("left out 2 <use> elements that refer to nothing in this file" in n and "parts.svg#bracket" in n
               for n in drawing.notes)
    with pytest.raises(InputError, match="only <use> elements that refer to nothing in this file"):
        segment_drawing(write_svg(tmp_path, refs, name="refs.svg", attrs=attrs), TOL)


@pytest.mark.parametrize("attrs, unit_mm", [(MM, "1"), ('width="200mm" height="100mm" viewBox="0 0 800 400"', "0.25"),
                                            ('width="200" height="100"', "0.264583333")])
def test_summary_states_the_user_unit_in_mm(tmp_path, attrs, unit_mm):
    drawing = read_drawing(write_svg(tmp_path, '<circle cx="50" cy="50" r="20"/>', attrs=attrs))
    assert drawing.units == f"SVG user unit {unit_mm} mm (y flipped)"


@pytest.mark.parametrize("d", ["M 0 0 C 30 60 70 -60 100 0", "M 0 0 Q 50 80 100 0 T 200 0",
                               "M 0 0 A 60 20 30 1 1 100 10"])
def test_curves_within_tolerance(tmp_path, d):
    import svgelements as se

    path = write_svg(tmp_path, f'<path d="{d}"/>', attrs='width="300mm" height="200mm" viewBox="0 -100 300 200"')
    exact = np.vstack([np.asarray(seg.npoint(np.linspace(0, 1, 5000))) for seg in se.Path(d).segments()
                       if not isinstance(seg, se.Move)])
    exact = np.column_stack((exact[:, 0], -(exact[:, 1] + 100.0)))  # the viewBox starts at y = -100
    for tol in (0.05, 0.2):
        c = segment_drawing(path, tol).contours[0]
        assert c.max_deviation_mm <= tol
        assert max_distance(exact, c.polysegment, step=tol / 100) <= tol * 1.01
        assert max(g1_breaks(c.polysegment), default=0.0) < 1e-9


# ---------------------------------------------------------------- bad drawings

def _error(path, match: str, **kwargs) -> None:
    with pytest.raises(InputError, match=match) as info:
        segment_drawing(path, TOL, **kwargs)
    assert "\n" not in str(info.value) and str(path) in str(info.value)


def test_not_well_formed(tmp_path):
    path = tmp_path / "broken.svg"
    path.write_text('<svg xmlns="http://www.w3.org/2000/svg">\n  <path d="M 0 0 L 1 1">\n</svg>\n', encoding="utf-8")
    _error(path, r"broken\.svg:3:\d+: not well-formed SVG")


@pytest.mark.parametrize(("d", "match"), [
    ("M 0 0 L 10", r"'L' needs 2 numbers"),
    ("M 0 0 Q 1", r"'Q' needs 4 numbers"),
    ("L 0 0 10 10", r"must start with M"),
    ("M 0 0 X 3 4", r"unknown path command 'X'"),
    ("M 0 0 A 5 5 0 2 1 10 0", r"arc flag expected"),
])
def test_broken_path_data_names_the_element(tmp_path, d, match):
    _error(write_svg(tmp_path, f'<path id="outline" d="{d}"/>', attrs=MM), rf"<path id='outline'>: .*{match}")


def test_path_data_validator_accepts_compact_forms():
    for d in ("M0,0L10,10", "m0 0l10-10.5.5.5", "M0 0a5 5 0 1010 0", "M 0 0 h 1e1 v -2E-1 z m 3 3 l 1 1 Z", ""):
        assert path_data_error(d) is None, d


def test_not_svg_and_empty_and_only_text(tmp_path):
    html = tmp_path / "page.svg"
    html.write_text("<html><body/></html>", encoding="utf-8")
    _error(html, r"not an SVG")
    _error(write_svg(tmp_path, "", "empty.svg"), r"no geometry to spray")
    _error(write_svg(tmp_path, "<text x='1' y='1'>hello</text>", "text.svg"), r"no geometry to spray: only 1 text")
