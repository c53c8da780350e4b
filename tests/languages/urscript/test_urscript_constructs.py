"""One test per URScript construct the reader runs: def … end, movel/movec/movej/movep, p[]
literals in metres and rotation vectors, a= v= t= r=, set_tcp, set_digital_out, pose_trans and the
other pose functions, functions, loops, variables, and what it refuses."""

from __future__ import annotations

import math

import numpy as np
import pytest

from coatsim.core.errors import ExecutionError, InputError
from coatsim.geometry.space.primitives import arc_through
from coatsim.geometry.space.rotations import rot_x, rot_z
from coatsim.languages.urscript.values import PoseValue, pose_add, pose_inv, pose_sub, pose_trans, rpy2rotvec, rotvec2rpy

from language_plans import read_text

DOWN = "3.14159265359, 0, 0"  # a rotation vector of a half turn about x: the tool points down


def run(body, tmp_path, head="", **options):
    text = head + "def prog():\n" + "".join(f"  {line}\n" for line in body.strip("\n").split("\n")) + "end\n"
    return read_text("urscript", text, tmp_path, **options)


def at(move):
    return np.round((move.target if move.kind == "joint" else move.end).translation_mm, 6)


def test_a_script_is_a_function_the_controller_runs(tmp_path):
    tp = run(f"movej(p[0.5, 0, 0.3, {DOWN}])\nmovel(p[0.6, 0, 0.3, {DOWN}])", tmp_path)
    assert tp.name == "prog" and [m.kind for m in tp.moves] == ["joint", "line"]


def test_pose_literals_are_metres_and_rotation_vectors(tmp_path):
    tp = run("movej(p[0.5, -0.1, 0.3, 0, 0, 1.5707963267949])", tmp_path)
    assert list(at(tp.moves[0])) == [500, -100, 300]
    assert np.allclose(tp.moves[0].target.rotation, rot_z(math.pi / 2))


def test_movel_speed_time_and_blend_radius(tmp_path):
    body = (f"movej(p[0.5, 0, 0.3, {DOWN}])\nmovel(p[0.6, 0, 0.3, {DOWN}], a=1.2, v=0.25, r=0.002)\n"
            f"movel(p[0.6, 0.1, 0.3, {DOWN}], 1.2, 0.1, 0, 0)\nmovel(p[0.6, 0.2, 0.3, {DOWN}], t=2)")
    moves = run(body, tmp_path).moves[1:]
    assert [m.settings.speed_mm_s for m in moves] == [250.0, 100.0, 50.0]
    assert moves[0].settings.accuracy_mm == 2.0 and not moves[0].settings.stop_at_end
    assert moves[1].settings.stop_at_end and moves[2].settings.stop_at_end


def test_movec_through_the_via_with_orientation_to_the_target_or_fixed_to_the_path(tmp_path):
    head = f"movej(p[0.6, 0, 0.3, {DOWN}])\n"
    free = run(head + f"movec(p[0.65, 0.05, 0.3, 0, 0, 0], p[0.6, 0.1, 0.3, {DOWN}], v=0.2)", tmp_path).moves[1]
    arc = arc_through(free.start.translation_mm, free.via.translation_mm, free.end.translation_mm)
    assert np.allclose(arc.center, [600, 50, 300]) and arc.sweep == pytest.approx(math.pi)
    assert np.allclose(free.end.rotation, rot_x(math.pi))
    assert np.allclose(free.via.rotation, rot_x(math.pi))   # the tool turns start -> end; the via's is not used
    fixed = run(head + "movec(p[0.65, 0.05, 0.3, 0, 0, 0], p[0.6, 0.1, 0.3, 0, 0, 0], mode=1)", tmp_path).moves[1]
    assert np.allclose(fixed.end.rotation, rot_z(math.pi) @ rot_x(math.pi))  # turned with the half circle
    assert np.allclose(fixed.via.rotation, rot_z(math.pi / 2) @ rot_x(math.pi))  # a quarter turn at the via
    tilt = f"movec(p[0.65, 0.05, 0.3, 0, 0, 0], p[0.6, 0.1, 0.3, {math.pi / 2}, 0, 0])"
    turning = run(head + tilt, tmp_path).moves[1]   # from pointing down to pointing sideways: half-way at the via
    assert np.allclose(turning.via.rotation, rot_x(3 * math.pi / 4))


def test_movep_is_a_blended_linear_move(tmp_path):
    tp = run(f"movej(p[0.5, 0, 0.3, {DOWN}])\nmovep(p[0.6, 0, 0.3, {DOWN}], a=1.2, v=0.3, r=0.005)", tmp_path)
    assert tp.moves[1].kind == "line" and tp.moves[1].settings.accuracy_mm == 5.0


def test_movej_to_joint_values_needs_the_cell(tmp_path):
    with pytest.raises(InputError, match="prog.script:2: a target given as joint values needs the cell"):
        run("movej([0, -1.57, 1.57, -1.57, -1.57, 0], a=1.4, v=1.05)", tmp_path)
    from coatsim.robot.cell import load_cell
    from coatsim.robot.kinematics import CellKinematics

    tp = run("movej([0, 0, 0, 0, -1.5707963, 0], v=0.5)\nq = get_actual_joint_positions()\nmovej(q)", tmp_path,
             kinematics=CellKinematics(load_cell()))
    assert np.allclose(tp.moves[0].joints_rad, [0, 0, 0, 0, -1.5707963, 0]) and tp.moves[0].settings.speed_mm_s == 500
    assert np.allclose(tp.moves[1].joints_rad, tp.moves[0].joints_rad)


def test_movej_to_a_pose_through_get_inverse_kin(tmp_path):
    tp = run(f"movej(get_inverse_kin(p[0.5, 0, 0.3, {DOWN}], qnear=[0,0,0,0,0,0]), a=1.4, v=1.05)", tmp_path)
    assert tp.moves[0].kind == "joint" and list(at(tp.moves[0])) == [500, 0, 300]


def test_set_tcp_sets_the_tool_of_the_motions_after_it(tmp_path):
    tp = run(f"set_tcp(p[0, 0, 0.25, 0, 0, 0])\nmovej(p[0.5, 0, 0.3, {DOWN}])", tmp_path)
    assert np.allclose(tp.moves[0].settings.tool.offset_mm, [0, 0, 250]) and tp.tool is not None


def test_set_digital_out_switches_the_gun_from_the_next_motion(tmp_path):
    body = (f"movej(p[0.5, 0, 0.3, {DOWN}])\nset_digital_out(1, True)\nmovel(p[0.6, 0, 0.3, {DOWN}], r=0.001)\n"
            f"set_configurable_digital_out(1, True)\nmovel(p[0.7, 0, 0.3, {DOWN}])\n"
            f"set_standard_digital_out(1, False)\nmovel(p[0.8, 0, 0.3, {DOWN}])")
    tp = run(body, tmp_path)
    assert [m.spray for m in tp.moves] == [False, True, True, False]
    with pytest.raises(InputError, match=r"gun \(digital output 2\) is never on during a motion; the program "
                                         r"switches output 1, configurable output 1"):
        run(body, tmp_path, gun_signal=2, needs_spray=True)


def test_pose_functions():
    a, b = PoseValue((0.1, 0.2, 0.3, 0, 0, math.pi / 2)), PoseValue((0.01, 0, 0, 0.3, 0, 0))
    composed = pose_trans(a, b).pose()
    assert np.allclose(composed.translation_mm, [100, 210, 300])
    assert np.allclose(pose_trans(a, pose_inv(a)).pose().as_matrix4(), np.eye(4), atol=1e-12)
    added = pose_add(a, b).pose()
    assert np.allclose(added.translation_mm, [110, 200, 300])
    assert np.allclose(added.rotation, rot_z(math.pi / 2) @ rot_x(0.3))
    assert np.allclose(pose_add(b, pose_sub(a, b)).pose().as_matrix4(), a.pose().as_matrix4(), atol=1e-12)
    assert np.allclose(rotvec2rpy(rpy2rotvec([0.1, -0.2, 0.3])), [0.1, -0.2, 0.3])


def test_frames_by_pose_trans_and_variables(tmp_path):
    body = ("global frame = p[0.7, 0, 0.2, 0, 0, 1.5707963267949]\nlocal target = p[0.1, 0, 0.1, 3.14159265359, 0, 0]\n"
            "movej(pose_trans(frame, target))\ntarget[0] = 0.2\nmovel(pose_trans(frame, target), v=0.1)\n"
            "here = get_actual_tcp_pose()\nmovel(pose_add(here, p[0, 0, 0.05, 0, 0, 0]))")
    tp = run(body, tmp_path)
    assert [list(at(m)) for m in tp.moves] == [[700, 100, 300], [700, 200, 300], [700, 200, 350]]


def test_functions_with_parameters_return_values_and_globals(tmp_path):
    head = ("def offset(pose, dz=0.05):\n  return pose_add(pose, p[0, 0, dz, 0, 0, 0])\nend\n"
            "def count():\n  global calls = calls + 1\nend\n")
    body = (f"global calls = 0\nstart = p[0.5, 0, 0.3, {DOWN}]\nmovej(offset(start))\nmovel(offset(start, dz=0))\n"
            "count()\ncount()\nmovel(offset(start, calls / 10))")
    tp = run(body, tmp_path, head=head)
    assert [list(at(m)) for m in tp.moves] == [[500, 0, 350], [500, 0, 300], [500, 0, 500]]


def test_loops_and_conditions(tmp_path):
    body = (f"movej(p[0.5, 0, 0.3, {DOWN}])\ni = 0\nwhile (i < 3):\n  movel(p[0.5, 0.01 * (i + 1), 0.3, {DOWN}])\n"
            "  i = i + 1\nend\nfor k in range(0, 2):\n  if k == 0 and not False:\n"
            f"    movel(p[0.6, 0, 0.3, {DOWN}])\n  elif k == 1:\n    movel(p[0.7, 0, 0.3, {DOWN}])\n  else:\n"
            "    halt\n  end\nend\nwhile True:\n  break\nend")
    tp = run(body, tmp_path)
    assert [list(at(m))[:2] for m in tp.moves] == [[500, 0], [500, 10], [500, 20], [500, 30], [600, 0], [700, 0]]


def test_a_program_looping_forever_runs_one_cycle(tmp_path):
    tp = run(f"while (True):\n  movej(p[0.5, 0, 0.3, {DOWN}])\n  movel(p[0.6, 0, 0.3, {DOWN}])\nend", tmp_path)
    assert len(tp.moves) == 2 and any("repeats forever" in w for w in tp.warnings)


def test_sleep_rests_and_a_wait_on_an_unknown_input_is_taken_as_met(tmp_path):
    body = (f"movej(p[0.5, 0, 0.3, {DOWN}])\nmovel(p[0.6, 0, 0.3, {DOWN}], r=0.01)\nsleep(0.75)\n"
            f"while (get_standard_digital_in(3) == False):\n  sync()\nend\nmovel(p[0.7, 0, 0.3, {DOWN}])")
    tp = run(body, tmp_path)
    assert [(d.after, d.seconds) for d in tp.dwells] == [(1, 0.75)] and tp.moves[1].settings.stop_at_end
    assert any("waits for an input nobody gives" in w for w in tp.warnings)
    tp = run(body, tmp_path, inputs={3: True})
    assert len(tp.moves) == 3 and not any("nobody gives" in w for w in tp.warnings)


def test_polyscope_markers_comments_and_the_process_record(tmp_path):
    head = "# coatsim: variant=polyline-stop\n# coatsim: lead_in_mm=7\n"
    body = f'$ 1 "Robot Program"\n# a note\n$ 2 "MoveJ"\nmovej(p[0.5, 0, 0.3, {DOWN}])  # above'
    tp = run(body, tmp_path, head=head)
    assert tp.process.variant == "polyline-stop" and tp.process.lead_in_mm == 7.0 and len(tp.moves) == 1


def test_top_level_calls_run_as_written(tmp_path):
    text = f"def a():\n  movej(p[0.5, 0, 0.3, {DOWN}])\nend\ndef b():\n  movej(p[0.6, 0, 0.3, {DOWN}])\nend\nb()\na()\n"
    tp = read_text("urscript", text, tmp_path)
    assert [list(at(m))[0] for m in tp.moves] == [600, 500]
    only = read_text("urscript", text.replace("b()\na()\n", ""), tmp_path, program="b")
    assert [list(at(m))[0] for m in only.moves] == [600]


def test_values_the_controller_keeps_come_as_variables(tmp_path):
    tp = run("movej(pose_trans(feature, p[0, 0, 0.1, 3.14159265359, 0, 0]))", tmp_path,
             variables={"feature": "p[0.7, 0, 0.2, 0, 0, 0]"})
    assert list(at(tp.moves[0])) == [700, 0, 300]


@pytest.mark.parametrize("body, message", [
    ("movel(p[0.1, 0.2])", "a pose p"), ("movel(p[y, 0, 0, 0, 0, 0])", "movel\\(\\) skipped: it depends on y"),
    ("movel(p[0.1, 0, 0, 0, 0, 0], v=-1)", "v must be a number >= 0"), ("if True:\n  x = 1", "not closed"),
    ("movel(p[0.1, 0, 0, 0, 0, 0], speed=1)", "has no parameter 'speed'"), ("x = 1 / 0", "division by zero"),
    ("x = [1, 2]\nx[5] = 1", "index 5 is outside"), ("sleep(-1)", "sleep\\(\\) takes a time"),
    ("movel(p[0.1, 0, 0, 0, 0, 0]) movel", "unexpected"),
])
def test_defects_are_one_line_input_errors_naming_the_line(tmp_path, body, message):
    with pytest.raises(InputError, match=message) as info:
        run(f"movej(p[0.5, 0, 0.3, {DOWN}])\n" + body, tmp_path)
    assert "prog.script:" in str(info.value) and "\n" not in str(info.value)


def test_speed_and_force_control_are_refused_with_exit_3(tmp_path):
    with pytest.raises(ExecutionError, match="speedl .* not simulated") as info:
        run(f"movej(p[0.5, 0, 0.3, {DOWN}])\nspeedl([0.1, 0, 0, 0, 0, 0], 0.5, 1)", tmp_path)
    assert info.value.exit_code == 3


def test_set_up_calls_pass_and_unknown_functions_and_threads_are_noted(tmp_path):
    body = ("set_payload(1.5)\nset_gravity([0.0, 0.0, 9.82])\ntextmsg(\"hi\")\nmy_vendor_call(1)\n"
            f"run worker()\nmovej(p[0.5, 0, 0.3, {DOWN}])")
    head = "thread worker():\n  sleep(1)\nend\n"
    tp = run(body, tmp_path, head=head)
    assert len(tp.moves) == 1 and len(tp.warnings) == 2
