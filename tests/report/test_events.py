"""Events tied to program lines: the robot stage's messages parsed back, speed dips at the move
where the speed is lowest, the curve's limits and the seam."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from coatsim.path.process_record import decode
from coatsim.report.events import lines_of, parse_step, run_events, speed_dips
from coatsim.robot.sampling import step_label


def _toolpath(lines, header=()):
    """A stand-in program of line moves; ``header`` its AS header fields (decoded as the reader does)."""
    moves = [SimpleNamespace(line=line, kind="line") for line in lines]
    return SimpleNamespace(name="job", moves=moves, process=decode(tuple(header), "job"))


def test_messages_give_back_the_line_of_step_label():
    toolpath = _toolpath([12, 14, 20])
    for index, line in ((0, 12), (2, 20)):
        line_back, kind, text = parse_step(f"{step_label(toolpath, index)}: JT5 within 2 deg of its limit")
        assert (line_back, kind, text) == (line, "linear move", "JT5 within 2 deg of its limit")
    assert parse_step(f"{step_label(toolpath, None)}: near wrist singularity")[0] is None
    assert parse_step("something else") == (None, "", "something else")


def _execution(speed, progress, events=(), residual=0.0):
    """A run along 3 moves of 100 mm each (lines 11, 12, 13); the curve proper 0..300 mm."""
    n = len(speed)
    log = SimpleNamespace(t=np.arange(n) * 0.002, speed=np.asarray(speed, float), progress=np.asarray(progress, float),
                          spray=np.ones(n, bool))
    reference = SimpleNamespace(offsets=np.array([0.0, 100.0, 200.0]), moves=np.array([0, 1, 2]),
                                move_span=lambda i: (100.0 * i, 100.0 * (i + 1)))
    return SimpleNamespace(log=log, curve=(0.0, 300.0), reference=reference, events=tuple(events),
                           metrics=SimpleNamespace(programmed_speed_mm_s=200.0, max_ik_residual_mm=residual))


def test_a_stop_at_a_vertex_is_a_dip_at_the_move_that_ends_there():
    progress = np.linspace(0.0, 300.0, 3001)
    speed = np.full_like(progress, 200.0)
    speed[(progress > 95) & (progress < 105)] = 20.0 * np.abs(progress[(progress > 95) & (progress < 105)] - 100.0)
    dips = speed_dips("polyline-stop", _execution(speed, progress), _toolpath([11, 12, 13]))
    assert len(dips) == 1
    (dip,) = dips
    assert dip.line == 11 and dip.s_mm == pytest.approx(100.0, abs=0.2) and dip.severity == "warning"
    assert "0 mm/s (0 % of 200)" in dip.message and "1 stop" in dip.message


def test_no_dip_at_speed_and_dips_apart_are_apart():
    progress = np.linspace(0.0, 300.0, 3001)
    assert speed_dips("p", _execution(np.full_like(progress, 199.0), progress), _toolpath([11, 12, 13])) == []
    speed = np.full_like(progress, 200.0)
    speed[(progress > 140) & (progress < 150)] = 150.0
    speed[(progress > 250) & (progress < 260)] = 100.0
    dips = speed_dips("p", _execution(speed, progress), _toolpath([11, 12, 13]))
    assert [d.line for d in dips] == [12, 13]


def test_run_events_order_warnings_first_with_lines_and_notes():
    progress = np.linspace(0.0, 300.0, 3001)
    toolpath = _toolpath([11, 12, 13], {"closed": "yes", "speed_limits": "150:150:0 240:260:120"}.items())
    messages = [f"{step_label(toolpath, 2)}: JT1 joint speed at 101.0 % of its limit (more than 100 %) at t = 1.000 s",
                f"{step_label(toolpath, 1)}: near wrist singularity (JT5 = 3.0 deg)"]
    events = run_events("v", _execution(np.full_like(progress, 200.0), progress, messages, residual=0.02), toolpath)
    kinds = [e.kind for e in events]
    assert kinds[:2] == ["joint speed over the limit", "singularity proximity"]
    assert {"IK residual", "speed-limited stretch", "true corner", "seam"} <= set(kinds)
    assert events[0].line == 13 and events[0].t_s == 1.0 and events[1].s_mm == pytest.approx(150.0)
    corner = next(e for e in events if e.kind == "true corner")
    assert corner.line == 12 and corner.severity == "note"
    assert lines_of(events, "v") == {12, 13}


def test_the_travel_between_the_contours_of_a_part_has_no_dip():
    """A part's run: two curves proper (0..100 and 200..300 mm) with a stop in the travel between."""
    progress = np.linspace(0.0, 300.0, 3001)
    speed = np.full_like(progress, 200.0)
    speed[(progress > 120) & (progress < 180)] = 0.0
    execution = _execution(speed, progress)
    execution.curves = ((0.0, 100.0), (200.0, 300.0))
    assert speed_dips("part", execution, _toolpath([11, 12, 13])) == []
    execution.curves = ()
    assert len(speed_dips("part", execution, _toolpath([11, 12, 13]))) == 1


def test_a_part_program_header_gives_each_contour_its_limits_and_seam():
    from coatsim.report.events import curve_notes

    progress = np.linspace(0.0, 300.0, 3001)
    execution = _execution(np.full_like(progress, 200.0), progress)
    execution.curves = ((0.0, 100.0), (200.0, 300.0))
    toolpath = _toolpath([11, 12, 13], {"speed_limits": "none | 50:50:0", "closed": "no | yes"}.items())
    notes = curve_notes("part", execution, toolpath)
    corner = next(e for e in notes if e.kind == "true corner")
    assert corner.s_mm == pytest.approx(250.0) and corner.line == 13 and corner.message.startswith("contour 2: ")
    seam = next(e for e in notes if e.kind == "seam")
    assert seam.s_mm == pytest.approx(200.0) and "contour 2" in seam.message
    assert len(notes) == 2
