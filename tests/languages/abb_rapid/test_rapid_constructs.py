"""ABB RAPID: each construct the reader and the twin must handle, in several authors' styles
(RobotStudio exports, hand-written, upper and lower case, comments)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from coatsim.core.errors import ExecutionError, InputError
from coatsim.languages.abb_rapid.language import ABB_RAPID
from coatsim.path.language import ReadOptions

TOOL = "PERS tooldata tGun := [TRUE,[[0,0,150],[1,0,0,0]],[2,[0,0,100],[1,0,0,0],0,0,0]];"
DOWN = "[0,0,1,0]"  # tool z pointing down (180 deg about y)


def rt(x: float, y: float, z: float, q: str = DOWN) -> str:
    return f"[[{x},{y},{z}],{q},[0,0,0,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]]"


def read(tmp_path, text: str, name: str = "prog.mod", **options):
    path = tmp_path / name
    path.write_text(text)
    return ABB_RAPID.reading([path], ReadOptions(**options))


def module(body: str, data: str = "") -> str:
    return (f"MODULE Prog\n  {TOOL}\n  CONST robtarget p10 := {rt(500, 0, 300)};\n"
            f"  CONST robtarget p20 := {rt(600, 0, 300)};\n  CONST robtarget p30 := {rt(600, 100, 300)};\n{data}\n"
            f"  PROC main()\n    MoveJ p10, v1000, fine, tGun;\n{body}\n  ENDPROC\nENDMODULE\n")


def test_robotstudio_export_with_header_movel_movec_zones(tmp_path):
    text = ("%%%\n  VERSION:1\n  LANGUAGE:ENGLISH\n%%%\n" + module(
        "    MoveL p20, v500, z10, tGun;\n    MoveC p30, p10, v200, fine, tGun;   ! arc back"))
    r = read(tmp_path, text)
    kinds = [m.kind for m in r.toolpath.moves]
    assert kinds == ["joint", "line", "arc"]
    line, arc = r.toolpath.moves[1:]
    assert line.settings.speed_mm_s == 500 and line.settings.accuracy_mm == 10 and not line.settings.stop_at_end
    assert arc.settings.stop_at_end and np.allclose(arc.end.translation_mm, [500, 0, 300])
    assert np.allclose(arc.end.rotation[:, 2], [0, 0, -1])  # q = [0,0,1,0]: the tool points down


def test_custom_zonedata_speeddata_and_optional_arguments(tmp_path):
    data = ("  CONST zonedata zSpray := [FALSE,2.5,4,4,0.4,4,0.4];\n"
            "  CONST speeddata vSpray := [250,500,5000,1000];\n"
            "  PERS wobjdata wPart := [FALSE,TRUE,\"\",[[100,50,0],[1,0,0,0]],[[0,0,0],[1,0,0,0]]];")
    body = ("    MoveL p20, vSpray, zSpray, tGun\\WObj:=wPart;\n"
            "    MoveL p30, vSpray \\V:=123, zSpray \\Z:=1.5, tGun \\WObj:=wPart;\n"
            "    MoveL p20, v100, z50, tGun\\Inpos:=inpos50;")
    r = read(tmp_path, module(body, data))
    a, b, c = r.toolpath.moves[1:]
    assert a.settings.accuracy_mm == 2.5 and a.settings.speed_mm_s == 250
    assert np.allclose(a.end.translation_mm, [700, 50, 300])  # the work object's frame
    assert b.settings.speed_mm_s == 123 and b.settings.accuracy_mm == 1.5
    assert c.settings.stop_at_end  # \Inpos: a stop point
    assert np.allclose(r.move_frames[1].translation_mm, [100, 50, 0])


def test_tooldata_is_the_tcp_of_each_move(tmp_path):
    r = read(tmp_path, module("    MoveL p20, v500, fine, tGun;"))
    tool = r.toolpath.moves[1].settings.tool
    assert np.allclose(tool.offset_mm, [0, 0, 150]) and np.allclose(tool.rotation, np.eye(3))


def test_offs_reltool_crobt(tmp_path):
    body = ("    MoveL Offs(p10, 10, 20, -30), v500, fine, tGun;\n"
            "    MoveL RelTool(p10, 0, 0, -50 \\Rz:=90), v500, fine, tGun;\n"
            "    cur := CRobT(\\Tool:=tGun \\WObj:=wobj0);\n"
            "    MoveL Offs(cur, 0, 0, 100), v500, fine, tGun;")
    r = read(tmp_path, module(body, "  VAR robtarget cur;"))
    offs, rel, up = r.toolpath.moves[1:]
    assert np.allclose(offs.end.translation_mm, [510, 20, 270])
    assert np.allclose(rel.end.translation_mm, [500, 0, 350])  # 50 back along tool z (pointing down)
    assert np.allclose(rel.end.rotation, r.toolpath.moves[0].target.rotation @ np.array([[0, -1, 0], [1, 0, 0], [0, 0, 1]]))
    assert np.allclose(up.end.translation_mm, [500, 0, 450])


def test_setdo_set_reset_switch_the_gun_by_the_number_in_the_name(tmp_path):
    body = ("    SetDO do1, 1;\n    MoveL p20, v500, z1, tGun;\n    Reset do1;\n    MoveL p30, v500, fine, tGun;\n"
            "    Set doSpray2;")
    r = read(tmp_path, module(body))
    assert [m.spray for m in r.toolpath.moves] == [False, True, False]
    assert r.outputs == (1, 2) and any("(gun on)" in str(s) for s in r.switches)
    named = read(tmp_path, module("    SetDO doGun, 1;\n    MoveL p20, v500, fine, tGun;"), variables={"doGun": "1"})
    assert named.toolpath.moves[-1].spray


def test_pers_const_var_data_and_arrays(tmp_path):
    data = (f"  PERS robtarget pts{{3}} := [{rt(500, 0, 300)},{rt(510, 0, 300)},{rt(520, 0, 300)}];\n"
            "  VAR num k := 0;\n  CONST num n := 3;")
    body = "    FOR i FROM 1 TO n DO\n      MoveL pts{i}, v500, z5, tGun;\n      k := k + 1;\n    ENDFOR"
    r = read(tmp_path, module(body, data))
    assert [m.end.translation_mm[0] for m in r.toolpath.moves[1:]] == [500, 510, 520]


def test_proc_and_func_calls_with_parameters(tmp_path):
    text = module("    Pass 20;\n    Pass Half(60);", "") .replace("ENDMODULE", (
        "  PROC Pass(num dx)\n    MoveL Offs(p10, dx, 0, 0), v500, z1, tGun;\n  ENDPROC\n"
        "  FUNC num Half(num x)\n    RETURN x / 2;\n  ENDFUNC\nENDMODULE"))
    r = read(tmp_path, text)
    assert [m.end.translation_mm[0] for m in r.toolpath.moves[1:]] == [520, 530]


def test_while_if_elseif_test_and_goto(tmp_path):
    body = ("    VAR num i := 0;\n    WHILE i < 3 DO\n      i := i + 1;\n      IF i = 1 THEN\n        MoveL p20, v500, z1, tGun;\n"
            "      ELSEIF i = 2 THEN\n        MoveL p30, v500, z1, tGun;\n      ELSE\n        MoveL p10, v500, z1, tGun;\n"
            "      ENDIF\n    ENDWHILE\n    TEST i\n    CASE 1, 2:\n      Stop;\n    DEFAULT:\n      GOTO skip;\n    ENDTEST\n"
            "    MoveL p20, v500, fine, tGun;\n  skip:\n    MoveL p30, v500, fine, tGun;")
    r = read(tmp_path, module(body))
    ends = [tuple(m.end.translation_mm[:2]) if m.kind != "joint" else None for m in r.toolpath.moves[1:]]
    assert ends == [(600, 0), (600, 100), (500, 0), (600, 100)]


def test_moveabsj_uses_the_cells_kinematics(tmp_path):
    class Kin:
        def forward(self, joints, tool=None):
            from coatsim.geometry.space.pose import Pose
            return Pose(np.eye(3), np.array([joints[0], 0.0, 0.0]))

        def home(self, number):
            return np.zeros(6)

    text = module("    MoveAbsJ [[90,0,0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]], v500, fine, tGun;")
    r = read(tmp_path, text, kinematics=Kin())
    move = r.toolpath.moves[-1]
    assert move.kind == "joint" and math.isclose(move.joints_rad[0], math.pi / 2)
    with pytest.raises(InputError, match="kinematics"):
        read(tmp_path, text)


def test_traps_and_interrupts_are_noted_not_run(tmp_path):
    text = module("    CONNECT intno1 WITH tr;\n    ISignalDI di1, 1, intno1;\n    MoveL p20, v500, fine, tGun;",
                  "  VAR intnum intno1;").replace("ENDMODULE", "  TRAP tr\n    MoveL p30, v500, fine, tGun;\n  ENDTRAP\nENDMODULE")
    r = read(tmp_path, text)
    assert len(r.toolpath.moves) == 2 and any("TRAP tr" in p for p in r.problems)
    assert any("interrupt" in w for w in r.toolpath.warnings)


def test_quaternion_must_be_unit_and_q1_may_be_negative(tmp_path):
    r = read(tmp_path, module("    MoveL [[600,0,300],[0,0,-1,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]], v500, fine, tGun;"))
    assert np.allclose(r.toolpath.moves[-1].end.rotation[:, 2], [0, 0, -1])
    with pytest.raises(InputError, match="unit quaternion"):
        read(tmp_path, module("    MoveL [[600,0,300],[0,0,2,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]], v500, fine, tGun;"))


def test_waittime_is_a_rest_and_a_stop(tmp_path):
    r = read(tmp_path, module("    MoveL p20, v500, z10, tGun;\n    WaitTime 0.5;\n    MoveL p30, v500, fine, tGun;"))
    assert r.toolpath.moves[1].settings.stop_at_end and r.toolpath.dwells[0].seconds == 0.5


def test_lower_case_and_compact_if(tmp_path):
    text = module("    moveL p20, v500, z1, tGun;\n    if TRUE setdo do1, 1;\n    movel p30, V500, FINE, tgun;").lower()
    r = read(tmp_path, text)
    assert r.toolpath.moves[-1].spray and r.program == "main"


def test_unknown_data_and_routines_skip_the_statement(tmp_path):
    r = read(tmp_path, module("    MoveL pElsewhere, v500, fine, tGun;\n    GripperOpen;"))
    assert len(r.skipped) == 2 and "pElsewhere" in r.unknowns[0]
    with pytest.raises(InputError, match="statement skipped"):
        r.require_complete()


@pytest.mark.parametrize("text, words", [
    ("MODULE a\n  PROC main()\n    MoveL p, v5, fine, tool0\n  ENDPROC\nENDMODULE", "expected ',' or ';'"),
    ("MODULE a\n  PROC main()\n  ENDMODULE", "ENDPROC"),
    ("PROC main()\nENDPROC", "expected MODULE"),
    ("MODULE a\n  PROC main()\n    MoveL *, v5, fine, tool0;\n  ENDPROC\nENDMODULE", "written as \\*"),
])
def test_defects_name_the_line(tmp_path, text, words):
    with pytest.raises((InputError, ExecutionError)) as info:
        read(tmp_path, text)
    assert "prog.mod:" in str(info.value) and "\n" not in str(info.value)


def test_movec_turns_the_tool_from_start_to_end_whatever_the_circle_point_s_orientation(tmp_path):
    """RAPID uses the circle point's orientation only to pick the way round: the tool turns
    from the start's orientation to the destination's, so the via is read with that turn's
    orientation at its place (a quarter of the way at a circle point a quarter along)."""
    from coatsim.geometry.space.pose import slerp

    quarter = f"[{math.cos(math.pi / 8)},0,0,{math.sin(math.pi / 8)}]"
    data = (f"  CONST robtarget c1 := {rt(600 + 50 * math.sqrt(0.5), 50 - 50 * math.sqrt(0.5), 300, '[0.5,0.5,0.5,0.5]')};\n"
            f"  CONST robtarget c2 := {rt(600, 100, 300, quarter)};")
    r = read(tmp_path, module("    MoveL p20, v500, fine, tGun;\n    MoveC c1, c2, v200, fine, tGun;", data))
    arc = r.toolpath.moves[2]
    np.testing.assert_allclose(arc.via.rotation, slerp(arc.start.rotation, arc.end.rotation, 0.25)[0], atol=1e-9)
