"""KUKA KRL: each construct the reader and the twin must handle, in several authors' styles
(WorkVisual folds, hand-written, upper and lower case, a .src with its .dat)."""

from __future__ import annotations

import numpy as np
import pytest

from coatsim.core.errors import ExecutionError, InputError
from coatsim.languages.kuka_krl.language import KUKA_KRL
from coatsim.path.language import ReadOptions




def read(tmp_path, src: str, dat: str | None = None, name: str = "prog", **options):
    (tmp_path / f"{name}.src").write_text(src)
    if dat is not None:
        (tmp_path / f"{name}.dat").write_text(dat)
    return KUKA_KRL.reading([tmp_path / f"{name}.src"], ReadOptions(**options))


def prog(body: str, name: str = "prog") -> str:
    return (f"&ACCESS RVP\n&REL 3\nDEF {name}( )\n;FOLD INI\n  BAS(#INITMOV,0)\n;ENDFOLD (INI)\n"
            f"  $VEL.CP=0.3\n  $APO.CDIS=2\n  PTP {{X 500,Y 0,Z 300,A 0,B 90,C 0}}\n{body}\nEND\n")


def test_src_with_dat_pair_decl_e6pos_frame_pos(tmp_path):
    dat = ("&ACCESS RVP\nDEFDAT prog PUBLIC\n  DECL E6POS XP1={X 600,Y 0,Z 300,A 0,B 90,C 0,S 2,T 35,E1 0,E2 0,E3 0,"
           "E4 0,E5 0,E6 0}\n  DECL FRAME F1={X 10,Y 20,Z 0,A 0,B 0,C 0}\n  DECL POS P2={X 600,Y 100,Z 300,A 0,B 90,C 0}\n"
           "ENDDAT\n")
    r = read(tmp_path, prog("  LIN XP1 C_DIS\n  LIN P2\n  LIN F1:XP1"), dat)
    lin1, lin2, lin3 = r.toolpath.moves[1:]
    assert np.allclose(lin1.end.translation_mm, [600, 0, 300]) and not lin1.settings.stop_at_end
    assert lin1.settings.accuracy_mm == 2 and lin1.settings.speed_mm_s == pytest.approx(300.0)  # m/s -> mm/s
    assert lin2.settings.stop_at_end  # no approximation: an exact stop
    assert np.allclose(lin3.end.translation_mm, [610, 20, 300])  # F1 : XP1


def test_circ_auxiliary_and_end_point(tmp_path):
    r = read(tmp_path, prog("  LIN {X 600,Y 0,Z 300}\n  CIRC {X 650,Y 50,Z 300},{X 600,Y 100,Z 300} C_DIS\n  LIN {X 500}"))
    arc = r.toolpath.moves[2]
    assert arc.kind == "arc" and np.allclose(arc.via.translation_mm, [650, 50, 300])
    assert np.allclose(r.toolpath.moves[3].end.translation_mm, [500, 100, 300])  # missing components kept


def test_base_and_tool_inline_and_from_tables(tmp_path):
    body = ("  BASE_DATA[2]={X 100,Y 0,Z 0,A 90,B 0,C 0}\n  TOOL_DATA[1]={X 0,Y 0,Z 150,A 0,B 0,C 0}\n"
            "  BAS(#BASE,2)\n  BAS(#TOOL,1)\n  LIN {X 10,Y 0,Z 300,A 0,B 90,C 0}\n"
            "  $BASE={X 0,Y 0,Z 0,A 0,B 0,C 0}\n  LIN {X 700,Y 0,Z 300,A 0,B 90,C 0}")
    r = read(tmp_path, prog(body), "DEFDAT prog\n  DECL FRAME BASE_DATA[4]\n  DECL FRAME TOOL_DATA[4]\nENDDAT\n")
    a, b = r.toolpath.moves[1:]
    assert np.allclose(a.end.translation_mm, [100, 10, 300])
    assert np.allclose(a.settings.tool.offset_mm, [0, 0, 150]) and np.allclose(b.end.translation_mm, [700, 0, 300])


def test_out_stops_the_advance_run_out_c_and_trigger_do_not(tmp_path):
    body = ("  LIN {X 600} C_DIS\n  $OUT[1]=TRUE\n  LIN {X 610} C_DIS\n  TRIGGER WHEN DISTANCE=0 DELAY=0 DO $OUT[1]=FALSE\n"
            "  LIN {X 620} C_DIS\n  $OUT_C[1]=TRUE\n  LIN {X 630}\n  CONTINUE\n  $OUT[1]=FALSE\n  LIN {X 640}")
    r = read(tmp_path, prog(body))
    moves = r.toolpath.moves[1:]
    assert moves[0].settings.stop_at_end  # $OUT: approximation not possible
    assert [m.spray for m in moves] == [False, True, False, True, False]
    assert not moves[1].settings.stop_at_end and any("CONTINUE" in w for w in r.toolpath.warnings)


def test_loops_switch_goto_and_subroutines_with_deffct(tmp_path):
    src = prog("  DECL INT i\n  FOR i = 1 TO 3 STEP 1\n    pass(i * 10)\n  ENDFOR\n  i = 0\n  LOOP\n    i = i + 1\n"
               "    IF i >= twice(1) THEN\n      EXIT\n    ENDIF\n  ENDLOOP\n  REPEAT\n    i = i - 1\n  UNTIL i == 0\n"
               "  SWITCH i\n  CASE 0\n    GOTO done\n  DEFAULT\n    HALT\n  ENDSWITCH\n  LIN {X 999}\n  done:\n"
               "  WHILE i < 1\n    i = i + 1\n  ENDWHILE") + \
        "DEF pass(dx:IN)\n  DECL REAL dx\n  LIN {X 600,Y 0,Z 300,A 0,B 90,C 0}:{X 0,Y 0,Z 0,A 0,B 0,C 0}\n" \
        "  LIN_REL {X 0,Y 5,Z 0,A 0,B 0,C 0}\nEND\nDEFFCT INT twice(n:IN)\n  DECL INT n\n  RETURN n * 2\nENDFCT\n"
    r = read(tmp_path, src)
    assert len(r.toolpath.moves) == 1 + 6 and not any(m.end.translation_mm[0] == 999 for m in r.toolpath.moves[1:])


def test_wait_sec_is_a_rest_and_halt_ends(tmp_path):
    r = read(tmp_path, prog("  LIN {X 600} C_DIS\n  WAIT SEC 0.5\n  HALT\n  LIN {X 700}"))
    assert r.toolpath.moves[1].settings.stop_at_end and r.toolpath.dwells[0].seconds == 0.5
    assert len(r.toolpath.moves) == 2 and "HALT ends it" in r.ended


def test_lower_case_and_folds_from_the_pendant(tmp_path):
    src = ("def prog( )\n;fold ini\n  bas(#initmov,0)\n;endfold\n;FOLD PTP HOME Vel= 100 % DEFAULT;%{PE}%R 8.3.40\n"
           "  ptp {x 500,y 0,z 300,a 0,b 90,c 0}\n;ENDFOLD\n  bas(#vel_cp,0.25)\n  lin {x 600} c_dis\nend\n")
    r = read(tmp_path, src)
    assert r.toolpath.moves[-1].settings.speed_mm_s == pytest.approx(250.0)


def test_name_must_match_file_and_unknowns_skip(tmp_path):
    r = read(tmp_path, prog("  LIN XSOMEWHERE", name="other"), name="prog")
    assert any("file's name" in p for p in r.problems) and r.skipped


@pytest.mark.parametrize("src, words", [
    ("DEF p( )\n  LIN {X 1}\n", "without END"),
    ("DEF p( )\n  IF TRUE THEN\nEND\n", "ENDIF"),
    ("DEF p( )\n  LIN {X 1}\nEND\n", "first motion"),
    ("WHATEVER\n", "expected DEF"),
    ("DEF p( )\n  PTP {X 500,Y 0,Z 300}\n  LIN {X 500 + 10}\nEND\n", "an aggregate holds values, not expressions"),
])
def test_defects_name_the_line(tmp_path, src, words):
    with pytest.raises((InputError, ExecutionError)) as info:
        read(tmp_path, src)
    assert words in str(info.value) and "prog.src:" in str(info.value) and "\n" not in str(info.value)


@pytest.mark.parametrize("body", [
    "  DECL E6POS p\n  p.X = 600\n  p.Y = 50\n  LIN p",  # partly set: Z, A, B, C have no value
    "  DECL POS pts[3]\n  pts[2] = {X 600, Y 50, Z 300}\n  LIN pts[2]",
    "  DECL FRAME aux\n  aux.X = 650\n  CIRC aux, {X 600,Y 100,Z 300,A 0,B 90,C 0}",
])
def test_a_position_declared_without_a_value_and_partly_set_is_refused_not_zeroed(tmp_path, body):
    with pytest.raises((InputError, ExecutionError)) as info:  # the controller stops; 0 would move elsewhere
        read(tmp_path, prog(body))
    assert "has no" in str(info.value) and "declared without a value" in str(info.value)
    assert "prog.src:" in str(info.value) and "\n" not in str(info.value)


def test_a_position_set_component_by_component_is_used_once_complete(tmp_path):
    body = "".join(f"  p.{k} = {x}\n" for k, x in zip("XYZABC", (600, 50, 280, 0, 90, 0)))
    r = read(tmp_path, prog(f"  DECL E6POS p\n{body}  LIN p\n  p.X = 620\n  LIN p"))
    assert np.allclose(r.toolpath.moves[1].end.translation_mm, [600, 50, 280])
    assert np.allclose(r.toolpath.moves[2].end.translation_mm, [620, 50, 280])


def test_frames_set_by_the_program_after_an_unknown_fdat_bring_the_motions_back(tmp_path):
    """``FDAT_ACT = FHOME`` ($config.dat's, not loaded) leaves the frames unknown and skips the
    Cartesian motions, until the program sets both $TOOL and $BASE itself."""
    body = ("  FDAT_ACT=FHOME\n  BAS(#PTP_PARAMS,100)\n  PTP {A1 0,A2 -90,A3 90,A4 0,A5 0,A6 0}\n"
            "  $TOOL = {X 0,Y 0,Z 250,A 0,B 0,C 0}\n{base}  LIN {X 0,Y 0,Z 100,A 0,B 180,C 0}\n"
            "  LIN {X 100,Y 0,Z 100,A 0,B 180,C 0}\n")
    from coatsim.robot.cell import load_cell
    from coatsim.robot.kinematics import CellKinematics

    kin = CellKinematics(load_cell())
    only_tool = read(tmp_path, prog(body.replace("{base}", "")), kinematics=kin)
    assert len(only_tool.skipped) == 2 and "FHOME" in only_tool.skipped[0]
    both = read(tmp_path, prog(body.replace("{base}", "  $BASE = {X 700,Y 0,Z 200,A 0,B 0,C 0}\n")), kinematics=kin)
    assert both.skipped == () and len(both.toolpath.moves) == 4
    assert np.allclose(both.toolpath.moves[-1].end.translation_mm, [800, 0, 300])


def test_circ_turns_the_tool_from_start_to_end_whatever_the_auxiliary_point_s_orientation(tmp_path):
    """KRL does not use the auxiliary point's orientation: the tool turns from the start's to
    the end's along the arc, so the via is read with that turn's orientation at its place."""
    from coatsim.geometry.space.pose import slerp

    r = read(tmp_path, prog("  LIN {X 600,Y 0,Z 300,A 0,B 90,C 0}\n"
                            "  CIRC {X 650,Y 50,Z 300,A 40,B 10,C 70},{X 600,Y 100,Z 300,A 90,B 90,C 0}"))
    arc = r.toolpath.moves[2]
    np.testing.assert_allclose(arc.via.rotation, slerp(arc.start.rotation, arc.end.rotation, 0.5)[0], atol=1e-9)
