"""Placement of a planar polysegment in the robot base frame."""

from __future__ import annotations

import math

import numpy as np
import pytest

from coatsim.core.errors import InputError
from coatsim.geometry.polysegment import Polysegment, chain
from coatsim.geometry.space.rotations import oat_to_matrix
from coatsim.geometry.space.pose import rotation_angle
from coatsim.path.frames import DEFAULT_FRAME
from coatsim.geometry.space.xyzoat import parse_xyzoat, pose_from_xyzoat
from coatsim.path.placement import Placement, centering_offset, place, polyline_polysegment

from program_helpers import arc_spiral, roundrect


def test_default_frame_standoff_and_tool_down(rr):
    path = place(rr, Placement(standoff_mm=80.0))
    for seg in path.segments:
        for pose in (seg.start, seg.end):
            assert pose.translation_mm[2] == pytest.approx(DEFAULT_FRAME.translation_mm[2] + 80.0)
            assert np.allclose(pose.rotation, oat_to_matrix(0, 180, 0), atol=1e-15)
    assert path.segments[1].start.translation_mm[:2] == pytest.approx([700.0 - 65.0, -40.0])


def test_tilted_frame_maps_points_and_normal():
    frame = pose_from_xyzoat((500.0, -100.0, 300.0, 30.0, 60.0, -20.0))
    line = Polysegment((chain((10.0, 5.0), 0.0, [0.0], [20.0])[0],))
    path = place(line, Placement(frame=frame, standoff_mm=50.0, lead_in_mm=0.0, lead_out_mm=0.0))
    r = frame.rotation
    seg = path.segments[0]
    assert np.allclose(seg.start.translation_mm, frame.translation_mm + r @ [10.0, 5.0, 0.0] + 50.0 * r[:, 2])
    assert np.allclose(seg.end.translation_mm, frame.translation_mm + r @ [30.0, 5.0, 0.0] + 50.0 * r[:, 2])
    assert np.allclose(seg.start.rotation[:, 2], -r[:, 2])   # spray axis points at the surface
    assert np.allclose(path.normal, r[:, 2])


def test_lead_in_and_out_are_tangent_extensions():
    poly = arc_spiral(turns=1)
    path = place(poly, Placement(lead_in_mm=25.0, lead_out_mm=12.0))
    lead_in, first, last, lead_out = path.segments[0], path.segments[1], path.segments[-2], path.segments[-1]
    assert (lead_in.part, lead_out.part) == ("lead_in", "lead_out")
    assert lead_in.length == pytest.approx(25.0) and lead_out.length == pytest.approx(12.0)
    assert np.array_equal(lead_in.end.translation_mm, first.start.translation_mm)
    assert np.array_equal(lead_out.start.translation_mm, last.end.translation_mm)
    _, t_in = lead_in.point_tangent(np.array([1.0]))
    _, t_first = first.point_tangent(np.array([0.0]))
    _, t_last = last.point_tangent(np.array([1.0]))
    _, t_out = lead_out.point_tangent(np.array([0.0]))
    assert np.allclose(t_in, t_first, atol=1e-12) and np.allclose(t_last, t_out, atol=1e-12)
    assert path.length == pytest.approx(poly.length + 37.0)
    assert path.curve_length_mm == pytest.approx(poly.length)


def test_no_leads_when_zero(rr):
    path = place(rr, Placement(lead_in_mm=0.0, lead_out_mm=0.0))
    assert [s.part for s in path.segments] == ["curve"] * 8


def test_placed_arcs_follow_the_planar_arcs(rr):
    path = place(rr, Placement(lead_in_mm=0.0, lead_out_mm=0.0))
    for seg, placed in zip(rr.segments, path.segments):
        s = np.linspace(0.0, seg.length, 7)
        p2 = seg.points(s)
        p3, t3 = placed.point_tangent(s / seg.length)
        assert np.allclose(p3[:, :2] - [700.0, 0.0], p2, atol=1e-12)
        assert np.allclose(t3[:, :2], seg.tangents(s), atol=1e-12)
        assert placed.is_arc == (seg.kind == "arc")


def test_follow_tangent_turns_the_tool_with_the_path(rr):
    path = place(rr, Placement(follow_tangent=True, roll_deg=0.0))
    for seg in path.segments:
        for u, pose in ((0.0, seg.start), (1.0, seg.end)):
            _, tangent = seg.point_tangent(np.array([u]))
            assert np.allclose(pose.rotation[:, 0], tangent[0], atol=1e-12)
            assert np.allclose(pose.rotation[:, 2], [0, 0, -1], atol=1e-12)
    arc = path.segments[2]
    mid = arc.via
    assert rotation_angle(arc.start.rotation, mid.rotation) == pytest.approx(math.pi / 4)


def test_fixed_roll_rotates_about_the_spray_axis(rr):
    a = place(rr, Placement(roll_deg=0.0)).segments[1].start
    b = place(rr, Placement(roll_deg=30.0)).segments[1].start
    assert rotation_angle(a.rotation, b.rotation) == pytest.approx(math.radians(30.0))
    assert np.allclose(a.rotation[:, 2], b.rotation[:, 2])


def test_arc_split_into_equal_pieces():
    circle = Polysegment(chain((0.0, 0.0), 0.0, [0.05], [2 * math.pi * 20.0]), closed=True)
    arc = place(circle, Placement(lead_in_mm=0, lead_out_mm=0)).segments[0]
    pieces = arc.split(math.radians(170.0))
    assert len(pieces) == 3
    assert all(p.geometry.sweep == pytest.approx(2 * math.pi / 3) for p in pieces)
    assert np.array_equal(pieces[-1].end.translation_mm, arc.end.translation_mm)
    for a, b in zip(pieces[:-1], pieces[1:]):
        assert np.allclose(a.end.translation_mm, b.start.translation_mm, atol=1e-12)
    assert arc.split(math.radians(360.0)) == (arc,)


def test_centering_offset_uses_the_exact_bounding_box():
    # A half circle of radius 10 above the x axis from (10, 0) to (-10, 0): the box is
    # [-10, 10] x [0, 10], reached at the arc's top, not at its end points.
    half = Polysegment(chain((10.0, 0.0), math.pi / 2, [0.1], [math.pi * 10.0]))
    assert centering_offset(half) == pytest.approx((0.0, -5.0), abs=1e-12)
    assert centering_offset(roundrect()) == pytest.approx((0.0, 0.0), abs=1e-12)


def test_frame_parse_and_errors():
    assert parse_xyzoat("1, 2,3,4,5,6", "frame").is_close(pose_from_xyzoat((1, 2, 3, 4, 5, 6)))
    for bad in ("1,2,3", "a,b,c,d,e,f", "1,2,3,4,5,nan", ""):
        with pytest.raises(InputError, match="^frame: expected 6") as info:
            parse_xyzoat(bad, "frame")
        assert str(info.value.reworded({"frame": "--frame"})).startswith("--frame: expected 6")


@pytest.mark.parametrize("field,value", [("standoff_mm", 0.0), ("lead_in_mm", -1.0), ("lead_out_mm", math.inf)])
def test_placement_rejects_bad_values(field, value):
    with pytest.raises(InputError, match=field):
        Placement(**{field: value})


def test_polyline_polysegment_closes_and_drops_repeats():
    poly = polyline_polysegment(np.array([[0, 0], [1, 0], [1, 0], [1, 1]]), closed=True)
    assert poly.n_segments == 3 and all(isinstance(s, type(poly.segments[0])) for s in poly.segments)
    assert poly.end == poly.start
    with pytest.raises(InputError):
        polyline_polysegment(np.array([[0, 0], [0, 0]]), closed=False)
    assert not place(poly, Placement()).segments[1].is_arc
