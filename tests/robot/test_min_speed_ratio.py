"""motion.min_speed_ratio: the lowest speed where the curve allows the programmed speed."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from coatsim.path.process_record import decode
from coatsim.path.process import ProcessInfo, SprayedContour
from coatsim.path.speed_limits import SpeedLimit
from coatsim.core.errors import InputError
from coatsim.path.toolpath import ToolPath
from coatsim.robot.cell import load_cell
from coatsim.robot.execute import execute
from coatsim.robot.motion_metrics import RAMP_FACTOR, CurveAllowance, allowed_by_curve

from robot_helpers import square, straight_line

A = 5000.0  # mm/s², the default cell's tool acceleration limit
V = 300.0


@pytest.fixture(scope="module")
def cell():
    return load_cell()


def ramp(v_limit: float) -> float:
    return RAMP_FACTOR * (V**2 - v_limit**2) / (2 * A)


def test_analytic_mask_of_one_corner_and_one_slow_stretch():
    s = np.linspace(0.0, 200.0, 20001)
    allowance = CurveAllowance(((50.0, 50.0, 0.0), (120.0, 130.0, 200.0)), lead_in_mm=100.0, lead_out_mm=100.0)
    ok = allowed_by_curve(s, 200.0, V, A, allowance)
    expected = (np.abs(s - 50.0) >= ramp(0.0)) & ((s <= 120.0 - ramp(200.0)) | (s >= 130.0 + ramp(200.0)))
    assert np.array_equal(ok, expected)


def test_rest_points_beyond_short_leads_exclude_the_ramps_only():
    s = np.linspace(0.0, 100.0, 1001)
    ok = allowed_by_curve(s, 100.0, V, A, CurveAllowance(lead_in_mm=5.0, lead_out_mm=0.0))
    assert np.array_equal(ok, (s + 5.0 >= ramp(0.0)) & (100.0 - s >= ramp(0.0)))
    assert allowed_by_curve(s, 100.0, V, A, CurveAllowance(lead_in_mm=50.0, lead_out_mm=50.0)).all()


def test_a_corner_at_the_seam_of_a_closed_curve_excludes_both_sides():
    s = np.linspace(0.0, 300.0, 3001)
    leads = dict(lead_in_mm=50.0, lead_out_mm=50.0)
    closed = allowed_by_curve(s, 300.0, V, A, CurveAllowance(((0.0, 0.0, 0.0),), closed=True, **leads))
    assert np.array_equal(closed, (s >= ramp(0.0)) & (300.0 - s >= ramp(0.0)))
    open_ = allowed_by_curve(s, 300.0, V, A, CurveAllowance(((0.0, 0.0, 0.0),), closed=False, **leads))
    assert open_[-1] and not open_[0]


limit = st.tuples(st.floats(0, 400), st.floats(0, 50), st.floats(0, 400))


@settings(max_examples=80, deadline=None)
@given(st.lists(limit, max_size=6), limit, st.booleans(), st.floats(0, 30), st.floats(0, 30))
def test_more_limits_never_allow_more(limits, extra, closed, lead_in, lead_out):
    s = np.linspace(0.0, 400.0, 801)
    as_limits = [(a, a + b, v) for a, b, v in limits]
    base = allowed_by_curve(s, 400.0, V, A, CurveAllowance(tuple(as_limits), closed, lead_in, lead_out))
    more = allowed_by_curve(s, 400.0, V, A, CurveAllowance(tuple(as_limits + [(extra[0], extra[0] + extra[1], extra[2])]),
                                                            closed, lead_in, lead_out))
    assert not np.any(more & ~base)
    if extra[2] >= V:
        assert np.array_equal(more, base)


def test_a_line_that_reaches_its_speed_keeps_it(cell):
    result = execute(straight_line(speed=200.0), cell)
    assert result.metrics.min_speed_ratio == pytest.approx(1.0, abs=0.02)


def test_stops_count_where_the_curve_allows_the_speed_and_declared_corners_do_not(cell):
    stopping = square(side=200.0, speed=200.0, stop=True)
    assert execute(stopping, cell).metrics.min_speed_ratio < 0.05
    # the same square declared as a curve with four true corners: the stops are where it must slow
    corners = tuple(SpeedLimit(s, s, 0.0) for s in (200.0, 400.0, 600.0))
    declared = ToolPath(stopping.name, stopping.moves, ProcessInfo(contours=(SprayedContour(speed_limits=corners),)))
    assert execute(declared, cell).metrics.min_speed_ratio == pytest.approx(1.0, abs=0.03)


def test_a_curve_that_allows_the_speed_nowhere_has_no_ratio(cell):
    line = straight_line(length=6.0, speed=200.0, lead=0.0)
    assert execute(line, cell).metrics.min_speed_ratio is None


def test_a_malformed_header_is_an_input_error():
    with pytest.raises(InputError, match="speed_limits"):
        decode((("speed_limits", "10:5:0"),), "line")
    with pytest.raises(InputError, match="sprayed='everything'"):
        decode((("sprayed", "everything"),), "line")


def test_the_sprayed_header_decides_whether_the_leads_are_part_of_the_curve(cell):
    """straight_line sprays only its middle move: with sprayed=curve that move is the curve
    proper; with the leads declared sprayed, the header's lead lengths are cut from it."""
    line = straight_line(length=300.0, lead=20.0)
    only_curve = execute(ToolPath(line.name, line.moves, ProcessInfo(lead_in_mm=20.0, contours=(
        SprayedContour(leads_sprayed=False),))), cell)
    assert only_curve.metrics.curve_length_mm == pytest.approx(300.0, abs=1e-6)
    with_leads = execute(ToolPath(line.name, line.moves, ProcessInfo(lead_in_mm=20.0, lead_out_mm=30.0)), cell)
    assert with_leads.metrics.curve_length_mm == pytest.approx(250.0, abs=1e-6)



def test_a_speed_that_varies_along_the_curve_is_the_measure_of_each_row():
    """With the speed on the trace every move asks its own: a tool at 300 mm/s where 300 is asked
    and at 600 where 600 is, slowed to 25 mm/s in the first half, runs at speed everywhere but
    there, and that slowing is no stop (5 % of 300 is 15); measured against the largest (600)
    half the curve was slow and the dip a stop."""
    from coatsim.robot.motion_metrics import motion_metrics
    from coatsim.robot.trajectory_log import TrajectoryLog

    s = np.linspace(0.0, 200.0, 2001)
    asked = np.where(s < 100.0, 300.0, 600.0)
    speed = asked.copy()
    speed[(s > 80) & (s < 82)] = 25.0
    t = np.concatenate(([0.0], np.cumsum(np.diff(s) / speed[1:])))
    log = TrajectoryLog(t=t, position=np.column_stack((s, 0 * s, 0 * s)), axis=np.tile([0, 0, -1.0], (len(s), 1)),
                        speed=speed, spray=np.ones(len(s), bool), progress=s, path_error=0 * s,
                        q=np.zeros((len(s), 6)), trace_speed=speed)
    args = (np.zeros(len(s)), A, np.full(6, 1e9), np.full(6, 1e9), (0.0, 0.0))
    rows = motion_metrics(log, (0.0, 200.0), asked, *args)
    flat = motion_metrics(log, (0.0, 200.0), 600.0, *args)
    assert rows.stops == 0 and flat.stops == 1
    assert rows.fraction_at_speed == pytest.approx(0.99, abs=0.005) and flat.fraction_at_speed == pytest.approx(0.5, abs=0.01)
    assert rows.min_speed_ratio == pytest.approx(25 / 300) and rows.programmed_speed_mm_s == 600.0
    assert rows.ideal_time_s == pytest.approx(100 / 300 + 100 / 600, rel=1e-3)
