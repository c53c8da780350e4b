"""Speed limits in the program header: corners and the fitter's stretches, per variant."""

from __future__ import annotations

import math
import re
from dataclasses import replace

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from coatsim.languages.kawasaki_as.language import KAWASAKI_AS
from coatsim.core.errors import InputError
from coatsim.geometry.polysegment import Polysegment, chain
from coatsim.languages.kawasaki_as import interpret, parse_as
from coatsim.path.build import VARIANTS, ProgramOptions, build_program
from coatsim.path.placement import Placement
from coatsim.path.process_record import format_limits, parse_limits
from coatsim.path.speed_limits import SpeedLimit, corner_limits, curve_limits

from program_helpers import roundrect


def d_shape(radius: float = 50.0, stem: float = 40.0) -> Polysegment:
    """Up the stem, right along the top, clockwise half circle, back left along the bottom: two
    true 90-degree corners (junction 0 at the top of the stem, the seam at its foot)."""
    up = chain((0.0, -radius), math.pi / 2, [0.0], [2 * radius])
    rest = chain((0.0, radius), 0.0, [0.0, -1.0 / radius, 0.0], [stem, math.pi * radius, stem])
    return Polysegment(up + rest, closed=True, corners=(0, 3))


def test_corners_become_zero_speed_points_at_their_arc_length():
    d = d_shape()
    first, seam = corner_limits(d)
    assert first == SpeedLimit(100.0, 100.0, 0.0)
    assert seam.s0_mm == seam.s1_mm == pytest.approx(d.length) and seam.v_max_mm_s == 0.0
    assert corner_limits(roundrect()) == ()


def test_fitter_stretches_and_corners_are_merged_in_order_once():
    d = d_shape()
    # the fitter lists the corners too once it knows the speed: they are not repeated
    limited = replace(d, speed_limited=((10.0, 12.0, 80.5), (100.0, 100.0, 0.0), (150.0, 160.0, 120.0)))
    limits = curve_limits(limited)
    assert [lim.s0_mm for lim in limits] == [10.0, 100.0, 150.0, pytest.approx(d.length)]
    assert [lim.v_max_mm_s for lim in limits] == [80.5, 0.0, 120.0, 0.0]
    assert curve_limits(d) == corner_limits(d)


@settings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(st.floats(0, 1e4), st.floats(0, 1e3), st.floats(0, 1e3)), max_size=8))
def test_header_value_round_trips(items):
    limits = tuple(SpeedLimit(round(a, 4), round(a + b, 4), round(v, 4)) for a, b, v in items)
    back = parse_limits(format_limits(limits), "t.as")
    assert back == tuple(SpeedLimit(float(f"{x.s0_mm:.4f}"), float(f"{x.s1_mm:.4f}"), float(f"{x.v_max_mm_s:.4f}"))
                         for x in limits)
    assert not re.search(r"\s{2,}", format_limits(limits))


@pytest.mark.parametrize("text,words", [
    ("1:2", "is not S0:S1:V"), ("a:b:c", "is not S0:S1:V"), ("5:4:1", "S0 <= S1"), ("1:2:-3", "speed >= 0"),
    ("", "is empty"), ("1:2:nan", "S0 <= S1"),
])
def test_bad_header_values_name_the_field(text, words):
    with pytest.raises(InputError, match=words) as info:
        parse_limits(text, "t.as")
    assert str(info.value).startswith("t.as: header field speed_limits")


@pytest.mark.parametrize("variant", VARIANTS)
def test_every_variant_carries_the_same_stretches_scaled_to_its_curve(variant):
    d = replace(d_shape(), speed_limited=((150.0, 160.0, 120.0),))
    built = build_program(d, Placement(), ProgramOptions(variant=variant), language=KAWASAKI_AS, tolerance_mm=0.1, source="d")
    limits = interpret(parse_as(built.text)).process.contours[0].speed_limits
    scale = built.curve.length / d.length
    assert [lim.v_max_mm_s for lim in limits] == [0.0, 120.0, 0.0]
    assert limits[1].s0_mm == pytest.approx(150.0 * scale, abs=1e-4)
    assert limits[-1].s0_mm == pytest.approx(built.curve.length, abs=1e-4)
    assert scale == pytest.approx(1.0, abs=1e-3) and (variant != "polysegment" or scale == 1.0)
