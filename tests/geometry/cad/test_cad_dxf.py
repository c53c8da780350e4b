"""DXF drawings written with ezdxf: exact round trips of lines, arcs and bulges, blocks with
transforms, units, layers, versions and encodings, free-form pieces within σ, and every kind
of bad drawing."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from coatsim.core.errors import InputError
from coatsim.geometry import Arc, Line, chain
from coatsim.geometry.cad import read_drawing, segment_drawing

from cad_helpers import EXACT, g1_breaks, max_distance, same_segment, write_dxf

TOL = 0.1


def rounded_rectangle(w: float = 100.0, h: float = 60.0, r: float = 10.0, x0: float = 0.0, y0: float = 0.0):
    """The eight primitives of a rounded rectangle, counter-clockwise from the bottom edge."""
    c = [(x0 + w - r, y0 + r), (x0 + w - r, y0 + h - r), (x0 + r, y0 + h - r), (x0 + r, y0 + r)]
    segs = [
        Line((x0 + r, y0), (x0 + w - r, y0)),
        Arc((x0 + w - r, y0), (x0 + w, y0 + r), c[0], r, math.pi / 2),
        Line((x0 + w, y0 + r), (x0 + w, y0 + h - r)),
        Arc((x0 + w, y0 + h - r), (x0 + w - r, y0 + h), c[1], r, math.pi / 2),
        Line((x0 + w - r, y0 + h), (x0 + r, y0 + h)),
        Arc((x0 + r, y0 + h), (x0, y0 + h - r), c[2], r, math.pi / 2),
        Line((x0, y0 + h - r), (x0, y0 + r)),
        Arc((x0, y0 + r), (x0 + r, y0), c[3], r, math.pi / 2),
    ]
    return segs


def add_segment(msp, seg, reverse: bool = False, layer: str = "0") -> None:
    """Write a line or arc as a DXF LINE or ARC (an ARC is always counter-clockwise)."""
    attrs = {"layer": layer}
    if isinstance(seg, Line):
        a, b = (seg.end, seg.start) if reverse else (seg.start, seg.end)
        msp.add_line(a, b, dxfattribs=attrs)
        return
    a0 = math.degrees(math.atan2(seg.start[1] - seg.center[1], seg.start[0] - seg.center[0]))
    a1 = a0 + math.degrees(seg.sweep)
    lo, hi = (a0, a1) if seg.sweep > 0 else (a1, a0)
    if abs(seg.sweep) >= 2 * math.pi - 1e-12:
        msp.add_circle(seg.center, seg.radius, dxfattribs=attrs)
    else:
        msp.add_arc(seg.center, seg.radius, lo, hi, dxfattribs=attrs)


def assert_same_chain(got, want, tol: float = EXACT) -> None:
    """``got`` is ``want`` segment by segment, or ``want`` traversed backwards."""
    forward = len(got) == len(want) and all(same_segment(a, b, tol) for a, b in zip(got, want))
    backward = len(got) == len(want) and all(same_segment(a, b.reversed(), tol) for a, b in zip(got, reversed(want)))
    assert forward or backward, f"{got} != {want}"


def rotate_to(segs, first: int):
    return segs[first:] + segs[:first]


# ---------------------------------------------------------------- exact round trips

def test_lines_and_arcs_come_back_exactly_in_either_direction(tmp_path):
    want = rounded_rectangle()
    path = write_dxf(tmp_path, lambda msp, doc: [add_segment(msp, s, reverse=k in (2, 4)) for k, s in enumerate(want)])
    part = segment_drawing(path, TOL)
    assert len(part.contours) == 1
    c = part.contours[0]
    poly = c.polysegment
    assert poly.closed and poly.corners == () and c.max_deviation_mm == 0.0
    assert_same_chain(list(poly.segments), want)
    assert max(g1_breaks(poly)) < 1e-9
    assert c.n_pieces == 8 and poly.n_segments == 8


def test_inserts_of_external_references_are_named(tmp_path):
    def draw(msp, doc, circle=True):
        doc.add_xref_def("frame.dxf", "FRAME")
        msp.add_blockref("FRAME", (0, 0))
        if circle:
            msp.add_circle((0, 0), 20)

    drawing = segment_drawing(write_dxf(tmp_path, draw), 0.1)
    assert len(drawing.contours) == 1
    assert any("1 inserts of external references (XREF)" in n and "'frame.dxf'" in n for n in drawing.notes)
    with pytest.raises(InputError, match=r"only inserts of external references \(XREF\)"):
        segment_drawing(write_dxf(tmp_path, lambda m, d: draw(m, d, False), name="xref.dxf"), 0.1)


def test_closed_polylines_touching_at_a_corner_stay_apart(tmp_path):
    def draw(msp, doc):
        msp.add_lwpolyline([(0, 0), (50, 0), (50, 50), (0, 50)], close=True)
        msp.add_lwpolyline([(50, 50), (100, 50), (100, 100), (50, 100)], close=True)

    contours = segment_drawing(write_dxf(tmp_path, draw), 0.1).contours
    assert [(c.polysegment.closed, c.polysegment.n_segments) for c in contours] == [(True, 4), (True, 4)]


def test_bulged_lwpolyline_is_its_lines_and_arcs(tmp_path):
    bulge = math.tan(math.pi / 8)  # a quarter circle
    pts = [(10, 0, 0, 0, 0), (90, 0, 0, 0, bulge), (100, 10, 0, 0, 0), (100, 50, 0, 0, bulge), (90, 60, 0, 0, 0),
           (10, 60, 0, 0, bulge), (0, 50, 0, 0, 0), (0, 10, 0, 0, bulge)]
    path = write_dxf(tmp_path, lambda msp, doc: msp.add_lwpolyline(pts, format="xyseb", close=True))
    poly = segment_drawing(path, TOL).contours[0].polysegment
    assert_same_chain(list(poly.segments), rounded_rectangle())
    assert poly.closed and poly.corners == ()


def test_r12_polyline_with_bulges_crlf(tmp_path):
    """An R12 file (POLYLINE/VERTEX, no $INSUNITS) with CRLF line ends."""
    path = write_dxf(tmp_path, lambda msp, doc: msp.add_polyline2d(
        [(0, 0, 0), (50, 0, 1.0), (50, 20, 0), (0, 20, 0)], format="xyb", close=True), version="R12", units=None)
    text = path.read_bytes().replace(b"\r\n", b"\n").replace(b"\n", b"\r\n")
    path.write_bytes(text)
    part = segment_drawing(path, TOL)
    poly = part.contours[0].polysegment
    assert any("no $INSUNITS" in n for n in part.notes)
    arc = next(s for s in poly.segments if isinstance(s, Arc))
    assert abs(arc.radius - 10.0) < EXACT and abs(abs(arc.sweep) - math.pi) < 1e-12
    assert math.dist(arc.center, (50.0, 10.0)) < EXACT
    assert poly.closed and len(poly.corners) == 2  # the semicircle is tangent to both long sides
    assert part.contours[0].max_deviation_mm == 0.0


@st.composite
def chains(draw):
    """Random chains of lines and arcs (G1, or with corners), none of them mergeable."""
    n = draw(st.integers(2, 7))
    kinds = draw(st.lists(st.sampled_from(["line", "arc"]), min_size=n, max_size=n))
    curv, lengths, corners = [], [], []
    for k, kind in enumerate(kinds):
        kappa = 0.0 if kind == "line" else draw(st.sampled_from([-1, 1])) / draw(st.floats(2.0, 60.0))
        if k and kind == "arc" and kinds[k - 1] == "arc" and abs(kappa - curv[-1]) < 1e-3:
            kappa = -kappa if abs(kappa + curv[-1]) > 1e-3 else kappa * 1.5
        curv.append(kappa)
        lengths.append(draw(st.floats(3.0, 40.0)) if kind == "line" else min(draw(st.floats(3.0, 40.0)), 5.0 / abs(kappa)))
        corners.append(draw(st.floats(0.3, 2.5)) * draw(st.sampled_from([-1, 1])) if k and kind == "line" and kinds[k - 1] == "line"
                       else (draw(st.sampled_from([0.0, 0.8])) if k else 0.0))
    segs, p, h = [], (draw(st.floats(-100, 100)), draw(st.floats(-100, 100))), draw(st.floats(-math.pi, math.pi))
    for kappa, length, turn in zip(curv, lengths, corners):
        seg = chain(p, h + turn, [kappa], [length])[0]
        segs.append(seg)
        p, h = seg.end, seg.end_heading
    flips = draw(st.lists(st.booleans(), min_size=n, max_size=n))
    order = draw(st.permutations(list(range(n))))
    return segs, flips, order


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(case=chains())
def test_random_line_arc_chains_come_back_exactly(tmp_path, case):
    """Property: any chain of lines and arcs written as LINE/ARC entities, in any order and
    direction, is read back as the same chain exactly, tangent where it was tangent."""
    segs, flips, order = case
    path = write_dxf(tmp_path, lambda msp, doc: [add_segment(msp, segs[k], reverse=flips[k]) for k in order])
    part = segment_drawing(path, TOL)
    assert len(part.contours) == 1
    c = part.contours[0]
    assert c.max_deviation_mm == 0.0 and not c.polysegment.closed
    assert_same_chain(list(c.polysegment.segments), segs, tol=1e-8)
    breaks = g1_breaks(c.polysegment)
    for k, b in enumerate(breaks):
        assert (k in c.polysegment.corners) == (b > 1e-6)


def test_collinear_lines_and_concentric_arcs_merge(tmp_path):
    def draw(msp, doc):
        msp.add_line((0, 0), (10, 0))
        msp.add_line((10, 0), (25, 0))
        msp.add_line((40, 0), (25, 0))  # drawn backwards
        msp.add_arc((40, 20), 20, -90, 0)
        msp.add_arc((40, 20), 20, 0, 45)
        msp.add_circle((200, 0), 5)
        msp.add_arc((300, 0), 5, 0, 180)
        msp.add_arc((300, 0), 5, 180, 360)

    part = segment_drawing(write_dxf(tmp_path, draw), TOL)
    polys = [c.polysegment for c in part.contours]
    assert [p.n_segments for p in polys] == [2, 1, 1]
    line, arc = polys[0].segments
    assert same_segment(line, Line((0.0, 0.0), (40.0, 0.0)))
    assert abs(arc.sweep - math.radians(135)) < 1e-12 and arc.radius == 20.0
    for poly in polys[1:]:
        assert poly.closed and abs(abs(poly.segments[0].sweep) - 2 * math.pi) < 1e-12
    assert all(c.max_deviation_mm <= 1e-9 for c in part.contours)
    assert sum(c.n_pieces for c in part.contours) == 8


# ---------------------------------------------------------------- blocks, transforms, units

def _slot(block_or_msp, layer: str = "0") -> None:
    block_or_msp.add_line((0, 0), (10, 0), dxfattribs={"layer": layer})
    block_or_msp.add_arc((10, 5), 5, -90, 90, dxfattribs={"layer": layer})
    block_or_msp.add_line((10, 10), (0, 10), dxfattribs={"layer": layer})
    block_or_msp.add_arc((0, 5), 5, 90, 270, dxfattribs={"layer": layer})


def _transform(scale: float, deg: float, offset, mirror: bool = False):
    a = math.radians(deg)
    rot = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
    flip = np.diag([-1.0, 1.0]) if mirror else np.eye(2)
    return lambda p: tuple(float(v) for v in rot @ (scale * flip @ np.asarray(p, float)) + np.asarray(offset, float))


def test_nested_insert_scaled_and_rotated(tmp_path):
    def draw(msp, doc):
        inner = doc.blocks.new("SLOT")
        _slot(inner)
        outer = doc.blocks.new("HOLDER")
        outer.add_blockref("SLOT", (0, 0), dxfattribs={"rotation": 10})
        msp.add_blockref("HOLDER", (100, 50), dxfattribs={"xscale": 2, "yscale": 2, "rotation": 20})

    poly = segment_drawing(write_dxf(tmp_path, draw), TOL).contours[0].polysegment
    f = _transform(2.0, 30.0, (100, 50))
    want = [Line(f((0, 0)), f((10, 0))), Arc(f((10, 0)), f((10, 10)), f((10, 5)), 10.0, math.pi),
            Line(f((10, 10)), f((0, 10))), Arc(f((0, 10)), f((0, 0)), f((0, 5)), 10.0, math.pi)]
    assert poly.closed and poly.corners == ()
    assert_same_chain(list(poly.segments), want)


def test_mirrored_insert_keeps_arcs_exact(tmp_path):
    def draw(msp, doc):
        _slot(doc.blocks.new("SLOT"))
        msp.add_blockref("SLOT", (0, 0), dxfattribs={"xscale": -1, "yscale": 1})

    poly = segment_drawing(write_dxf(tmp_path, draw), TOL).contours[0].polysegment
    f = _transform(1.0, 0.0, (0, 0), mirror=True)
    want = [Line(f((0, 0)), f((10, 0))), Arc(f((10, 0)), f((10, 10)), f((10, 5)), 5.0, -math.pi),
            Line(f((10, 10)), f((0, 10))), Arc(f((0, 10)), f((0, 0)), f((0, 5)), 5.0, -math.pi)]
    assert_same_chain(list(poly.segments), want)


def test_non_uniform_insert_turns_arcs_into_fitted_ellipses(tmp_path):
    def draw(msp, doc):
        doc.blocks.new("C").add_circle((0, 0), 10)
        msp.add_blockref("C", (0, 0), dxfattribs={"xscale": 3, "yscale": 1})

    c = segment_drawing(write_dxf(tmp_path, draw), TOL).contours[0]
    t = np.linspace(0, 2 * math.pi, 4000)
    exact = np.column_stack((30 * np.cos(t), 10 * np.sin(t)))
    assert c.polysegment.closed and c.polysegment.corners == ()
    assert c.max_deviation_mm <= TOL
    assert max_distance(exact, c.polysegment, step=TOL / 100) <= TOL * 1.01
    assert max(g1_breaks(c.polysegment)) < 1e-9


@pytest.mark.parametrize(("code", "factor"), [(1, 25.4), (2, 304.8), (5, 10.0), (6, 1000.0), (4, 1.0)])
def test_insunits_convert_to_mm(tmp_path, code, factor):
    path = write_dxf(tmp_path, lambda msp, doc: msp.add_line((0, 0), (1, 2)), units=code)
    line = segment_drawing(path, TOL).contours[0].polysegment.segments[0]
    assert math.dist(line.end, (factor, 2 * factor)) < 1e-9 * factor


def test_unknown_insunits_is_an_error(tmp_path):
    path = write_dxf(tmp_path, lambda msp, doc: msp.add_line((0, 0), (1, 2)), units=19)  # light years
    with pytest.raises(InputError, match=r"INSUNITS = 19"):
        segment_drawing(path, TOL)


# ---------------------------------------------------------------- layers and ignored entities

def test_layers_default_visible_and_selected_by_name(tmp_path):
    def draw(msp, doc):
        doc.layers.add("CUT")
        doc.layers.add("NOTES")
        doc.layers.add("HIDDEN").off()
        doc.layers.add("ICE").freeze()
        msp.add_circle((0, 0), 5, dxfattribs={"layer": "CUT"})
        msp.add_circle((20, 0), 5, dxfattribs={"layer": "NOTES"})
        msp.add_circle((40, 0), 5, dxfattribs={"layer": "HIDDEN"})
        msp.add_circle((60, 0), 5, dxfattribs={"layer": "ICE"})
        block = doc.blocks.new("B")
        block.add_circle((0, 0), 2)  # on layer 0: takes the INSERT's layer
        msp.add_blockref("B", (0, 30), dxfattribs={"layer": "CUT"})
        msp.add_blockref("B", (0, 60), dxfattribs={"layer": "HIDDEN"})

    path = write_dxf(tmp_path, draw)
    centers = lambda part: sorted(tuple(round(v) for v in c.polysegment.segments[0].center) for c in part.contours)  # noqa: E731
    default = segment_drawing(path, TOL)
    assert centers(default) == [(0, 0), (0, 30), (20, 0)]
    assert any("off or frozen" in n for n in default.notes)
    assert centers(segment_drawing(path, TOL, layers=["cut"])) == [(0, 0), (0, 30)]
    assert centers(segment_drawing(path, TOL, layers=["HIDDEN", "ICE"])) == [(0, 60), (40, 0), (60, 0)]
    with pytest.raises(InputError, match=r"layer 'WOOD' \(--layer\): no such layer .*'CUT'"):
        segment_drawing(path, TOL, layers=["WOOD"])


def test_annotation_fills_views_meshes_ignored_with_a_note(tmp_path):
    def draw(msp, doc):
        msp.add_circle((0, 0), 10)
        msp.add_text("Außenkontur")
        msp.add_mtext("note")
        msp.add_linear_dim(base=(0, 15), p1=(-10, 0), p2=(10, 0)).render()
        msp.add_hatch().paths.add_polyline_path([(0, 0), (1, 0), (1, 1)])
        with msp.add_mesh().edit_data() as mesh:
            mesh.vertices = [(0, 0, 0), (1, 0, 0), (1, 1, 1)]
            mesh.faces = [(0, 1, 2)]
        msp.add_point((3, 3))

    part = segment_drawing(write_dxf(tmp_path, draw), TOL)
    assert len(part.contours) == 1
    note = next(n for n in part.notes if n.startswith("ignored"))
    for kind in ("TEXT", "MTEXT", "DIMENSION", "HATCH", "MESH", "POINT"):
        assert kind in note


@pytest.mark.parametrize(("version", "layer"), [("R2000", "Außenkontur"), ("R2018", "輪郭"), ("R12", "AUSSEN")])
def test_versions_and_non_ascii_names(tmp_path, version, layer):
    def draw(msp, doc):
        doc.layers.add(layer)
        doc.header["$PROJECTNAME"] = "Prüfteil Größe 2" if version != "R12" else "P2"
        msp.add_circle((0, 0), 10, dxfattribs={"layer": layer})
        msp.add_line((20, 0), (30, 0))

    path = write_dxf(tmp_path, draw, version=version, units=None if version == "R12" else 4)
    part = segment_drawing(path, TOL, layers=[layer])
    assert len(part.contours) == 1 and part.contours[0].polysegment.n_arcs == 1


def test_binary_dxf_is_read(tmp_path):
    import ezdxf

    doc = ezdxf.new("R2010")
    _slot(doc.modelspace())
    path = tmp_path / "binary.dxf"
    doc.saveas(path, fmt="bin")
    assert path.read_bytes().startswith(b"AutoCAD Binary DXF")
    poly = segment_drawing(path, TOL).contours[0].polysegment
    assert poly.closed and poly.n_segments == 4


# ---------------------------------------------------------------- free-form pieces

def test_spline_within_tolerance_and_g1_to_its_lines(tmp_path):
    fit = [(0, 0), (20, 15), (40, -5), (60, 10), (80, 0)]

    def draw(msp, doc):
        msp.add_spline(fit_points=fit)

    path = write_dxf(tmp_path, draw)
    import ezdxf

    curve = ezdxf.readfile(path).modelspace()[0].construction_tool()
    exact = np.array([(v.x, v.y) for v in curve.points(np.linspace(0, curve.max_t, 20000))])
    for tol in (0.01, 0.1, 0.5):
        c = segment_drawing(path, tol).contours[0]
        assert c.max_deviation_mm <= tol
        assert max_distance(exact, c.polysegment, step=tol / 100) <= tol * 1.01
        assert max(g1_breaks(c.polysegment)) < 1e-9 and c.polysegment.corners == ()
        assert math.dist(c.polysegment.start, (0, 0)) < 1e-9 and math.dist(c.polysegment.end, (80, 0)) < 1e-9


def test_free_form_pieces_join_tangent_neighbours_g1(tmp_path):
    """A spline tangent to a line at each end, and half an ellipse tangent to a line: the
    fitted chains are G1 to the native lines, exactly; the lines stay exact."""

    def draw(msp, doc):
        msp.add_line((0, 0), (10, 0))
        msp.add_open_spline([(10, 0), (20, 0), (30, 10), (30, 20)])
        msp.add_line((30, 40), (30, 20))  # drawn backwards
        msp.add_line((100, 0), (120, 0))
        msp.add_ellipse((120, 5), major_axis=(0, -5), ratio=0.6, start_param=0, end_param=math.pi)
        msp.add_line((120, 10), (90, 10))

    part = segment_drawing(write_dxf(tmp_path, draw), TOL)
    for c in part.contours:
        poly = c.polysegment
        assert poly.corners == () and max(g1_breaks(poly)) < 1e-9 and c.max_deviation_mm <= TOL
    first, second = (c.polysegment.segments for c in part.contours)
    assert same_segment(first[0], Line((0.0, 0.0), (10.0, 0.0))) and same_segment(first[-1], Line((30.0, 20.0), (30.0, 40.0)))
    assert same_segment(second[0], Line((100.0, 0.0), (120.0, 0.0))) and same_segment(second[-1], Line((120.0, 10.0), (90.0, 10.0)))


def test_cusp_inside_a_spline_is_a_corner(tmp_path):
    """A triple control point makes a kink inside a span: a corner there, not a pile of
    fillets; a smooth ellipse and spline get none."""
    path = write_dxf(tmp_path, lambda msp, doc: msp.add_open_spline(
        [(0, 0), (10, 0), (20, 10), (20, 10), (20, 10), (30, 0), (40, 0)]))
    c = segment_drawing(path, TOL).contours[0]
    poly = c.polysegment
    assert [tuple(round(v, 9) for v in poly.segments[k].end) for k in poly.corners] == [(20.0, 10.0)]
    assert c.max_deviation_mm <= TOL and poly.n_segments <= 6


def test_full_ellipse_is_a_closed_g1_loop(tmp_path):
    path = write_dxf(tmp_path, lambda msp, doc: msp.add_ellipse((5, 5), major_axis=(40, 10), ratio=0.4))
    c = segment_drawing(path, TOL).contours[0]
    assert c.polysegment.closed and c.polysegment.corners == ()
    assert c.max_deviation_mm <= TOL and max(g1_breaks(c.polysegment)) < 1e-9


def test_circle_drawn_as_ellipse_is_native(tmp_path):
    path = write_dxf(tmp_path, lambda msp, doc: msp.add_ellipse((0, 0), major_axis=(10, 0), ratio=1.0,
                                                                start_param=0, end_param=math.pi))
    seg = segment_drawing(path, TOL).contours[0].polysegment.segments
    assert len(seg) == 1 and isinstance(seg[0], Arc) and seg[0].radius == 10.0


def test_tilted_entities_are_left_out_with_a_note(tmp_path):
    def draw(msp, doc):
        msp.add_circle((0, 0), 10)
        msp.add_line((0, 0, 0), (10, 0, 5))
        msp.add_circle((0, 0), 10, dxfattribs={"extrusion": (0, 1, 1)})

    part = segment_drawing(write_dxf(tmp_path, draw), TOL)
    assert len(part.contours) == 1
    assert any("not parallel to the drawing plane" in n for n in part.notes)


def test_drawing_wholly_in_a_tilted_plane_is_read_in_that_plane(tmp_path):
    """A flat part drawn in a tilted UCS: every entity shares one extrusion."""
    normal = (0.0, 0.6, 0.8)

    def draw(msp, doc):
        msp.add_lwpolyline([(0, 0), (40, 0), (40, 20), (0, 20)], close=True, dxfattribs={"extrusion": normal})
        msp.add_circle((20, 10), 5, dxfattribs={"extrusion": normal})

    part = segment_drawing(write_dxf(tmp_path, draw), TOL)
    outline, hole = (c.polysegment for c in part.contours)
    assert any("tilted from XY" in n for n in part.notes)
    corners = sorted((round(s.start[0], 9), round(s.start[1], 9)) for s in outline.segments)
    assert corners == [(0.0, 0.0), (0.0, 20.0), (40.0, 0.0), (40.0, 20.0)]
    assert math.dist(hole.segments[0].center, (20.0, 10.0)) < EXACT and hole.segments[0].radius == 5.0


# ---------------------------------------------------------------- bad drawings

def _error(path, match: str, **kwargs) -> None:
    with pytest.raises(InputError, match=match) as info:
        segment_drawing(path, TOL, **kwargs)
    assert "\n" not in str(info.value) and str(path) in str(info.value)


def test_empty_modelspace(tmp_path):
    _error(write_dxf(tmp_path, lambda msp, doc: None), r"modelspace is empty")


def test_only_text(tmp_path):
    _error(write_dxf(tmp_path, lambda msp, doc: (msp.add_text("A"), msp.add_mtext("B"))),
           r"no geometry to spray: only 1 MTEXT, 1 TEXT")


def test_everything_on_frozen_layers(tmp_path):
    def draw(msp, doc):
        doc.layers.add("ICE").freeze()
        msp.add_circle((0, 0), 5, dxfattribs={"layer": "ICE"})

    _error(write_dxf(tmp_path, draw), r"no visible geometry.*ICE.*--layer")


def test_ends_nearly_meeting_are_joined_or_named(tmp_path):
    """A gap below half the tolerance is closed (the contour is fitted within what is left
    of it); a wider one below the tolerance leaves two contours, and a note names them."""
    def draw(gap):
        def inner(msp, doc):
            msp.add_line((0, 0), (10, 0))
            msp.add_line((10 + gap, 0), (10, 10))
        return inner

    part = segment_drawing(write_dxf(tmp_path, draw(0.04)), TOL)
    assert len(part.contours) == 1 and part.contours[0].polysegment.n_segments == 2
    assert part.contours[0].max_deviation_mm <= TOL
    assert any("largest gap closed is 0.04 mm" in n for n in part.notes)
    part = segment_drawing(write_dxf(tmp_path, draw(0.08), name="apart.dxf"), TOL)
    assert len(part.contours) == 2
    assert any(re.search(r"not joined .* first LINE #\w+ at \(10, 0\), 0\.08 mm from LINE #\w+", n) for n in part.notes)
    part = segment_drawing(write_dxf(tmp_path, draw(0.08), name="wide.dxf"), TOL, join_tolerance_mm=0.09)
    assert len(part.contours) == 1 and part.contours[0].polysegment.n_segments == 2


@pytest.mark.parametrize(("content", "match"), [
    (b"\x00\x01\x02garbage\xff" * 50, r"not a readable DXF file"),
    (b"AC1032\x00\x00binary dwg", r"a DWG file, not DXF"),
    (b"", r"not a readable DXF file"),
    (b"hello\nthis is not a drawing\n", r"not a readable DXF file"),
])
def test_files_that_are_not_dxf(tmp_path, content, match):
    path = tmp_path / "bad.dxf"
    path.write_bytes(content)
    _error(path, match)


def test_truncated_dxf(tmp_path):
    path = write_dxf(tmp_path, lambda msp, doc: _slot(msp))
    text = path.read_text(encoding="utf-8")
    path.write_text(text[: text.index("ENTITIES") + 200], encoding="utf-8")
    with pytest.raises(InputError, match=str(path)):
        segment_drawing(path, TOL)


def test_missing_file_and_folder(tmp_path):
    _error(tmp_path / "nothing.dxf", r"no such file")
    folder = tmp_path / "dir.dxf"
    folder.mkdir()
    _error(folder, r"is a folder")


def test_reader_keeps_drawing_order_and_names(tmp_path):
    def draw(msp, doc):
        msp.add_circle((50, 0), 3)
        _slot(msp)

    drawing = read_drawing(write_dxf(tmp_path, draw))
    assert drawing.pieces[0].source.startswith("CIRCLE #")
    part = segment_drawing(write_dxf(tmp_path, draw), TOL)
    assert part.contours[0].polysegment.n_segments == 1 and part.contours[1].polysegment.n_segments == 4


def test_paperspace_geometry_is_noted_not_dropped_silently(tmp_path):
    def draw(msp, doc):
        msp.add_circle((0, 0), 10)
        paper = doc.paperspace("Layout1")
        paper.add_circle((5, 5), 100)
        paper.add_line((0, 0), (200, 0))

    drawing = read_drawing(write_dxf(tmp_path, draw))
    assert len(drawing.pieces) == 1
    assert any("2 entities in paperspace layouts (Layout1)" in n for n in drawing.notes)


def test_only_paperspace_geometry_is_an_error_that_says_so(tmp_path):
    def draw(msp, doc):
        doc.paperspace("Layout1").add_circle((5, 5), 10)

    with pytest.raises(InputError, match="modelspace is empty.*paperspace"):
        read_drawing(write_dxf(tmp_path, draw))
