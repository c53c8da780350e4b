"""TOOL and BASE at any point of a program: what the interpreter hands the robot stage.

Pinned semantics (the robot stage builds on them): every motion carries the TOOL in force
(``MotionSettings.tool``: the controller's TCP in the flange frame, with its source line; None
before any TOOL); a TOOL after motion stops that motion (like BREAK) and re-expresses the
current pose with the new TCP, the flange unmoved; BASE applies to every pose evaluated after
it, positions and orientations alike.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from coatsim.languages.kawasaki_as import interpret, parse_as
from coatsim.geometry.space.rotations import oat_to_matrix
from coatsim.path.tool_frames import gun_in_tcp, tool_mismatches

TRANS = """.TRANS
a 500 0 300 0 180 0
b 600 0 300 0 180 0
c 600 100 300 0 180 0
.END
"""


def run(body: str, trans: str = TRANS):
    return interpret(parse_as(".PROGRAM t()\n" + body + ".END\n" + trans, "t.as"))


def test_every_motion_carries_the_tool_in_force_and_its_line():
    tp = run("  JMOVE a\n  TOOL TRANS(0,0,250,0,0,0)\n  LMOVE b\n  LMOVE c\n  TOOL TRANS(10,0,300,0,0,0)\n  LMOVE b\n")
    tools = [m.settings.tool for m in tp.moves]
    assert tools[0] is None
    assert tools[1] is tools[2] and tools[1].line == 3
    np.testing.assert_allclose(tools[1].offset_mm, [0, 0, 250])
    assert tools[3].line == 6
    np.testing.assert_allclose(tools[3].offset_mm, [10, 0, 300])
    np.testing.assert_allclose(tools[3].rotation, np.eye(3), atol=1e-15)
    assert tp.tool is tools[3]


def test_a_tool_change_after_motion_stops_it_and_keeps_the_flange():
    tp = run("  TOOL TRANS(0,0,250,0,0,0)\n  JMOVE a\n  LMOVE b\n  TOOL TRANS(0,0,300,0,0,0)\n  LMOVE c\n")
    assert tp.moves[1].settings.stop_at_end  # the controller finishes the motion before changing frames
    start = tp.moves[2].start
    # same flange: the new TCP is 50 mm further along the tool z (pointing down, base -z)
    np.testing.assert_allclose(start.translation_mm, [600, 0, 250], atol=1e-9)
    np.testing.assert_allclose(start.rotation, tp.moves[1].end.rotation, atol=1e-12)
    np.testing.assert_allclose(tp.moves[2].end.translation_mm, [600, 100, 300], atol=1e-9)


def test_relative_motion_after_a_tool_change_uses_the_new_tcp():
    tp = run("  TOOL TRANS(0,0,250,0,0,0)\n  JMOVE a\n  TOOL TRANS(0,0,300,0,0,0)\n  LDEPART 20\n")
    # the new TCP starts at z = 250 (50 mm below the old one), then backs off 20 mm along tool z (up)
    np.testing.assert_allclose(tp.moves[1].end.translation_mm, [500, 0, 270], atol=1e-9)


def test_base_applies_from_where_it_is_set():
    tp = run("  JMOVE a\n  BASE TRANS(0,200,0,90,0,0)\n  LMOVE a\n  BASE NULL\n  LMOVE b\n")
    np.testing.assert_allclose(tp.moves[0].target.translation_mm, [500, 0, 300], atol=1e-9)
    # a = (500, 0, 300) in a base frame turned 90 deg about z and shifted 200 mm along y
    np.testing.assert_allclose(tp.moves[1].end.translation_mm, [0, 700, 300], atol=1e-9)
    np.testing.assert_allclose(tp.moves[1].end.rotation, oat_to_matrix(90, 0, 0) @ oat_to_matrix(0, 180, 0), atol=1e-12)
    np.testing.assert_allclose(tp.moves[2].end.translation_mm, [600, 0, 300], atol=1e-9)
    assert tp.moves[2].start is tp.moves[1].end


offsets = st.floats(-300, 300, allow_nan=False)
angles = st.floats(-180, 180, allow_nan=False)


@given(tool=st.tuples(offsets, offsets, offsets, angles, st.floats(0, 180), angles),
       gun=st.tuples(offsets, offsets, offsets, angles, st.floats(0, 180), angles))
def test_the_gun_in_the_tcp_frame_composes_back_to_the_gun(tool, gun):
    """Flange = P T^-1, gun on the flange = P T^-1 G = P M: M composed with T gives G."""
    from coatsim.path.toolpath import ToolFrame

    t = ToolFrame(oat_to_matrix(*tool[3:]), np.array(tool[:3]), 1)
    g_r, g_p = oat_to_matrix(*gun[3:]), np.array(gun[:3])
    m_r, m_p = gun_in_tcp(t, g_r, g_p)
    np.testing.assert_allclose(t.rotation @ m_r, g_r, atol=1e-9)
    np.testing.assert_allclose(t.offset_mm + t.rotation @ m_p, g_p, atol=1e-9)


def test_mismatches_name_the_tool_line_and_the_offset():
    tp = run("  TOOL TRANS(0,0,250,0,0,0)\n  JMOVE a\n  TOOL TRANS(0,0,300,0,0,0)\n  LMOVE b\n  TOOL TRANS(0,0,300,0,0,0)\n  LMOVE c\n")
    found = tool_mismatches(tp, np.eye(3), np.array([0.0, 0.0, 250.0]))
    assert [line for line, _ in found] == [4, 6]
    assert "TRANS(0,0,300,0,0,0) is not the gun's TCP TRANS(0,0,250,0,0,0)" in found[0][1]
    assert "runs 50.000 mm from the programmed TCP (tool frame x 0.000, y 0.000, z -50.000 mm)" in found[0][1]
    turned = tool_mismatches(run("  TOOL TRANS(0,0,250,0,10,0)\n  JMOVE a\n"), np.eye(3), np.array([0.0, 0.0, 250.0]))
    assert "spray axis tilted by 10.000 deg" in turned[0][1] and math.isclose(
        float(turned[0][1].split("runs ")[1].split(" mm")[0]), 0.0, abs_tol=1e-3)
    rolled = tool_mismatches(run("  TOOL TRANS(0,0,250,30,0,0)\n  JMOVE a\n"), np.eye(3), np.array([0.0, 0.0, 250.0]))
    assert "runs 0.000 mm" in rolled[0][1] and "rolled by 30.000 deg about the spray axis" in rolled[0][1]
    assert tool_mismatches(run("  JMOVE a\n"), np.eye(3), np.zeros(3)) == []
    assert tool_mismatches(run("  TOOL TRANS(0,0,250,0,0,0)\n  JMOVE a\n"), np.eye(3), np.array([0.0, 0.0, 250.0])) == []


@pytest.mark.parametrize("body", ["  TOOL NULL\n  JMOVE a\n", "  JMOVE a\n  TOOL NULL\n  LMOVE b\n"])
def test_tool_null_is_the_flange(body):
    tp = run(body)
    tool = tp.moves[-1].settings.tool
    np.testing.assert_allclose(tool.offset_mm, 0.0)
    np.testing.assert_allclose(tool.rotation, np.eye(3))
