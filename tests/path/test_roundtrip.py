"""Round trip: polysegment -> AS text -> parse -> interpret -> the same 3-D path.

Positions within 1e-4 mm and tangents within 1e-6 rad, piece by piece, for both variants.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from coatsim.languages.kawasaki_as.language import KAWASAKI_AS
from coatsim.geometry.benchmark import NAMES as BENCH_NAMES
from coatsim.geometry.benchmark import bench_curve
from coatsim.geometry.polysegment import Polysegment, chain
from coatsim.languages.kawasaki_as import interpret, parse_as
from coatsim.path.build import VARIANTS, ProgramOptions, build_program
from coatsim.geometry.space.xyzoat import pose_from_xyzoat
from coatsim.path.placement import Placement, centering_offset

from program_helpers import arc_spiral, path_errors, roundrect

POSITION_MM, TANGENT_RAD, ROTATION_RAD = 1e-4, 1e-6, 1e-6


def round_trip(poly: Polysegment, variant: str, placement: Placement = Placement(), points=None):
    built = build_program(poly, placement, ProgramOptions(variant=variant), language=KAWASAKI_AS, tolerance_mm=0.05,
                          source="rt", points=points)
    toolpath = interpret(parse_as(built.text, "rt.as"))
    return built, toolpath, path_errors(built.path, toolpath)


def assert_same_path(errors):
    dp, dt, dr = errors
    assert dp <= POSITION_MM and dt <= TANGENT_RAD and dr <= ROTATION_RAD, errors


@pytest.mark.parametrize("variant", VARIANTS)
@pytest.mark.parametrize("poly", [roundrect(), arc_spiral(), roundrect(300.0, 20.0, 2.0)], ids=["rr", "spiral", "thin"])
def test_constructed_curves(poly, variant):
    built, toolpath, errors = round_trip(poly, variant)
    assert_same_path(errors)
    assert toolpath.process.variant == variant
    assert toolpath.process.lead_in_mm == 30.0


@pytest.mark.parametrize("frame", [pose_from_xyzoat((700, 0, 200, 0, 0, 0)), pose_from_xyzoat((600, -300, 900, 90, 90, 0)),
                                   pose_from_xyzoat((-400, 500, 100, 35, 150, -60)), pose_from_xyzoat((800, 100, 300, 10, 180, 20))])
@pytest.mark.parametrize("follow", [False, True])
def test_frames_and_tool_roll(frame, follow):
    placement = Placement(frame=frame, follow_tangent=follow, roll_deg=25.0, standoff_mm=60.0)
    assert_same_path(round_trip(arc_spiral(turns=2), "polysegment", placement)[2])


def _approach_and_depart_are_dry(toolpath):
    approach, down = toolpath.moves[:2]
    assert not approach.spray and not down.spray and not toolpath.moves[-1].spray
    assert down.settings.stop_at_end
    # The approach and depart are along the surface normal, standoff + 50 mm above the surface.
    assert approach.target.translation_mm[2] == pytest.approx(200.0 + 100.0 + 50.0)
    assert toolpath.moves[-1].end.translation_mm[2] == pytest.approx(200.0 + 100.0 + 50.0)


@pytest.mark.parametrize("variant", VARIANTS)
def test_closed_contour_is_sprayed_exactly_once_around(rr, variant):
    """Lead-in and lead-out run with the gun closed; the gun is on from the seam to the seam."""
    built, toolpath, _ = round_trip(rr, variant, Placement(lead_in_mm=12.0, lead_out_mm=7.0))
    from coatsim.path.arcs import move_length

    path_moves = toolpath.moves[2:-1]
    assert [m.spray for m in path_moves] == [False] + [True] * (len(path_moves) - 2) + [False]
    assert sum(move_length(m) for m in toolpath.spray_moves) == pytest.approx(built.curve.length, abs=1e-5)
    assert np.allclose(toolpath.spray_moves[0].start.translation_mm, toolpath.spray_moves[-1].end.translation_mm, atol=1e-6)
    assert not toolpath.process.contours[0].leads_sprayed
    # on the fly: no stop where the gun switches, unless the variant stops at every point
    stop = variant == "polyline-stop"
    assert all(m.settings.stop_at_end == stop for m in path_moves[:-1]) and path_moves[-1].settings.stop_at_end
    _approach_and_depart_are_dry(toolpath)


@pytest.mark.parametrize("lead_in,lead_out", [(12.0, 7.0), (0.0, 7.0), (12.0, 0.0), (0.0, 0.0)])
def test_closed_contour_without_leads_switches_at_rest(rr, lead_in, lead_out):
    built, toolpath, _ = round_trip(rr, "polysegment", Placement(lead_in_mm=lead_in, lead_out_mm=lead_out))
    from coatsim.path.arcs import move_length

    assert sum(move_length(m) for m in toolpath.spray_moves) == pytest.approx(rr.length, abs=1e-5)
    path_moves = toolpath.moves[2:-1]
    assert path_moves[0].spray == (lead_in == 0.0) and path_moves[-1].spray == (lead_out == 0.0)
    assert toolpath.spray_moves[-1].settings.stop_at_end == (lead_out == 0.0)


def test_open_curve_is_sprayed_with_its_leads_and_nothing_else():
    poly = arc_spiral(turns=1)
    built, toolpath, _ = round_trip(poly, "polysegment", Placement(lead_in_mm=12.0, lead_out_mm=7.0))
    from coatsim.path.arcs import move_length

    sprayed = sum(move_length(m) for m in toolpath.spray_moves)
    assert sprayed == pytest.approx(poly.length + 19.0, abs=1e-5)
    assert toolpath.process.contours[0].leads_sprayed
    assert toolpath.spray_moves[-1].settings.stop_at_end
    assert not any(m.settings.stop_at_end for m in toolpath.spray_moves[:-1])
    _approach_and_depart_are_dry(toolpath)


# make_segment builds an arc from its centre, so curvatures near zero (radius beyond ~1e6 mm)
# give end points that are off by more than the test tolerance before any program is written.
curvature = st.one_of(st.floats(1e-5, 0.3), st.floats(-0.3, -1e-5))


@settings(max_examples=40, deadline=None)
@given(st.lists(st.tuples(curvature, st.floats(0.5, 60.0), st.booleans()), min_size=1, max_size=12),
       st.floats(-math.pi, math.pi))
def test_random_g1_chains(pieces, heading):
    curvatures = [k if arc else 0.0 for k, _, arc in pieces]
    poly = Polysegment(chain((3.0, -7.0), heading, curvatures, [length for _, length, _ in pieces]))
    assert_same_path(round_trip(poly, "polysegment")[2])


@pytest.mark.parametrize("name", BENCH_NAMES)
@pytest.mark.parametrize("variant", ["polyline-stop", "polyline-blend"])
def test_benchmark_curves_polyline_variants(name, variant):
    """The polyline variants simplify the input points directly (no fitter needed)."""
    curve = bench_curve(name)
    # A stand-in polysegment only fixes closedness and centring here: the polyline comes from the points.
    anchor = Polysegment(chain(tuple(curve.points[0]), 0.0, [0.0], [1.0]), closed=curve.closed)
    built, _, errors = round_trip(anchor, variant, points=curve.points)
    assert_same_path(errors)
    assert built.curve.n_segments >= 4


@pytest.mark.slow
@pytest.mark.parametrize("name", BENCH_NAMES)
@pytest.mark.parametrize("tol", [0.01, 0.1])
def test_benchmark_curves_segmented(name, tol):
    """Every benchmark curve through the fitter, then both program variants."""
    from coatsim.geometry import segment_curve

    curve = bench_curve(name)
    poly = segment_curve(curve, tol).polysegment
    placement = Placement(offset_xy=centering_offset(poly))
    for variant in VARIANTS:
        built, toolpath, errors = round_trip(poly, variant, placement, points=curve.points)
        assert_same_path(errors)
        if variant == "polysegment":
            arcs_written = sum(m.kind == "arc" for m in toolpath.spray_moves)
            assert arcs_written >= poly.n_arcs
            assert np.isclose(toolpath.process.curve_length_mm, poly.length, atol=1e-6)


def test_a_full_circle_split_into_arc_pairs_is_sprayed_from_its_first_pair():
    """The gun switches as the first move of the first segment starts, even when that segment is
    an arc the writer splits into several C1MOVE/C2MOVE pairs."""
    circle = Polysegment(chain((0.0, 0.0), 0.0, [0.02], [2 * math.pi * 50.0]), closed=True)
    built, toolpath, errors = round_trip(circle, "polysegment")
    assert_same_path(errors)
    assert [m.kind for m in toolpath.spray_moves] == ["arc"] * 3
    assert not toolpath.moves[2].spray and not toolpath.moves[-2].spray  # lead-in and lead-out
    text = built.text.splitlines()
    first_signal = next(i for i, line in enumerate(text) if line.strip().startswith("SIGNAL 1"))
    assert text[first_signal - 1].strip().startswith("C2MOVE") and text[first_signal - 2].strip().startswith("C1MOVE")
    assert "segment 1 (1/3)" in text[first_signal - 2]
