"""A part program on the simulated arm: one curve proper per contour (closed ones sprayed once
around, an open one with its lead-in and lead-out), metrics per contour that add up to the
part's."""

from __future__ import annotations

import math

import numpy as np
import pytest

from coatsim.languages.kawasaki_as.language import KAWASAKI_AS
from coatsim.geometry import Arc, Line, Polysegment, chain
from coatsim.languages.kawasaki_as.parser import parse_as
from coatsim.path.build import ProgramOptions
from coatsim.languages.kawasaki_as.interpreter import interpret
from coatsim.path.part_program import build_part_program
from coatsim.geometry.space.xyzoat import pose_from_xyzoat
from coatsim.path.placement import Placement
from coatsim.robot.cell import load_cell
from coatsim.robot.execute import execute


def circle(cx: float, cy: float, r: float) -> Polysegment:
    return Polysegment((Arc((cx + r, cy), (cx + r, cy), (cx, cy), r, 2 * math.pi),), closed=True)


@pytest.fixture(scope="module")
def run():
    outline = Polysegment(chain((-60.0, -40.0), 0.0, [0, 0.1, 0, 0.1, 0, 0.1, 0, 0.1],
                                [100, 5 * math.pi, 60, 5 * math.pi] * 2), closed=True)
    stroke = Polysegment((Line((-40.0, -20.0), (40.0, -20.0)),))  # open: sprayed with its lead-in and lead-out
    part = [outline, circle(-25.0, 10.0, 8.0), circle(25.0, 10.0, 10.0), stroke]
    placement = Placement(frame=pose_from_xyzoat((700, 0, 200, 0, 0, 0)), standoff_mm=100.0, lead_in_mm=10.0, lead_out_mm=10.0)
    built = build_part_program(part, placement, ProgramOptions(speed_mm_s=200.0, accuracy_mm=0.5), language=KAWASAKI_AS, tolerance_mm=0.1,
                               source="part")
    return part, execute(interpret(parse_as(built.text, "part.as")), load_cell(), step_mm=2.0)


def test_one_curve_proper_per_contour(run):
    part, ex = run
    assert len(ex.curves) == 4 and len(ex.contour_metrics) == 4
    for (a, b), poly in zip(ex.curves, part):
        assert b - a == pytest.approx(poly.length, abs=1e-6)
    assert all(b1 < a2 for (_, b1), (a2, _) in zip(ex.curves[:-1], ex.curves[1:]))
    on = ex.log.spray.astype(int)
    assert np.count_nonzero(np.diff(on) == 1) == 4  # the gun opens once per contour


def test_part_metrics_add_up(run):
    _, ex = run
    m, each = ex.metrics, ex.contour_metrics
    assert m.curve_length_mm == pytest.approx(sum(c.curve_length_mm for c in each))
    assert m.cycle_time_s == pytest.approx(sum(c.cycle_time_s for c in each))
    assert m.ideal_time_s == pytest.approx(sum(c.ideal_time_s for c in each))
    assert m.stops == sum(c.stops for c in each) == 0
    assert m.max_path_error_mm == pytest.approx(max(c.max_path_error_mm for c in each))
    assert m.min_speed_mm_s == pytest.approx(min(c.min_speed_mm_s for c in each))
    assert m.fraction_at_speed >= 0.95
    # the travel between contours is not part of the curve proper
    assert m.cycle_time_s < m.total_time_s - 2.0
