"""Interpreter: the controller model (poses, settings, stops, forward-processed signals, dwells,
joint poses, HOME) and errors with lines."""

from __future__ import annotations

import math

import numpy as np
import pytest

from coatsim.core.errors import ExecutionError, InputError
from coatsim.languages.kawasaki_as.files import read_toolpath
from coatsim.languages.kawasaki_as import interpret, interpret_run, parse_as
from coatsim.geometry.space.primitives import arc_through
from coatsim.path.arcs import move_length
from coatsim.languages.kawasaki_as.motion import FULL_SPEED_MM_S
from coatsim.geometry.space.rotations import oat_to_matrix
from coatsim.path.process import ProcessInfo
from coatsim.path.toolpath import CircularMove, JointMove, LinearMove

TRANS = """.TRANS
a 0 0 0 0 180 0
b 100 0 0 0 180 0
c 100 100 0 0 180 0
v 170.7106781 29.2893219 0 0 180 0
e 200 100 0 0 180 0
.END
"""


def run(body: str, trans: str = TRANS, **kw):
    return interpret(parse_as(".PROGRAM t()\n" + body + ".END\n" + trans, "t.as"), **kw)


def test_reference_example_a_draws_the_rounded_square():
    """Example A of the reference (SHIFT of a POINT origin, % and MM/S speeds, TWAIT)."""
    text = """.PROGRAM sq_round()
  BASE NULL
  TOOL TRANS(0,0,150,0,0,0)
  POINT org = TRANS(500,-100,200,0,180,0)
  SPEED 30 ALWAYS
  ACCURACY 10 ALWAYS
  CP ON
  JMOVE SHIFT(org BY 20,0,50)
  ACCURACY 1 ALWAYS
  SPEED 100 MM/S ALWAYS
  LMOVE SHIFT(org BY 20,0,0)
  BREAK
  SIGNAL 5
  TWAIT 0.2
  LMOVE SHIFT(org BY 180,0,0)
  C1MOVE SHIFT(org BY 194.142,5.858,0)
  C2MOVE SHIFT(org BY 200,20,0)
  LMOVE SHIFT(org BY 200,180,0)
  C1MOVE SHIFT(org BY 194.142,194.142,0)
  C2MOVE SHIFT(org BY 180,200,0)
  LMOVE SHIFT(org BY 20,200,0)
  C1MOVE SHIFT(org BY 5.858,194.142,0)
  C2MOVE SHIFT(org BY 0,180,0)
  LMOVE SHIFT(org BY 0,20,0)
  C1MOVE SHIFT(org BY 5.858,5.858,0)
  C2MOVE SHIFT(org BY 20,0,0)
  BREAK
  SIGNAL -5
  LDEPART 50
.END
"""
    tp = interpret(parse_as(text), gun_signal=5)
    assert [m.kind for m in tp.moves] == ["joint", "line", "line", "arc", "line", "arc", "line", "arc", "line", "arc", "line"]
    assert tp.moves[0].start is None and tp.moves[0].settings.speed_mm_s == pytest.approx(0.3 * FULL_SPEED_MM_S)
    assert tp.moves[0].settings.accuracy_mm == 10.0 and tp.moves[1].settings.accuracy_mm == 1.0
    assert [m.spray for m in tp.moves] == [False, False] + [True] * 8 + [False]
    assert tp.moves[1].settings.stop_at_end and tp.moves[9].settings.stop_at_end
    arcs = [m for m in tp.moves if isinstance(m, CircularMove)]
    for arc in arcs:
        c = arc_through(arc.start.translation_mm, arc.via.translation_mm, arc.end.translation_mm)
        assert c.radius == pytest.approx(20.0, abs=2e-3) and c.sweep == pytest.approx(math.pi / 2, abs=1e-4)
    sprayed = sum(move_length(m) for m in tp.spray_moves)
    assert sprayed == pytest.approx(4 * 160 + 2 * math.pi * 20, abs=0.01)
    depart = tp.moves[-1]
    assert np.allclose(depart.end.translation_mm, [520, -100, 250])   # tool z points down: depart goes up
    np.testing.assert_allclose(tp.tool.offset_mm, [0, 0, 150])
    np.testing.assert_allclose(tp.tool.rotation, np.eye(3), atol=1e-15)


def test_signal_after_break_switches_at_the_next_move():
    tp = run("  JMOVE a\n  LMOVE b\n  BREAK\n  SIGNAL 1\n  LMOVE c\n  BREAK\n  SIGNAL -1\n  LMOVE a\n")
    assert [m.spray for m in tp.moves] == [False, False, True, False]


def test_signal_without_break_switches_as_the_previous_move_starts():
    tp = run("  JMOVE a\n  LMOVE b\n  SIGNAL 1\n  LMOVE c\n  SIGNAL -1\n  LMOVE a\n")
    assert [m.spray for m in tp.moves] == [False, True, False, False]


@pytest.mark.parametrize("cp", ["ON", "OFF"])
def test_seam_pattern_sprays_exactly_the_moves_between_the_signals(cp):
    """The closed-contour pattern of the writer (pinned: the robot stage and the coat rely on it):
    a SIGNAL right after a motion switches the gun as that motion starts, under CP ON and CP OFF
    alike, for an arc as for a line, and a SIGNAL never makes the robot stop."""
    body = (f"  CP {cp}\n  JMOVE a\n  LMOVE b\n  BREAK\n  LMOVE c\n  C1MOVE v\n  C2MOVE e\n  SIGNAL 1\n"
            "  LMOVE b\n  LMOVE a\n  SIGNAL -1\n  BREAK\n  LDEPART 10\n")
    tp = run(body)
    assert [m.kind for m in tp.moves] == ["joint", "line", "line", "arc", "line", "line", "line"]
    assert [m.spray for m in tp.moves] == [False, False, False, True, True, False, False]
    stops = [m.settings.stop_at_end for m in tp.moves]
    assert stops == ([False, True, False, False, False, True, True] if cp == "ON" else [True] * 7)


def test_signal_switches_once_per_motion_and_the_last_state_wins():
    tp = run("  JMOVE a\n  LMOVE b\n  SIGNAL 1\n  SIGNAL -1\n  LMOVE c\n  SIGNAL 1\n  TWAIT 0.5\n  SIGNAL 1\n  LMOVE a\n")
    assert [m.spray for m in tp.moves] == [False, False, True, True]


def test_signal_before_any_motion_and_other_outputs():
    tp = run("  SIGNAL 1, 7\n  JMOVE a\n  SIGNAL -7\n  LMOVE b\n")
    assert [m.spray for m in tp.moves] == [True, True]
    assert [m.spray for m in run("  SIGNAL 2\n  JMOVE a\n  LMOVE b\n", gun_signal=2).moves] == [True, True]
    assert not any(m.spray for m in run("  SIGNAL 2\n  JMOVE a\n  LMOVE b\n").moves)


def test_stop_at_end_from_break_cp_off_fine_delay_and_program_end():
    tp = run("  JMOVE a\n  LMOVE b\n  BREAK\n  LMOVE c\n  CP OFF\n  LMOVE b\n  CP ON\n  ACCURACY 1 FINE\n"
             "  LMOVE c\n  LMOVE b\n  DELAY 1\n  LMOVE c\n  TWAIT 1\n  LMOVE b\n  LMOVE a\n")
    stops = [m.settings.stop_at_end for m in tp.moves]
    assert stops == [False, True, False, True, True, True, False, False, True]
    assert [m.settings.cp for m in tp.moves][3:5] == [False, True]


def test_speed_and_accuracy_once_and_always():
    tp = run("  SPEED 200 MM/S ALWAYS\n  ACCURACY 5 ALWAYS\n  JMOVE a\n  SPEED 50 MM/S\n  ACCURACY 0\n"
             "  LMOVE b\n  LMOVE c\n  SPEED 6000 MM/MIN\n  LMOVE b\n  SPEED 4 S\n  LMOVE c\n  SPEED 50\n  LMOVE b\n")
    assert [m.settings.speed_mm_s for m in tp.moves] == pytest.approx([200, 50, 200, 100, 25, 0.5 * FULL_SPEED_MM_S])
    assert [m.settings.accuracy_mm for m in tp.moves] == [5, 0, 5, 5, 5, 5]


def test_speed_in_seconds_on_an_arc_uses_the_arc_length():
    tp = run("  JMOVE b\n  SPEED 2 S\n  C1MOVE v\n  C2MOVE e\n")
    arc = tp.moves[1]
    assert arc.settings.speed_mm_s == pytest.approx(math.pi / 2 * 100 / 2, rel=1e-6)


def test_reals_shift_compose_base_and_point():
    trans = ".TRANS\na 10 20 30 90 180 0\n.END\n.REALS\nd = 5\n.END\n"
    tp = run("  POINT q = SHIFT(a BY 1, 2, 3)\n  JMOVE q\n  LMOVE a + TRANS(0, 0, d, 0, 0, 0)\n"
             "  BASE TRANS(1000, 0, 0, 90, 0, 0)\n  LMOVE a\n  JAPPRO a, -d\n", trans=trans)
    assert np.allclose(tp.moves[0].target.translation_mm, [11, 22, 33])
    # a + TRANS(0,0,5): 5 mm along a's tool z, which points down.
    assert np.allclose(tp.moves[1].end.translation_mm, [10, 20, 25])
    # BASE rotates a by 90 deg about z and moves it by 1000 mm along x.
    assert np.allclose(tp.moves[2].end.translation_mm, [1000 - 20, 10, 30])
    assert np.allclose(tp.moves[2].end.rotation, oat_to_matrix(90, 0, 0) @ oat_to_matrix(90, 180, 0))
    assert np.allclose(tp.moves[3].target.translation_mm, [980, 10, 25])   # negative distance: towards the tool


def test_appro_depart_draw_tdraw():
    trans = ".TRANS\na 0 0 0 0 90 0\n.END\n"  # tool z along base +x
    tp = run("  JAPPRO a, 10\n  LAPPRO a, 4\n  LMOVE a\n  LDEPART 7\n  DRAW 1, 2, 3\n  TDRAW 0, 0, 5\n  JDEPART 1\n", trans=trans)
    xs = [m.target.translation_mm if isinstance(m, JointMove) else m.end.translation_mm for m in tp.moves]
    assert np.allclose(xs, [[-10, 0, 0], [-4, 0, 0], [0, 0, 0], [-7, 0, 0], [-6, 2, 3], [-1, 2, 3], [-2, 2, 3]])
    assert isinstance(tp.moves[1], LinearMove) and isinstance(tp.moves[6], JointMove)


def test_circle_through_three_poses():
    tp = run("  JMOVE b\n  C1MOVE v\n  C2MOVE e\n")
    c = arc_through(*(p.translation_mm for p in (tp.moves[1].start, tp.moves[1].via, tp.moves[1].end)))
    assert np.allclose(c.center, [100, 100, 0], atol=1e-6) and c.radius == pytest.approx(100.0)
    assert c.sweep == pytest.approx(math.pi / 2, abs=1e-8) and np.allclose(c.normal, [0, 0, 1])


def test_metadata_and_program_selection():
    text = ".PROGRAM a()\n  ; coatsim: lead_in_mm=12.5\n  JMOVE p\n.END\n.PROGRAM b()\n  JMOVE p\n  LMOVE q\n.END\n" \
           ".TRANS\np 0 0 0 0 0 0\nq 1 0 0 0 0 0\n.END\n"
    f = parse_as(text)
    assert interpret(f).process == ProcessInfo(lead_in_mm=12.5)
    assert len(interpret(f, program="B").moves) == 2
    with pytest.raises(InputError, match="no program named 'c'"):
        interpret(f, program="c")


# (body, line named in the error, words)
SEMANTIC_ERRORS = [
    ("  LMOVE a\n", 2, "needs a known start pose"),
    ("  JMOVE a\n  C2MOVE b\n", 3, "C2MOVE without a C1MOVE"),
    ("  JMOVE a\n  C1MOVE b\n  LMOVE c\n", 3, "C1MOVE must be followed by C2MOVE"),
    ("  JMOVE a\n  C1MOVE b\n", 3, "C1MOVE at the end of the program"),
    ("  JMOVE a\n  C1MOVE b\n  C2MOVE SHIFT(b BY 100, 0, 0)\n", 4, "lie on one line"),
    ("  JMOVE a\n  C1MOVE a\n  C2MOVE b\n", 4, "not distinct"),
    ("  SPEED 0 MM/S\n", 2, "SPEED must be > 0"),
    ("  ACCURACY -1\n", 2, "ACCURACY must be >= 0"),
    ("  TWAIT -1\n", 2, "time must be >= 0"),
]


@pytest.mark.parametrize("body,line,words", SEMANTIC_ERRORS)
def test_errors_name_the_line(body, line, words):
    with pytest.raises(InputError) as info:
        run(body)
    assert str(info.value).startswith(f"t.as:{line}: "), str(info.value)
    assert words in str(info.value)


def test_no_program_and_bad_gun():
    with pytest.raises(InputError, match="no .PROGRAM section"):
        interpret(parse_as(TRANS, "t.as"))
    with pytest.raises(InputError, match="gun signal"):
        run("  JMOVE a\n", gun_signal=0)


def test_read_toolpath_file_errors(tmp_path):
    with pytest.raises(InputError, match="missing.as: no such file"):
        read_toolpath(tmp_path / "missing.as")
    bad = tmp_path / "bad.as"
    bad.write_text(".PROGRAM x()\n  JMOVE a\n  LMOVE nowhere\n.END\n" + TRANS)
    with pytest.raises(InputError, match=r"bad\.as:3: LMOVE skipped: pose nowhere has no value"):
        read_toolpath(bad)


# --- joint poses and HOME use the cell's kinematics ----------------------------------------
@pytest.fixture(scope="module")
def kin():
    from coatsim.robot.cell import load_cell
    from coatsim.robot.kinematics import CellKinematics

    return CellKinematics(load_cell())


def test_joint_poses_and_home_with_the_cell(kin):
    trans = TRANS + ".JOINTS\n#j 10 0 35 0 55 0\n.END\n"
    tp = run("  JMOVE #j\n  HERE .p\n  LMOVE SHIFT(.p BY 0, 0, -20)\n  JMOVE #[0, 0, 35, 0, 55, 0]\n  HOME\n"
             "  LMOVE #j\n", trans=trans, kinematics=kin)
    j0, line, j1, home, lin = tp.moves
    assert isinstance(j0, JointMove) and np.allclose(np.degrees(j0.joints_rad), [10, 0, 35, 0, 55, 0])
    assert np.allclose(j0.target.translation_mm, kin.forward(j0.joints_rad).translation_mm)
    assert np.allclose(line.start.translation_mm, j0.target.translation_mm)
    assert np.allclose(line.end.translation_mm, j0.target.translation_mm - [0, 0, 20])
    assert np.allclose(home.joints_rad, kin.home(1)) and np.allclose(j1.joints_rad, kin.home(1))
    assert isinstance(lin, LinearMove) and np.allclose(lin.end.translation_mm, j0.target.translation_mm)


def test_start_pose_is_home_with_the_cell(kin):
    tp = run("  LMOVE a\n", kinematics=kin)
    assert np.allclose(tp.moves[0].start.translation_mm, kin.forward(kin.home(1)).translation_mm)


@pytest.mark.parametrize("body,kind,words", [
    ("  JMOVE #[0, 0, 35, 0, 55, 400]\n", ExecutionError, "outside the cell's range"),
    ("  JMOVE #[0, 0, 35]\n", InputError, "needs 6 values"),
])
def test_joint_pose_errors(kin, body, kind, words):
    with pytest.raises(kind) as info:
        run(body, kinematics=kin)
    assert words in str(info.value) and str(info.value).startswith("t.as:")


def test_here_into_a_joint_value_after_a_cartesian_motion_keeps_the_pose(kin):
    tp = run("  JMOVE a\n  LMOVE b\n  HERE #j\n  LMOVE c\n  JMOVE #j\n", kinematics=kin)
    assert np.allclose(tp.moves[-1].target.translation_mm, tp.moves[1].end.translation_mm) and tp.moves[-1].joints_rad is None


@pytest.mark.parametrize("where", ["#DEST", "#HERE"])
def test_dest_after_a_cartesian_motion_is_where_the_robot_is_as_here(kin, where):
    """#DEST (and #HERE) after a Cartesian motion keep the pose as HERE #j does: a JMOVE moves
    there, a POINT copies it; DECOMPOSE of its angles is skipped with a note (no stop)."""
    result = interpret_run(parse_as(".PROGRAM m()\n  JMOVE a\n  LMOVE b\n  POINT #j = " + where + "\n  LMOVE c\n"
                                    f"  JMOVE #j\n  JMOVE {where}\n  DECOMPOSE j[1] = {where}\n.END\n" + TRANS, "t.as"),
                           kinematics=kin)
    tp = result.toolpath
    assert np.allclose(tp.moves[3].target.translation_mm, tp.moves[1].end.translation_mm)
    assert np.allclose(tp.moves[4].target.translation_mm, tp.moves[1].end.translation_mm)
    assert result.skipped == (f"t.as:8: DECOMPOSE skipped: the joint angles of {where} (taken from a pose) need the "
                              "arm's inverse kinematics",)


def test_hmove_is_a_joint_move_to_its_pose_and_what_follows_starts_there(kin):
    """HMOVE (hybrid interpolation) ends at its pose: a joint move there (a note), so a relative
    move after it starts from that pose, not from the one before."""
    tp = run("  JMOVE a\n  HMOVE b\n  LDEPART 50\n  HMOVE #[0, 0, 35, 0, 55, 0]\n", kinematics=kin)
    hmove, depart, joints = tp.moves[1], tp.moves[2], tp.moves[3]
    assert hmove.kind == "joint" and np.allclose(depart.start.translation_mm, hmove.target.translation_mm)
    assert np.allclose(joints.joints_rad, np.radians([0, 0, 35, 0, 55, 0]))
    assert any("HMOVE (hybrid interpolation) is taken as a joint move to its pose" in w for w in tp.warnings)


def test_drive_turns_one_joint_from_where_the_arm_is(kin):
    """DRIVE joint, angle[, speed] is a joint move turning that joint by the angle; where the
    arm's joint angles are unknown (after a Cartesian motion) it is skipped with a note."""
    result = interpret_run(parse_as(".PROGRAM t()\n  JMOVE #[0, 0, 35, 0, 55, 0]\n  DRIVE 1, 30\n  DRIVE 6, -10, 50\n"
                                    "  LMOVE a\n  DRIVE 2, 5\n.END\n" + TRANS, "t.as"), kinematics=kin)
    moves = result.toolpath.moves
    assert np.allclose(moves[1].joints_rad, np.radians([30, 0, 35, 0, 55, 0]))
    assert np.allclose(moves[2].joints_rad, np.radians([30, 0, 35, 0, 55, -10]))
    assert np.allclose(moves[2].target.translation_mm, kin.forward(np.radians([30, 0, 35, 0, 55, -10])).translation_mm)
    assert len(moves) == 4 and result.skipped[0].startswith(
        "t.as:6: DRIVE skipped: DRIVE after a motion to a transformation (line 5) is not simulated: it turns a joint "
        "from the angles the arm has there, which only the arm's inverse kinematics tells")
    assert "reach that pose with JMOVE to a joint value (#...) before the DRIVE" in result.skipped[0]
    assert result.unsimulated == result.skipped
    with pytest.raises(InputError, match="DRIVE joint 7: this six-axis arm has joints 1 to 6"):
        run("  JMOVE #[0, 0, 35, 0, 55, 0]\n  DRIVE 7, 10\n", kinematics=kin)


def test_drive_before_any_motion_turns_a_joint_from_home(kin):
    """A DRIVE that opens the program turns a joint from where every program starts (the cell's
    home), not skipped for want of joint angles; without a cell it asks for a first motion."""
    tp = run("  DRIVE 1, 20\n  LMOVE a\n", kinematics=kin)
    home = kin.home(1).copy()
    home[0] += np.radians(20)
    assert tp.moves[0].kind == "joint" and np.allclose(tp.moves[0].joints_rad, home)
    with pytest.raises(InputError, match="DRIVE needs a known start pose"):
        run("  DRIVE 1, 20\n")


# --- what the twin cannot simulate: one line, exit 3 ----------------------------------------
@pytest.mark.parametrize("body,words", [
    ("  HOME\n", "needs the cell's kinematics"), ("  JMOVE #[0, 0, 0, 0, 0, 0]\n", "needs the cell's kinematics"),
])
def test_unsimulated_is_one_line_exit_3(body, words):
    with pytest.raises(ExecutionError) as info:
        run(body)
    assert words in str(info.value) and str(info.value).startswith("t.as:") and "\n" not in str(info.value)


@pytest.mark.parametrize("body,words", [
    ("  JMOVE a\n  DRAW 1, 0, 0, 0, 10, 0\n", "t.as:3: DRAW skipped: DRAW with a rotation is not simulated"),
    ("  JMOVE a\n  LMOVE b\n  BRAKE\n", "t.as:4: BRAKE skipped: BRAKE stops the motion"),
    ("  PULSE 1, 0.5\n  JMOVE a\n", "t.as:2: PULSE skipped: PULSE of the gun (output 1) is not simulated: the gun "
     "would spray for 0.5 s from here, over whatever motion runs then; switch the gun with SIGNAL 1 ... SIGNAL -1"),
    ("  SPEED 30 DEG/S\n  JMOVE a\n", "t.as:2: SPEED skipped: SPEED in DEG/S (a rotation speed) is not simulated"),
])
def test_what_the_twin_does_not_simulate_is_read_and_refused_by_a_simulation(body, words):
    """Reading goes on past it (a note); what simulates refuses it: one line, exit 3."""
    done = interpret_run(parse_as(".PROGRAM t()\n" + body + ".END\n" + TRANS, "t.as"))
    assert done.skipped[0].startswith(words) and done.unsimulated == done.skipped
    with pytest.raises(ExecutionError) as info:
        done.require_complete()
    assert str(info.value).startswith(words) and "\n" not in str(info.value)


@pytest.mark.parametrize("gun,signal,problem", [
    (1, "1", "/t.as:3: the sprayed path read lacks the 2 s the PULSE of the gun (output 1) sprays"),
    (9, "do.gun", "/t.as:3: the sprayed path read lacks the 2 s the PULSE of the gun (output 9) sprays"),
])
def test_a_pulse_of_the_gun_is_a_problem_of_the_reading(tmp_path, gun, signal, problem):
    """check-program does not say "no problems found" of a program whose gun is pulsed (output 1,
    or the --gun output named by a .REALS constant): its spray is missing from the path read."""
    from program_helpers import check_as

    path = tmp_path / "t.as"
    path.write_text(f".PROGRAM t()\n  JMOVE a\n  PULSE {signal}, 2\n  LMOVE b\n.END\n" + TRANS
                    + ".REALS\ndo.gun = 9\n.END\n")
    checked = check_as([path], gun_signal=gun)
    assert any(p.endswith(problem) for p in checked.problems), checked.problems
    assert any(f"t.as:3: PULSE skipped: PULSE of the gun (output {gun}) is not simulated" in s
               for s in checked.skipped), checked.skipped


def test_dlysig_of_the_gun_switches_it_where_the_program_reaches_it():
    """DLYSIG of the gun output is a switch (its delay not timed, a note), as SIGNAL would be:
    dropped, the gun stayed on through the depart."""
    done = interpret_run(parse_as(".PROGRAM t()\n  JMOVE a\n  BREAK\n  DLYSIG 1, 0.1\n  LMOVE b\n  BREAK\n"
                                  "  DLYSIG -1, 0.05\n  LDEPART 50\n.END\n" + TRANS, "t.as"))
    assert [m.spray for m in done.toolpath.moves] == [False, True, False] and done.skipped == ()
    assert not done.gun_on_at_end
    assert "t.as:7: DLYSIG -1: the delay is not timed; the gun switches here, as SIGNAL -1 would" in done.toolpath.warnings


def test_brake_at_rest_does_nothing():
    assert len(run("  JMOVE a\n  BREAK\n  BRAKE\n  LMOVE b\n").moves) == 2


# --- dwells: TWAIT, DELAY, STABLE ----------------------------------------------------------
def test_twait_after_break_is_a_dwell_with_the_gun_state():
    tp = run("  SPEED 100 MM/S ALWAYS\n  JMOVE a\n  LMOVE b\n  BREAK\n  SIGNAL 1\n  TWAIT 0.5\n  LMOVE c\n  SIGNAL -1\n")
    assert [(d.after, d.seconds, d.spray, d.line) for d in tp.dwells] == [(1, 0.5, True, 7)]
    assert tp.moves[1].settings.stop_at_end


def test_twait_counts_from_the_start_of_the_motion():
    # b -> c is 100 mm at 100 mm/s: a 0.4 s wait is over before the arm arrives, a 1.5 s one is not
    short = run("  SPEED 100 MM/S ALWAYS\n  JMOVE b\n  LMOVE c\n  TWAIT 0.4\n  LMOVE e\n")
    assert short.dwells == () and not short.moves[1].settings.stop_at_end
    long = run("  SPEED 100 MM/S ALWAYS\n  JMOVE b\n  LMOVE c\n  TWAIT 1.5\n  SIGNAL 1\n  LMOVE e\n")
    (d,) = long.dwells
    assert d.after == 1 and d.seconds == pytest.approx(0.5) and not d.spray and long.moves[1].settings.stop_at_end
    assert [m.spray for m in long.moves] == [False, False, True]   # the switch waits for the rest to end


def test_delay_is_a_motion_step_and_a_following_switch_sprays_it():
    tp = run("  JMOVE a\n  LMOVE b\n  DELAY 2\n  SIGNAL 1\n  LMOVE c\n  STABLE 1\n")
    assert [(d.after, d.seconds, d.spray) for d in tp.dwells] == [(1, 2.0, True), (2, 1.0, True)]
    assert [m.spray for m in tp.moves] == [False, False, True]


def test_twait_before_any_motion_leaves_no_dwell():
    assert run("  TWAIT 3\n  JMOVE a\n").dwells == ()


def test_speed_units_and_xmove():
    tp = run("  JMOVE a\n  SPEED 5 CM/S\n  LMOVE b\n  SPEED 60 CM/MIN\n  XMOVE c TILL 1001\n")
    assert [m.settings.speed_mm_s for m in tp.moves[1:]] == pytest.approx([50.0, 10.0])
    assert any("XMOVE" in w for w in tp.warnings)


def test_draw_with_empty_components_and_tdraw_in_tool_axes():
    tp = run("  JMOVE a\n  DRAW , 10\n  TDRAW ,,5\n")
    assert np.allclose(tp.moves[1].end.translation_mm, [0, 10, 0]) and np.allclose(tp.moves[2].end.translation_mm, [0, 10, -5])


def test_joint_poses_are_read_with_the_tool_in_force(kin):
    """The controller's TCP for a joint value is the flange times the TOOL: a TOOL 50 mm longer
    than the gun puts it 50 mm further along the tool axis."""
    trans = TRANS + ".JOINTS\n#j 10 0 35 0 55 0\n.END\n"
    gun = run("  JMOVE #j\n", trans=trans, kinematics=kin).moves[0].target
    same = run("  TOOL TRANS(0, 0, 250)\n  JMOVE #j\n", trans=trans, kinematics=kin).moves[0].target
    longer = run("  TOOL TRANS(0, 0, 300)\n  JMOVE #j\n", trans=trans, kinematics=kin).moves[0].target
    assert np.allclose(same.translation_mm, gun.translation_mm) and np.allclose(same.rotation, gun.rotation)
    assert np.allclose(longer.translation_mm, gun.translation_mm + 50.0 * gun.rotation[:, 2])
