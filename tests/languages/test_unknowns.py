"""A program that reads a value it never sets — a UR installation variable or feature, a G-code
parameter, a Fanuc register, a RAPID or KRL variable of another module, a position declared
without a value — is read by every reader alike: the unknown is listed with where it is read,
the motion that depends on it is skipped and listed, a value given from outside (NAME=VALUE)
brings it back, and a simulation refuses in one line naming it. What touches no motion is not
refused. Programs in several authors' styles per language."""

from __future__ import annotations

import numpy as np
import pytest
from coatsim.core.errors import InputError
from coatsim.languages.registry import language
from coatsim.path.language import ReadOptions

DOWN = "3.14159265359, 0, 0"
POSE_DOWN = "[[0,0,0],[0,1,0,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]]"


def _files(tmp_path, name, texts):
    paths = []
    for suffix, text in texts:
        path = tmp_path / f"{name}{suffix}"
        path.write_text(text)
        paths.append(path)
    return paths


def _reading(lang, paths, **variables):
    return language(lang).reading(paths, ReadOptions(variables=variables))


def _ends(reading):
    return [tuple(np.round((getattr(m, "end", None) or m.target).translation_mm, 6)) for m in reading.toolpath.moves]


# --- URScript --------------------------------------------------------------------------------------

UR_POLYSCOPE = f"""def Coat():
  set_tcp(p[0, 0, 0.25, 0, 0, 0])
  movej(p[0.5, 0, 0.4, {DOWN}], a=1.4, v=1.05)
  set_digital_out(1, True)
  movel(pose_trans(Plane_1, p[0.0, 0.1, 0, 0, 0, 0]), a=1.2, v=0.1)
  set_digital_out(1, False)
end
"""
UR_HAND = f"""def stroke(origin, dy):
  movel(pose_add(origin, p[0, dy, 0, 0, 0, 0]), v=speed)
end
def main():
  movej(p[0.5, 0, 0.4, {DOWN}])
  textmsg("width ", stroke_width)
  set_digital_out(1, True)
  stroke(p[0.5, 0, 0.4, {DOWN}], 0.1)
  set_digital_out(1, False)
end
"""
UR_CONDITION = f"""movej(p[0.5, 0, 0.4, {DOWN}])
if use_second_pass:
  movel(p[0.6, 0, 0.4, {DOWN}])
end
"""


def test_urscript_feature_is_an_unknown_and_its_value_brings_the_motion_back(tmp_path):
    paths = _files(tmp_path, "coat", [(".script", UR_POLYSCOPE)])
    r = _reading("urscript", paths)
    assert len(r.unknowns) == 1 and r.unknowns[0].startswith(f"{paths[0]}:5: Plane_1 is read")
    assert "Plane_1=VALUE" in r.unknowns[0]
    assert r.skipped == (f"{paths[0]}:5: movel() skipped: it depends on Plane_1, which the program never sets",)
    assert len(r.toolpath.moves) == 1
    with pytest.raises(InputError, match=r"coat.script:5: movel\(\) skipped: it depends on Plane_1") as info:
        language("urscript").read(paths, ReadOptions())
    assert "\n" not in str(info.value)
    given = _reading("urscript", paths, Plane_1=f"p[0.5, 0, 0.4, {DOWN}]")
    assert not given.unknowns and not given.skipped
    assert _ends(given)[-1] == pytest.approx((500, -100, 400), abs=1e-6)  # y of the plane is -y of the base


def test_urscript_unknown_in_a_message_refuses_nothing_and_parameters_carry_unknowns(tmp_path):
    paths = _files(tmp_path, "hand", [(".script", UR_HAND)])
    r = _reading("urscript", paths)
    names = sorted(u.split(": ")[1].split(" ")[0] for u in r.unknowns)
    assert names == ["speed", "stroke_width"]
    assert len(r.skipped) == 1 and "hand.script:2: movel() skipped: it depends on speed" in r.skipped[0]
    tp = language("urscript").read(paths, ReadOptions(variables={"speed": "0.2"}))  # stroke_width: a message only
    assert tp.moves[-1].settings.speed_mm_s == pytest.approx(200.0)
    assert _ends_tp(tp)[-1] == pytest.approx((500, 100, 400), abs=1e-6)


def test_urscript_condition_on_an_unknown_skips_the_if(tmp_path):
    paths = _files(tmp_path, "cond", [(".script", UR_CONDITION)])
    r = _reading("urscript", paths)
    assert r.skipped == (f"{paths[0]}:2: if skipped: it depends on use_second_pass, which the program never sets",)
    assert len(_reading("urscript", paths, use_second_pass=1).toolpath.moves) == 2
    assert len(_reading("urscript", paths, use_second_pass=0).toolpath.moves) == 1


def _ends_tp(tp):
    return [tuple(np.round((getattr(m, "end", None) or m.target).translation_mm, 6)) for m in tp.moves]


# --- G-code ----------------------------------------------------------------------------------------

GCODE_LINUXCNC = """%
G21 G90 G17 G64 P0.1
G0 X500 Y0 Z400
M3
G1 X500 Y#<_stroke> F1200 (a global the operator sets)
M5
M30
%
"""
GCODE_MACRO = """O1000 (FANUC MACRO STYLE)
G21 G90
G0 X500. Y0. Z400.
#1=[#500+10.]
M3
G1 X[500.+#1] F600.
G1 Y50.
M5
M30
"""
GCODE_UNUSED = """G21 G90
G0 X500 Y0 Z400
#2 = #101
M3
G1 X600 F600
M5
M2
"""


def test_gcode_named_parameter_never_set_is_an_unknown(tmp_path):
    paths = _files(tmp_path, "lc", [(".ngc", GCODE_LINUXCNC)])
    r = _reading("gcode", paths)
    assert r.unknowns[0].startswith(f"{paths[0]}:5: #<_stroke> is read")
    assert r.skipped == (f"{paths[0]}:5: the motion skipped: it depends on #<_stroke>, which the program never sets",)
    with pytest.raises(InputError, match=r"lc.ngc:5: the motion skipped: it depends on #<_stroke>"):
        language("gcode").read(paths, ReadOptions())
    given = _reading("gcode", paths, **{"#<_stroke>": 80})
    assert not given.skipped and _ends(given)[-1] == (500, 80, 400)


def test_gcode_parameter_set_from_an_unknown_is_unknown_and_the_feed_of_its_block_stays(tmp_path):
    paths = _files(tmp_path, "mac", [(".nc", GCODE_MACRO)])
    r = _reading("gcode", paths)
    assert r.unknowns[0].startswith(f"{paths[0]}:4: #500 is read")
    assert r.skipped == (f"{paths[0]}:6: the motion skipped: it depends on #500, which the program never sets",)
    assert r.toolpath.moves[-1].settings.speed_mm_s == pytest.approx(10.0)  # F600. on the skipped line holds
    given = _reading("gcode", paths, **{"500": 40})
    assert _ends(given)[-2:] == [(550, 0, 400), (550, 50, 400)]


def test_gcode_unknown_that_moves_nothing_is_listed_not_refused(tmp_path):
    paths = _files(tmp_path, "unused", [(".ngc", GCODE_UNUSED)])
    r = _reading("gcode", paths)
    assert len(r.unknowns) == 1 and "#101" in r.unknowns[0] and not r.skipped
    assert len(language("gcode").read(paths, ReadOptions()).moves) == 2


# --- Fanuc TP --------------------------------------------------------------------------------------

def _ls(name, lines, positions, uf=0):
    body = "".join(f"{k + 1:4d}:  {line} ;\n" for k, line in enumerate(lines))
    pos = "".join(
        f"P[{k + 1}]{{\n   GP1:\n\tUF : {uf}, UT : 1,\t\tCONFIG : 'N U T, 0, 0, 0',\n"
        f"\tX = {x:.3f}  mm,\tY = {y:.3f}  mm,\tZ = {z:.3f}  mm,\n\tW = 180.000 deg,\tP = 0.000 deg,\tR = 0.000 deg\n}};\n"
        for k, (x, y, z) in enumerate(positions))
    return f"/PROG  {name}\n/ATTR\n/MN\n{body}/POS\n{pos}/END\n"


def test_fanuc_register_speed_and_position_register_target_are_unknowns(tmp_path):
    text = _ls("COAT", ["UFRAME_NUM=0", "UTOOL_NUM=1", "J P[1] 50% FINE", "R[2]=R[1]+10", "DO[1]=ON",
                        "L P[2] R[2]mm/sec CNT100", "L PR[5] 200mm/sec FINE", "DO[1]=OFF"],
               [(500, 0, 400), (600, 0, 400)])
    paths = _files(tmp_path, "COAT", [(".ls", text)])
    r = _reading("fanuc", paths)
    shown = [u.split(" is read")[0] for u in r.unknowns]
    assert shown == [f"{paths[0]}:7: R[1]", f"{paths[0]}:10: PR[5]"]
    assert "also read at line 9" in r.unknowns[0]  # where R[2], set from it, sets the speed
    assert [s.split(": ", 1)[1] for s in r.skipped] == [
        "the motion skipped: it depends on R[1], which the program never sets",
        "the motion skipped: it depends on PR[5], which the program never sets"]
    with pytest.raises(InputError, match=r"COAT.ls:9: the motion skipped: it depends on R\[1\]"):
        language("fanuc").read(paths, ReadOptions())
    given = _reading("fanuc", paths, **{"R[1]": 90, "PR[5]": "550,50,400,180,0,0"})
    assert not given.skipped and given.toolpath.moves[1].settings.speed_mm_s == pytest.approx(100.0)
    assert _ends(given)[-1] == (550, 50, 400)


def test_fanuc_user_frame_never_given_skips_the_motions_in_it(tmp_path):
    text = _ls("INFRAME", ["UFRAME_NUM=3", "UTOOL_NUM=1", "J P[1] 50% FINE", "L P[2] 100mm/sec FINE"],
               [(0, 0, 0), (100, 0, 0)], uf=3)
    paths = _files(tmp_path, "INFRAME", [(".ls", text)])
    with pytest.raises(Exception, match=r"UFRAME\[3\], which the program never sets"):
        language("fanuc").read(paths, ReadOptions())
    given = _reading("fanuc", paths, **{"UFRAME[3]": "400,0,300,0,0,0"})
    assert _ends(given) == [(400, 0, 300), (500, 0, 300)]


def test_fanuc_counter_never_reset_is_unknown_until_given(tmp_path):
    text = _ls("COUNT", ["UTOOL_NUM=1", "J P[1] 50% FINE", "R[7]=R[7]+1", "L P[2] 100mm/sec FINE"],
               [(500, 0, 400), (600, 0, 400)])
    paths = _files(tmp_path, "COUNT", [(".ls", text)])
    r = _reading("fanuc", paths)
    assert len(r.unknowns) == 1 and "R[7]" in r.unknowns[0] and not r.skipped  # counted, never used to move
    assert len(language("fanuc").read(paths, ReadOptions()).moves) == 2


# --- RAPID and KRL ---------------------------------------------------------------------------------

RAPID_TAUGHT = f"""MODULE Coat
  VAR robtarget pTaught;
  PROC main()
    MoveJ [[500,0,400],[0,1,0,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]], v100, fine, tool0;
    SetDO do1, 1;
    MoveL pTaught, v100, fine, tool0;
    MoveL Offs(pTaught, 0, stroke, 0), v100, fine, tool0;
    SetDO do1, 0;
  ENDPROC
ENDMODULE
"""
KRL_SRC = """DEF coat()
  PTP {X 500, Y 0, Z 400, A 0, B 90, C 0}
  $OUT[1] = TRUE
  LIN XP1
  LIN {X 600, Y yoff, Z 400, A 0, B 90, C 0}
  $OUT[1] = FALSE
END
"""
KRL_DAT = """DEFDAT coat
  DECL E6POS XP1
ENDDAT
"""


def test_rapid_position_declared_without_a_value_is_an_unknown(tmp_path):
    paths = _files(tmp_path, "Coat", [(".mod", RAPID_TAUGHT)])
    r = _reading("rapid", paths)
    assert [u.split(" is read")[0] for u in r.unknowns] == [f"{paths[0]}:6: pTaught"]  # stroke: read after it
    assert "pTaught, which has no value (declared without one)" in r.skipped[0]
    assert "line 7" in r.unknowns[0]  # every place that reads it
    with pytest.raises(InputError, match="pTaught"):
        language("rapid").read(paths, ReadOptions())
    given = _reading("rapid", paths, pTaught=POSE_DOWN.replace("[0,0,0],", "[600,0,400],", 1), stroke=50)
    assert not given.skipped and _ends(given)[-2:] == [(600, 0, 400), (600, 50, 400)]


def test_krl_dat_declaration_without_a_value_is_an_unknown(tmp_path):
    paths = _files(tmp_path, "coat", [(".src", KRL_SRC), (".dat", KRL_DAT)])
    r = _reading("krl", paths)
    assert [u.split(" is read")[0] for u in r.unknowns] == [f"{paths[0]}:4: XP1", f"{paths[0]}:5: yoff"]
    assert "XP1, which has no value in the files (declared without one)" in r.skipped[0]
    given = _reading("krl", paths, XP1="{X 600, Y 0, Z 400, A 0, B 90, C 0}", yoff=50)
    assert not given.skipped and _ends(given)[-2:] == [(600, 0, 400), (600, 50, 400)]


def test_krl_component_set_gives_the_declared_position_a_value(tmp_path):
    src = KRL_SRC.replace("  LIN XP1\n", "  XP1 = {X 600, Y 0, Z 400, A 0, B 90, C 0}\n  XP1.Y = 20\n  LIN XP1\n")
    paths = _files(tmp_path, "coat", [(".src", src), (".dat", KRL_DAT)])
    r = _reading("krl", paths, yoff=0)
    assert not r.skipped and (600, 20, 400) in _ends(r)


# --- the command line ------------------------------------------------------------------------------

def test_check_program_lists_unknowns_and_set_gives_them(tmp_path, run_cli):
    paths = _files(tmp_path, "coat", [(".script", UR_POLYSCOPE)])
    code, out, err = run_cli(["check-program", str(paths[0])])
    assert code == 0, err
    assert f"unknown: {paths[0]}:5: Plane_1 is read" in out
    assert f"skipped: {paths[0]}:5: movel() skipped" in out
    code, out, err = run_cli(["check-program", str(paths[0]), "--set", f"Plane_1=p[0.5,0,0.4,{DOWN}]"])
    assert code == 0 and "unknown:" not in out and "1 linear" in out
    code, out, err = run_cli(["execute", str(paths[0]), "-o", str(tmp_path / "out")])
    assert code == 2 and "Plane_1" in err and len(err.strip().splitlines()) == 1


RAPID_CELL_DATA = """MODULE CoatMain
  CONST robtarget pStart := [[0,0,0],[0,1,0,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];
  PROC main()
    MoveJ pStart, v200, fine, tSprayGun \\WObj:=wobjTable;
    SetDO doGun, 1;
    MoveL Offs(pStart, 100, 0, 0), v200, z1, tSprayGun \\WObj:=wobjTable;
    SetDO doGun, 0;
  ENDPROC
ENDMODULE
"""
KRL_BAS = """DEF coat()
  BAS(#INITMOV, 0)
  BAS(#TOOL, 1)
  BAS(#BASE, 3)
  PTP {X 0, Y 0, Z 50, A 0, B 90, C 0}
  LIN {X 0, Y 0, Z 0}
  $OUT[1] = TRUE
  LIN {X 100, Y 0, Z 0}
  $OUT[1] = FALSE
END
"""


def test_rapid_tool_and_work_object_of_another_module_are_unknowns(tmp_path):
    paths = _files(tmp_path, "CoatMain", [(".mod", RAPID_CELL_DATA)])
    r = _reading("rapid", paths)
    assert [u.split(" is read")[0] for u in r.unknowns] == [f"{paths[0]}:4: tSprayGun"]
    assert "also read at line 6" in r.unknowns[0] and len(r.skipped) == 2
    given = _reading("rapid", paths, tSprayGun="[TRUE,[[0,0,250],[1,0,0,0]],[1,[0,0,1],[1,0,0,0],0,0,0]]",
                     wobjTable='[FALSE,TRUE,"",[[600,-100,200],[1,0,0,0]],[[0,0,0],[1,0,0,0]]]')
    assert not given.unknowns and not given.skipped
    assert _ends(given) == [(600, -100, 200), (700, -100, 200)]
    assert np.allclose(given.move_frames[-1].translation_mm, [600, -100, 200])


def test_krl_base_of_the_controllers_table_is_an_unknown(tmp_path):
    paths = _files(tmp_path, "coat", [(".src", KRL_BAS)])
    r = _reading("krl", paths)
    assert [u.split(" is read")[0] for u in r.unknowns] == [f"{paths[0]}:3: TOOL_DATA[1]", f"{paths[0]}:4: BASE_DATA[3]"]
    with pytest.raises(InputError, match="TOOL_DATA"):
        language("krl").read(paths, ReadOptions())
    given = _reading("krl", paths, **{"TOOL_DATA[1]": "{X 0,Y 0,Z 250,A 0,B 0,C 0}",
                                      "BASE_DATA[3]": "{X 500,Y 100,Z 300,A 0,B 0,C 0}"})
    assert not given.skipped and _ends(given)[-1] == (600, 100, 300)


@pytest.mark.parametrize("suffix,text", [
    (".script", "def spray():\n  set_digital_out(0, True)\n  movel(pose_trans(Plane_Part, p[0, 0, 0, 3.14, 0, 0]))\n"
                "  movel(pose_trans(Plane_Part, p[0.1, 0, 0, 3.14, 0, 0]))\n  set_digital_out(0, False)\nend\n"),
    (".as", ".PROGRAM sprayv()\n  SPEED bead_speed MM/S ALWAYS\n  JAPPRO start_p, 50\n  LMOVE start_p\n  SIGNAL 1\n"
            "  LMOVE SHIFT(start_p BY len, 0, 0)\n  SIGNAL -1\n.END\n"),
])
def test_a_program_whose_every_motion_waits_for_a_value_is_read_not_refused(tmp_path, run_cli, suffix, text):
    """Reading is not running: with every motion skipped for want of a value, check-program
    still reads the program (exit 0), lists what it needs and says it makes no motion."""
    path = tmp_path / f"p{suffix}"
    path.write_text(text)
    code, out, err = run_cli(["check-program", str(path)])
    assert code == 0, err
    assert "moves: 0 joint, 0 linear, 0 arc" in out and "makes no motion here: every motion of its run is skipped" in out
    assert out.count("skipped") >= 2 and "give values as --set NAME=VALUE" in out


def test_a_program_whose_every_motion_is_unsimulated_says_no_value_reads_it(tmp_path, run_cli):
    """Teach-pendant block steps are not simulated: the report said every motion was skipped "for
    want of a value" and asked for values (none could help), then "no problems found"."""
    path = tmp_path / "block.as"
    path.write_text(".PROGRAM b()\n  LINEAR SPEED4 ACCU1 TIMER0 TOOL1 WORK0 CLAMP1 (OFF,0,0,O) OX=1 WX= "
                    "#[8.1,22.6,-63.5,0.0,-93.9,8.1] ;\n.END\n")
    code, out, err = run_cli(["check-program", str(path)])
    assert code == 0, err
    assert "problem:" in out and "statements the twin does not simulate" in out
    assert "no problems found" not in out and "--set" not in out
