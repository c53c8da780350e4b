"""The twin runs the program's TOOL with the cell's gun, and never hides a diverged simulation.

Real program text, real mink / toppra / MuJoCo. Programs here are short so each run takes a
second or so.
"""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

import mujoco
import numpy as np
import pytest

from coatsim.core.errors import ExecutionError
from coatsim.languages.kawasaki_as.files import read_toolpath
from coatsim.robot.cell import load_cell
from coatsim.robot.checks import (LIMIT_FAIL_RATIO, TRACKING_FAIL_MM, check_playback, joint_ratios,
                                  tracking_error)
from coatsim.robot.execute import execute

# A tilted straight pass, an arc and a turn of the tool about its axis: the spray axis is not
# constant, so a TOOL offset along it moves the spray point along a varying direction.
PROGRAM = """.PROGRAM tooltest()
  BASE NULL
  TOOL TRANS(0,0,{tool_z},0,0,0) ; the gun's TCP is 250 mm from the flange
  SPEED 200 MM/S ALWAYS
  ACCURACY 1 ALWAYS
  CP ON
  JAPPRO p0, 50
  LMOVE p0
  BREAK
  SIGNAL 1
  LMOVE p1
  C1MOVE p2
  C2MOVE p3
  LMOVE p4
  BREAK
  SIGNAL -1
  LDEPART 50
.END
.TRANS
p0 640.0 -60.0 300.0 0.0 180.0 0.0
p1 700.0 -60.0 300.0 0.0 170.0 0.0
p2 742.4264069 -42.4264069 300.0 0.0 170.0 20.0
p3 760.0 0.0 300.0 0.0 175.0 40.0
p4 760.0 40.0 300.0 0.0 180.0 40.0
.END
"""
TOOL_LINE = 3


@pytest.fixture(scope="module")
def cell():
    return load_cell()


def program_file(folder: Path, tool_z: float, name: str = "p.as") -> Path:
    path = folder / name
    path.write_text(PROGRAM.format(tool_z=f"{tool_z:g}"), encoding="ascii")
    return path


@pytest.fixture(scope="module")
def runs(cell, tmp_path_factory):
    folder = tmp_path_factory.mktemp("tool")
    return {z: execute(read_toolpath(program_file(folder, z, f"tool{z:g}.as")), cell) for z in (250.0, 300.0)}


def test_a_matching_tool_runs_on_the_programmed_path_without_warnings(runs):
    matched = runs[250.0]
    assert matched.events == ()
    on = matched.log.spray
    assert matched.log.path_error[on].max() < 0.25


def test_tool_50_mm_longer_moves_the_spray_point_50_mm_back_along_the_tool_axis(runs):
    result = runs[300.0]
    log = result.log
    on = log.spray
    # the physical gun runs 50 mm short of the programmed TCP along the (varying) spray axis: 50 mm
    # ahead of it along its axis lies the programmed path (to 0.25 mm, so the axis is right to 0.3 deg)
    ahead = log.position[on] + 50.0 * log.axis[on]
    dist, _, _ = result.reference.project(ahead, np.maximum.accumulate(log.progress[on]), 100.0)
    assert dist.max() < 0.25
    # the logged path error says so (less where the tilted axis has a component along the path,
    # or where the retracted gun comes near the approach and depart lines)
    assert 49.0 < np.median(log.path_error[on]) <= 50.25


def test_the_mismatch_is_a_warning_naming_the_tool_line_and_the_offset(runs):
    events = runs[300.0].events
    tool = [e for e in events if "(TOOL)" in e]
    assert len(tool) == 1, events
    assert tool[0].startswith(f"tooltest: line {TOOL_LINE} (TOOL): TOOL TRANS(0,0,300,0,0,0) is not the gun's TCP "
                              "TRANS(0,0,250,0,0,0)")
    assert "runs 50.000 mm from the programmed TCP (tool frame x 0.000, y 0.000, z -50.000 mm)" in tool[0]


def test_a_tool_change_mid_program_moves_the_spray_point_from_there_on(cell, tmp_path):
    """After TOOL 20 mm longer, the controller's TCP is 20 mm further down from the unmoved flange,
    and the last LMOVE takes it from there to p4: the gun ends 20 mm above p4."""
    text = PROGRAM.format(tool_z="250").replace("  LMOVE p4\n", "  TOOL TRANS(0,0,270,0,0,0)\n  LMOVE p4\n")
    path = tmp_path / "change.as"
    path.write_text(text, encoding="ascii")
    result = execute(read_toolpath(path), cell)
    tool_line = text.splitlines().index("  TOOL TRANS(0,0,270,0,0,0)") + 1
    assert any(e.startswith(f"tooltest: line {tool_line} (TOOL):") and "runs 20.000 mm" in e for e in result.events)
    log, moves = result.log, read_toolpath(path).moves
    before = log.spray & (log.position[:, 1] < -1.0)  # the first pass and the arc, up to p3 (y = 0)
    assert log.path_error[before].max() < 0.25
    # the controller's TCP starts 20 mm down the tool axis of p3 (the flange unmoved) and runs to p4
    z3 = moves[3].end.rotation[:, 2]
    start, end = moves[3].end.translation_mm + 20.0 * z3, moves[4].end.translation_mm
    during = log.spray & (log.position[:, 1] > 2.0) & (log.position[:, 1] < 38.0)
    ahead = log.position[during] + 20.0 * log.axis[during]  # the gun is 20 mm behind that TCP
    u = np.clip((ahead - start) @ (end - start) / np.sum((end - start) ** 2), 0, 1)
    assert np.linalg.norm(ahead - (start + u[:, None] * (end - start)), axis=1).max() < 0.25
    gun_off = np.flatnonzero(log.spray)[-1]
    np.testing.assert_allclose(log.position[gun_off], [760.0, 40.0, 320.0], atol=0.3)


def test_check_program_reports_the_mismatch(tmp_path, run_cli):
    code, out, err = run_cli(["check-program", str(program_file(tmp_path, 300.0))])
    assert code == 0, err
    assert f"problem: {tmp_path / 'p.as'}:{TOOL_LINE}: TOOL TRANS(0,0,300,0,0,0) is not the gun's TCP" in out
    code, out, err = run_cli(["check-program", str(program_file(tmp_path, 250.0))])
    assert code == 0 and "is not the gun's TCP" not in out


def test_check_program_reads_a_program_that_never_opens_the_gun(tmp_path, run_cli):
    """Reading is not spraying: exit 0, a note naming the outputs the program does switch."""
    path = program_file(tmp_path, 250.0)
    code, out, err = run_cli(["check-program", str(path), "--gun", "2"])
    assert code == 0 and err == ""
    assert f"note: {path}: the gun (output 2) is never on during a motion; it switches output 1" in out
    assert "--gun N picks the process signal" in out


# ---------------------------------------------------------------- divergence


def test_the_diverged_ellipse_exits_3_naming_a_program_line(tmp_path, run_cli):
    """The issue's case: the approach drives the gun through the table; once it silently
    reported a path error of 1144 mm and exit 0."""
    prog = tmp_path / "e.as"
    code, _, err = run_cli(["program", "builtin:ellipse", "--tol", "0.1", "--frame", "300,0,-300,0,0,0", "-o", str(prog)])
    assert code == 0, err
    code, out, err = run_cli(["execute", str(prog), "-o", str(tmp_path / "out")])
    assert code == 3, out + err
    assert err.count("\n") == 1 and err.startswith("coatsim: error: ")
    line = re.search(r": line (\d+) \(", err)
    assert line, err
    stmt = prog.read_text().splitlines()[int(line.group(1)) - 1].split(";")[0].split()
    assert stmt[0] in ("JAPPRO", "LMOVE", "C1MOVE", "C2MOVE", "LDEPART", "JMOVE"), stmt
    assert "touches the" in err  # found on the commanded motion, before any playback
    assert not (tmp_path / "out" / "trajectory.csv").exists()


def test_tracking_error_is_the_distance_to_the_commanded_path_not_the_lag():
    t = np.arange(200) * 0.002
    commanded = np.column_stack((500.0 * t, np.zeros_like(t), np.zeros_like(t)))
    lagging = np.roll(commanded, 3, axis=0)
    lagging[:3] = commanded[0]
    assert tracking_error(lagging, commanded, 25).max() < 1e-9  # 3 mm behind, but on the path
    off = commanded + [0.0, 0.4, 0.0]
    np.testing.assert_allclose(tracking_error(off, commanded, 25), 0.4)


def test_playback_checks_fail_above_and_warn_below_the_thresholds(cell):
    n = 400
    t = np.arange(n) * cell.timestep
    data = mujoco.MjData(cell.model)

    def label(i: int) -> str:
        return f"p: line {10 + i // 100} (LMOVE)"

    def tcp_of(q: np.ndarray) -> np.ndarray:
        return np.array([cell.forward(data, qk)[0] for qk in q])

    rest = np.tile(cell.home, (n, 1))
    at_rest = tcp_of(rest)
    assert check_playback(cell, t, rest, at_rest, rest, label) == []
    rise = np.clip(np.arange(n) - 250, 0, None) * 0.01  # mm, 1 mm reached at row 350 (line 13)
    with pytest.raises(ExecutionError, match=r"^p: line 13 \(LMOVE\): the simulation diverged: the simulated tool is "):
        check_playback(cell, t, rest, at_rest + np.outer(rise, [0, 0, 1]), rest, label)
    warnings = check_playback(cell, t, rest, at_rest + np.outer(np.minimum(rise, 0.4), [0, 0, 1]), rest, label)
    assert len(warnings) == 1 and "0.400 mm off the commanded path (more than 0.25 mm)" in warnings[0]
    # JT1 at 103 % of its speed limit warns, at 110 % fails
    for factor in (1.03, 1.10):
        moving = rest.copy()
        moving[:, 0] += factor * cell.v_max[0] * t
        if factor > LIMIT_FAIL_RATIO:
            with pytest.raises(ExecutionError, match="JT1 joint speed at 110.0 % of its limit"):
                check_playback(cell, t, moving, tcp_of(moving), moving, label)
        else:
            found = check_playback(cell, t, moving, tcp_of(moving), moving, label)
            assert len(found) == 1 and "JT1 joint speed at 103.0 % of its limit (more than 100 %)" in found[0]
    assert TRACKING_FAIL_MM == 1.0


def test_normal_programs_stay_within_the_joint_limits(runs):
    """The planner commands 95 % of the limits, so the simulated arm stays within them (before:
    the command sat at 100 % and the arm overshot by 0.6 to 2 %)."""
    for result in runs.values():
        assert result.metrics.max_joint_accel_ratio < 1.0
        assert result.metrics.max_joint_speed_ratio < 1.0
        speed, accel, _ = joint_ratios(result.log.q, 0.002, load_cell().v_max, load_cell().a_max)
        assert accel.max() == pytest.approx(result.metrics.max_joint_accel_ratio, rel=1e-6)
        assert speed.max() == pytest.approx(result.metrics.max_joint_speed_ratio, rel=1e-6)


def test_execute_writes_warnings_to_stderr_and_motion_json(tmp_path):
    path = program_file(tmp_path, 300.0)
    done = subprocess.run([sys.executable, "-m", "coatsim.cli", "execute", str(path), "-o", str(tmp_path / "out")],
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    assert "warning: tooltest: line 3 (TOOL):" in done.stderr
    assert not [line for line in done.stdout.splitlines() if line.startswith("warning")]
    events = json.loads((tmp_path / "out" / "motion.json").read_text())["events"]
    assert any("(TOOL)" in e for e in events)
