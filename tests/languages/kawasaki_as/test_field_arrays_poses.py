"""Whole arrays passed to a subprogram (``CALL trace.part(.&p.rel[,])``, ``CALL tcp.send.pc(.$data[],
1)``), local string arrays, ``POINT .#j = .pose, #ref``, and the pose functions of the index
(AVE_TRANS, TOOL, BASE), in every author's style."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from coatsim.geometry.space.xyzoat import pose_from_xyzoat
from coatsim.languages.kawasaki_as import ast, parse_as
from coatsim.languages.kawasaki_as.interpreter import Interpreter
from coatsim.languages.kawasaki_as.values import average

from styles import STYLES, ends, notes, run_text, styled

REL = (".TRANS\nfixture 650 0 280 0 0 0\np.rel[1,1] -40 -40 0 0 180 0\np.rel[1,2] 40 -40 0 0 180 0\n"
       "p.rel[2,1] 40 40 0 0 180 0\np.rel[2,2] -40 40 0 0 180 0\n.END\n")
TRACE = (".PROGRAM trace.part(.&r[,])\n  LMOVE fixture + .r[1,1]\n  SIGNAL 1\n  LMOVE fixture + .r[1,2]\n"
         "  LMOVE fixture + .r[2,1]\n  LMOVE fixture + .r[2,2]\n  SIGNAL -1\n  POINT .r[3,1] = fixture\n.END\n")


@pytest.mark.parametrize("style", STYLES)
def test_a_whole_pose_array_goes_to_a_subprogram_and_back(style):
    body = ("FOR .i = 1 TO 2\nFOR .j = 1 TO 2\nPOINT .p.rel[.i,.j] = p.rel[.i,.j]\nEND\nEND\n"
            "JMOVE fixture + .p.rel[1,1]\nCALL trace.part(.&p.rel[,])\nLMOVE .p.rel[3,1]")
    run = run_text(styled(body, style, REL, extra=TRACE))
    xy = [tuple(np.round(p.translation_mm[:2]).astype(int)) for p in ends(run)]
    assert xy == [(610, -40), (610, -40), (690, -40), (690, 40), (610, 40), (650, 0)]
    assert run.skipped == () and run.unknowns == () and len(run.toolpath.spray_moves) == 3


@pytest.mark.parametrize("style", STYLES)
def test_a_string_array_by_value_is_a_copy(style):
    body = '.$data[1] = "READY"\n.$data[2] = "v1.2"\nCALL tcp.send.pc(.$data[], 2)\n$back = .$data[1]'
    extra = (".PROGRAM tcp.send.pc(.$msg[], .n)\n  .$line = \"\"\n  FOR .i = 1 TO .n\n"
             "    .$line = .$line + .$msg[.i] + \";\"\n  END\n  $sent = .$line\n  .$msg[1] = \"CHANGED\"\n.END\n")
    f = parse_as(styled(body, style, extra=extra), "f.as")
    run = Interpreter((f,), 1, {}, None, 1000.0, 100_000)
    run.run(f.programs[0])
    sent, back = run.globals.get("string", "$sent"), run.globals.get("string", "$back")
    assert (sent, back) == ("READY;v1.2;", "READY")


def test_whole_arrays_parse_only_as_call_arguments():
    f = parse_as(".PROGRAM t(.&a[,], .$m[], .n)\n  CALL u(.&p.rel[,], .$data[], &q[], x[1])\n.END\n", "f.as")
    (call,) = f.programs[0].body
    assert [p.name for p in f.programs[0].params] == [".a", ".$m", ".n"]
    assert call.args == (ast.Ref(ast.Name(".p.rel", (), True)), ast.Name(".$data", (), True),
                         ast.Ref(ast.Name("q", (), True)), ast.Name("x", (ast.Num(1.0),)))
    with pytest.raises(Exception, match="expected an array index in a"):
        parse_as(".PROGRAM t()\n  x = a[]\n.END\n", "f.as")


def test_an_array_never_filled_arrives_empty_and_its_elements_are_unknown():
    run = run_text(".PROGRAM t()\n  CALL u(.&pos[,])\n  JMOVE .pos[1,1]\n.END\n.PROGRAM u(.&p[,])\n  x = 1\n.END\n")
    assert run.skipped == ("f.as:3: JMOVE skipped: pose .pos[1,1] has no value",)


# --- POINT #j = pose, #ref ----------------------------------------------------------------------
@pytest.fixture(scope="module")
def kin():
    from coatsim.robot.cell import load_cell
    from coatsim.robot.kinematics import CellKinematics

    return CellKinematics(load_cell())


@pytest.mark.parametrize("style", STYLES)
def test_a_joint_value_from_a_pose_and_a_reference_moves_to_the_pose(style, kin):
    body = ("POINT .app = SHIFT(s1 BY 0, 0, 50)\nPOINT .#app = .app, #cfg\nJMOVE .#app\nLMOVE s1\n"
            "POINT #back = s1, #cfg\nJMOVE #back\nPOINT .q = #back\nLMOVE SHIFT(.q BY 10, 0, 0)")
    data = ".TRANS\ns1 650 -80 260 0 180 0\n.END\n.JOINTS\n#cfg 0 10 40 0 50 0\n.END\n"
    run = run_text(styled(body, style, data), kinematics=kin)
    assert [m.kind for m in run.toolpath.moves] == ["joint", "line", "joint", "line"]
    assert np.allclose([p.translation_mm for p in ends(run)], [[650, -80, 310], [650, -80, 260], [650, -80, 260],
                                                         [660, -80, 260]])
    assert run.toolpath.moves[0].joints_rad is None  # the cell's inverse kinematics solves it
    assert "the cell's inverse kinematics picks the configuration, not the reference" in notes(run)
    assert run.skipped == ()


def test_point_with_a_reference_parses_and_checks_its_target():
    f = parse_as(".PROGRAM t()\n  POINT .#j = .pose, #ref\n.END\n", "f.as")
    assert f.programs[0].body == (ast.PointAssign(2, ast.Name(".#j"), ast.Name(".pose"), None, ast.Name("#ref")),)
    with pytest.raises(Exception, match="the reference joint value picks the configuration of a joint value"):
        parse_as(".PROGRAM t()\n  POINT p = q, #ref\n.END\n", "f.as")


def test_the_angles_of_a_joint_value_from_a_pose_are_unknown(kin):
    run = run_text(".PROGRAM t()\n  POINT #j = TRANS(600, 0, 300, 0, 180, 0)\n  x = DEXT(#j, 2)\n  JMOVE #j\n.END\n",
                   kinematics=kin)
    assert len(run.toolpath.moves) == 1
    assert "need the arm's inverse kinematics" in run.skipped[0] and run.skipped[0].startswith("f.as:3: assignment")


# --- pose functions -------------------------------------------------------------------------
def test_ave_trans_is_the_midpoint_with_the_rotation_halfway():
    a, b = pose_from_xyzoat((600, -60, 250, 0, 180, 0)), pose_from_xyzoat((760, 80, 270, 90, 150, 0))
    m = average(a, b)
    assert np.allclose(m.translation_mm, [680, 10, 260])
    half = (Rotation.from_matrix(a.rotation).inv() * Rotation.from_matrix(m.rotation)).magnitude()
    whole = (Rotation.from_matrix(a.rotation).inv() * Rotation.from_matrix(b.rotation)).magnitude()
    assert half == pytest.approx(whole / 2) and np.allclose(average(a, a).rotation, a.rotation)
    run = run_text(".PROGRAM t()\n  POINT .m = AVE_TRANS(a, b)\n  JMOVE .m\n.END\n"
                   ".TRANS\na 600 -60 250 0 180 0\nb 760 80 270 90 150 0\n.END\n")
    assert np.allclose(ends(run)[0].translation_mm, [680, 10, 260]) and np.allclose(ends(run)[0].rotation, m.rotation)


def test_tool_and_base_as_values_are_the_frames_in_force():
    run = run_text(".PROGRAM t()\n  TOOL TRANS(0, 0, 200)\n  BASE TRANS(100, 0, 0)\n  POINT .t = TOOL\n"
                   "  POINT .b = base\n"
                   "  JMOVE .b + TRANS(500, 0, DZ(.t), 0, 180, 0)\n.END\n")
    assert np.allclose(ends(run)[0].translation_mm, [700, 0, 200]) and run.unknowns == ()
    before = run_text(".PROGRAM t()\n  POINT .t = TOOL\n  JMOVE TRANS(600, 0, 300, 0, 180, 0)\n.END\n")
    assert before.skipped == ("f.as:2: POINT skipped: pose TOOL has no value",)


@pytest.mark.parametrize("call,words", [
    ("TRADD(a, b)", "TRADD is not simulated; it gives no pose"), ("CCENTER(a, b, a)", "CCENTER is not simulated"),
    ("STRTOPOS(\"1,2,3\")", "STRTOPOS is not simulated"), ("zz.pose(1)", "ZZ.POSE is not a function of the AS index"),
])
def test_pose_functions_the_twin_does_not_compute_give_no_pose(call, words):
    run = run_text(f".PROGRAM t()\n  JMOVE a\n  LMOVE {call}\n.END\n"
                   ".TRANS\na 600 0 300 0 180 0\nb 0 0 10 0 0 0\n.END\n")
    assert len(run.toolpath.moves) == 1 and words in notes(run) and run.skipped[0].startswith("f.as:3: LMOVE skipped")


def test_existence_functions_of_the_index():
    f = parse_as('.PROGRAM t()\n  cnt = 1\n  .loc = 2\n  a = EXISTINTEGER("cnt") + EXISTDATA("p") * 10 + '
                 'EXISTLOCALREAL("loc") * 100 + EXISTLOCALREAL("cnt") * 1000 + EXISTDATA("none") * 10000 + '
                 'MSPEED2 + WHICHTASK\n.END\n.TRANS\np 1 2 3 0 0 0\n.END\n', "f.as")
    run = Interpreter((f,), 1, {}, None, 1000.0, 100_000)
    run.run(f.programs[0])
    assert run.globals.get("real", "a") == -1 - 10 - 100 + 100 + 1
