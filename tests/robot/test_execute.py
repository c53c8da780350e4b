"""End-to-end runs of the execute stage on ToolPaths built in code (real mink, toppra, MuJoCo)."""

import math

import numpy as np
import pytest

from coatsim.core.errors import ExecutionError
from coatsim.path.toolpath import ToolPath
from coatsim.robot.cell import load_cell
from coatsim.robot.execute import execute
from coatsim.robot.ik import POS_TOL_MM, ROT_TOL_DEG, Tracker
from coatsim.robot.sampling import plan_pieces
from coatsim.robot.timing import time_cartesian

from robot_helpers import approach, full_circle, lines, square, straight_line


@pytest.fixture(scope="module")
def cell():
    return load_cell()


def test_straight_line_reaches_and_holds_speed(cell):
    result = execute(straight_line(length=300.0, speed=200.0), cell)
    m = result.metrics
    assert m.stops == 0
    assert m.min_speed_mm_s > 0.99 * 200.0 and m.mean_speed_mm_s == pytest.approx(200.0, rel=0.005)
    assert m.fraction_at_speed == 1.0
    assert m.cycle_time_s == pytest.approx(m.ideal_time_s, rel=0.01)
    assert m.max_path_error_mm < 0.05
    assert result.residual.position_mm < POS_TOL_MM and result.residual.rotation_deg < ROT_TOL_DEG
    # the log is self-consistent: speed is the TCP displacement rate
    log = result.log
    fd = np.linalg.norm(np.diff(log.position, axis=0), axis=1) / np.diff(log.t)
    mid = slice(len(log) // 3, 2 * len(log) // 3)
    assert np.allclose(fd[mid], log.speed[mid], rtol=0.01)


def test_full_circle_of_two_arc_pairs_runs_at_constant_speed(cell):
    m = execute(full_circle(radius=100.0, speed=200.0), cell).metrics
    assert m.curve_length_mm == pytest.approx(2 * math.pi * 100.0, rel=1e-6)
    assert m.stops == 0
    assert m.min_speed_mm_s > 0.99 * 200.0 and m.speed_cv < 0.01
    assert m.max_path_error_mm < 0.1


def test_exact_stop_square_stops_at_its_corners_and_blended_one_does_not(cell):
    stop = execute(square(side=120.0, stop=True), cell)
    log, ref = stop.log, stop.reference
    for move in (2, 3, 4):  # the three corners inside the sprayed square
        corner = ref.move_span(move)[0]
        near = np.abs(log.progress - corner) < 0.5
        assert near.any() and log.speed[near].min() < 0.05 * 200.0
    blend = execute(square(side=120.0, stop=False, accuracy=5.0), cell).metrics
    assert blend.stops == 0 and blend.cycle_time_s < stop.metrics.cycle_time_s
    assert 0.5 < blend.max_path_error_mm <= 5.0  # corners cut, within the accuracy radius


def test_unreachable_pose_names_the_step(cell):
    far = ToolPath("far", (approach((700.0, 0.0)), *lines([(700.0, 0.0), (2600.0, 0.0)], first_line=42)))
    with pytest.raises(ExecutionError) as info:
        execute(far, cell)
    assert info.value.exit_code == 3
    assert "line 42 (linear move)" in str(info.value) and "out of reach: the wrist centre would be" in str(info.value)
    assert "\n" not in str(info.value)


def test_timed_trajectory_respects_every_limit(cell):
    tp = full_circle(radius=15.0, speed=300.0)  # v^2/R = 6 m/s^2 > the 5 m/s^2 tool limit
    piece = plan_pieces(tp, 1.0)[1]
    tracker = Tracker(cell)
    q0 = tracker.solve_pose(cell.home, piece.position[0], piece.rotation[0], "start")
    qs, _, res = tracker.track(q0, piece.s, piece.position, piece.rotation,
                               np.r_[0.0, np.diff(piece.s)] / piece.speed, str)
    assert res.position_mm < POS_TOL_MM and res.rotation_deg < ROT_TOL_DEG
    timed = time_cartesian(cell, piece.s, qs, piece.speed, piece.curvature, "circle")
    assert np.all(np.abs(timed.qd) <= cell.v_max * (1 + 1e-6))
    assert np.all(np.abs(timed.qdd) <= cell.a_max * (1 + 1e-6))
    assert timed.sd.max() <= 300.0 * (1 + 1e-6)
    # on the arc the centripetal acceleration caps the speed at sqrt(a R)
    on_arc = (timed.s > 40.0) & (timed.s < piece.length - 40.0)
    assert timed.sd[on_arc].max() <= math.sqrt(cell.tool_accel_mm_s2 * 15.0) * 1.001
    assert timed.sd[on_arc].min() > 0.95 * math.sqrt(cell.tool_accel_mm_s2 * 15.0)
    assert timed.q[0] == pytest.approx(qs[0]) and timed.q[-1] == pytest.approx(qs[-1])


def test_same_program_gives_identical_log(cell):
    a = execute(straight_line(length=60.0), cell).log.to_csv_text()
    b = execute(straight_line(length=60.0), cell).log.to_csv_text()
    assert a == b
