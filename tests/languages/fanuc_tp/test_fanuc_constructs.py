"""One test per Fanuc TP construct the reader runs: the file's sections, positions and W-P-R,
J/L/C motions, FINE/CNT/CR, speeds, frames, registers and position registers, control flow,
CALL, WAIT, DO, and what it refuses."""

from __future__ import annotations

import math

import numpy as np
import pytest

from coatsim.core.errors import ExecutionError, InputError
from coatsim.geometry.space.primitives import arc_through
from coatsim.geometry.space.rotations import rot_x, rot_y, rot_z, wpr_to_matrix
from coatsim.languages.fanuc_tp.blend import cnt_accuracy_mm, cnt_for
from coatsim.languages.fanuc_tp.language import FANUC_TP
from coatsim.path.language import ReadOptions

from fanuc_samples import ATTR, DOWN, ls
from language_plans import read_text

P = {1: (500, 0, 300, *DOWN), 2: (600, 0, 300, *DOWN), 3: (650, 50, 300, *DOWN), 4: (600, 100, 300, *DOWN)}


def run(text, tmp_path, **options):
    return read_text("fanuc-tp", text, tmp_path, **options)


def at(move):
    return np.round((move.target if move.kind == "joint" else move.end).translation_mm, 6)


def test_the_sections_of_a_file(tmp_path):
    text = ("/PROG  COAT\t  Macro\n" + ATTR + "\n/APPL\n  AUTO_SINGULARITY_HEADER;\n  ENABLE_SINGULARITY_AVOIDANCE"
            "   : TRUE;\n/MN\n   1:J P[1] 50% FINE ;\n   2:L P[2] 250mm/sec FINE ;\n/POS\n"
            + ls([], P).split("/POS\n")[1])
    tp = run(text, tmp_path)
    assert tp.name == "COAT" and [m.kind for m in tp.moves] == ["joint", "line"]
    assert list(at(tp.moves[1])) == [600, 0, 300]


def test_w_p_r_are_fixed_axis_turns_x_then_y_then_z(tmp_path):
    tp = run(ls(["J P[1] 50% FINE"], {1: (0, 0, 500, 30, -20, 110)}), tmp_path)
    expected = rot_z(math.radians(110)) @ rot_y(math.radians(-20)) @ rot_x(math.radians(30))
    assert np.allclose(tp.moves[0].target.rotation, expected)
    assert np.allclose(wpr_to_matrix(180, 0, 0), rot_x(math.pi))


def test_joint_linear_and_circular_motions(tmp_path):
    body = ["J P[1] 50% FINE", "L P[2] 200mm/sec FINE", "C P[3] :  P[4] 200mm/sec FINE"]
    tp = run(ls(body, P), tmp_path)
    assert [m.kind for m in tp.moves] == ["joint", "line", "arc"]
    arc = arc_through(*(p.translation_mm for p in (tp.moves[2].start, tp.moves[2].via, tp.moves[2].end)))
    assert np.allclose(arc.center, [600, 50, 300]) and arc.sweep == pytest.approx(math.pi)


def test_a_circular_motion_continues_on_a_colon_line(tmp_path):
    text = ls(["J P[1] 50% FINE", "L P[2] 200mm/sec FINE"], P).replace(
        "/POS", "   3:C P[3:via]   \n    :  P[4:end] 200mm/sec CNT50    ;\n/POS")
    assert run(text, tmp_path).moves[-1].kind == "arc"
    from coatsim.languages.fanuc_tp.language import FANUC_TP
    from coatsim.path.check import check_program

    path = tmp_path / "arc.ls"
    path.write_text(text.replace("   3:C", "   3:  DO[1]=ON ;\n   4:C"))
    end = text.replace("   3:C", "   3:  DO[1]=ON ;\n   4:C").splitlines().index("    :  P[4:end] 200mm/sec CNT50    ;") + 1
    report = check_program(path, FANUC_TP)
    assert [(r.first_line, r.last_line) for r in report.spray_runs] == [(end - 1, end)]  # the arc's two lines


def test_fine_cnt_and_cr(tmp_path):
    body = ["J P[1] 50% FINE", "L P[2] 500mm/sec CNT100", "L P[3] 500mm/sec CNT20", "L P[4] 500mm/sec CNT0",
            "L P[1] 500mm/sec CR5", "L P[2] 500mm/sec FINE"]
    moves = run(ls(body, P), tmp_path).moves[1:]
    assert [m.settings.stop_at_end for m in moves] == [False, False, True, False, True]
    assert moves[0].settings.accuracy_mm == pytest.approx(25.0)  # 500 mm/s braking at 5 m/s^2
    assert moves[1].settings.accuracy_mm == pytest.approx(1.0)
    assert moves[3].settings.accuracy_mm == 5.0
    assert cnt_for(1.0, 500.0) == 20 and cnt_for(100.0, 100.0) == 100
    assert cnt_accuracy_mm(cnt_for(0.5, 300.0), 300.0) == pytest.approx(0.5, rel=0.05)


@pytest.mark.parametrize("speed, mm_s", [("250mm/sec", 250.0), ("600cm/min", 100.0), ("120inch/min", 50.8),
                                         ("2sec", 50.0), ("500msec", 200.0), ("25%", 250.0)])
def test_speed_units(tmp_path, speed, mm_s):
    tp = run(ls(["J P[1] 50% FINE", f"L P[2] {speed} FINE"], P), tmp_path)
    assert tp.moves[1].settings.speed_mm_s == pytest.approx(mm_s)


def test_override_scales_every_speed(tmp_path):
    tp = run(ls(["OVERRIDE=50%", "J P[1] 50% FINE", "L P[2] 200mm/sec FINE"], P), tmp_path)
    assert tp.moves[1].settings.speed_mm_s == pytest.approx(100.0)


def test_user_frame_and_tool_selected_and_set_from_a_position_register(tmp_path):
    body = ["PR[9,1]=0", "PR[9,2]=0", "PR[9,3]=250", "PR[9,4]=0", "PR[9,5]=0", "PR[9,6]=0", "UTOOL[2]=PR[9]",
            "PR[9,1]=700", "PR[9,3]=200", "PR[9,6]=90", "UFRAME[3]=PR[9]", "UFRAME_NUM=3", "UTOOL_NUM=2",
            "J P[1] 50% FINE"]
    tp = run(ls(body, {1: (10, 0, 100, *DOWN)}, uf=3, ut=2), tmp_path)
    move = tp.moves[0]
    assert np.allclose(move.target.translation_mm, [700, 10, 300])  # x turned 90 deg about z
    assert np.allclose(move.settings.tool.offset_mm, [0, 0, 250]) and tp.tool is not None


def test_frames_the_cell_keeps_come_as_variables(tmp_path):
    tp = run(ls(["UFRAME_NUM=1", "UTOOL_NUM=1", "J P[1] 50% FINE"], {1: (0, 0, 100, *DOWN)}, uf=1, ut=1), tmp_path,
             variables={"UFRAME[1]": "700,0,200,0,0,0", "UTOOL[1]": "0 0 250 0 0 0"})
    assert np.allclose(tp.moves[0].target.translation_mm, [700, 0, 300])


def test_a_position_taught_in_another_frame_is_refused(tmp_path):
    with pytest.raises(InputError, match=r"MAIN.ls:23: .*taught in UFRAME 1 but UFRAME_NUM=2.*mismatch") as info:
        path = tmp_path / "MAIN.ls"
        path.write_text(ls(["UFRAME_NUM=2", "J P[1] 50% FINE"], P, uf=1))
        FANUC_TP.read([path], ReadOptions(variables={"UFRAME[1]": "0,0,0,0,0,0", "UFRAME[2]": "0,0,0,0,0,0"}))
    assert "\n" not in str(info.value)


def test_an_unknown_user_frame_is_an_unknown_and_an_unknown_tool_a_warning(tmp_path):
    with pytest.raises(InputError, match=r"the motion skipped: it depends on UFRAME\[4\], which the program never"):
        run(ls(["J P[1] 50% FINE"], P, uf=4), tmp_path)
    tp = run(ls(["J P[1] 50% FINE"], P, ut=5), tmp_path)
    assert any("UTOOL[5] is not set" in w for w in tp.warnings) and tp.moves[0].settings.tool is None


def test_registers_and_expressions(tmp_path):
    body = ["R[1]=2", "R[2:count]=R[1]*3+1", "R[3]=(R[2] MOD 4) DIV 1", "R[R[1]]=R[2]-R[1]", "J P[1] 50% FINE",
            "L P[2] R[2]mm/sec CNT R[3]"]
    tp = run(ls(body, P), tmp_path)
    assert tp.moves[1].settings.speed_mm_s == 5.0  # R[2] = 7, then R[R[1]] = R[2] - R[1] sets it to 5
    assert tp.moves[1].settings.accuracy_mm == pytest.approx(cnt_accuracy_mm(3, 5.0))  # R[3] = (7 MOD 4) DIV 1
    tp2 = run(ls(["R[1]=2", "R[R[1]]=9", "J P[1] 50% FINE", "L P[2] R[2]mm/sec FINE"], P), tmp_path)
    assert tp2.moves[1].settings.speed_mm_s == 9.0


def test_a_register_the_cell_keeps_comes_as_a_variable_or_is_an_unknown(tmp_path):
    tp = run(ls(["J P[1] 50% FINE", "L P[2] R[7]mm/sec FINE"], P), tmp_path, variables={"R[7]": 123})
    assert tp.moves[1].settings.speed_mm_s == 123.0
    tp = run(ls(["IF R[8]=0,JMP LBL[1]", "J P[1] 50% FINE", "LBL[1]", "J P[2] 50% FINE"], P), tmp_path,
             variables={"R[8]": 0})
    assert len(tp.moves) == 1
    with pytest.raises(InputError, match=r"prog.ls:22: IF skipped: it depends on R\[8\]"):
        run(ls(["IF R[8]=0,JMP LBL[1]", "J P[1] 50% FINE", "LBL[1]", "J P[2] 50% FINE"], P), tmp_path)


def test_position_registers(tmp_path):
    body = ["PR[1,1]=500", "PR[1,2]=0", "PR[1,3]=300", "PR[1,4]=180", "PR[2]=PR[1]", "PR[2,1]=PR[1,1]+100",
            "PR[3]=PR[2]-PR[1]", "J PR[1] 50% FINE", "L PR[2] 100mm/sec FINE", "PR[4]=LPOS", "L P[1] 100mm/sec FINE",
            "L PR[4] 100mm/sec FINE"]
    tp = run(ls(body, P), tmp_path)
    assert [list(at(m)) for m in tp.moves] == [[500, 0, 300], [600, 0, 300], [500, 0, 300], [600, 0, 300]]
    assert np.allclose(tp.moves[0].target.rotation, rot_x(math.pi))


def test_a_position_register_takes_a_taught_position_and_its_elements_change_it(tmp_path):
    """``PR[i] = P[j]`` copies the position's numbers (the palletising idiom: a taught base,
    then an element raised per layer)."""
    body = ["J P[1] 50% FINE", "PR[10]=P[3]", "PR[10,3]=PR[10,3]+25", "L PR[10] 100mm/sec FINE"]
    tp = run(ls(body, P), tmp_path)
    assert [list(at(m)) for m in tp.moves] == [[500, 0, 300], [650, 50, 325]]
    assert np.allclose(tp.moves[1].end.rotation, rot_x(math.pi))


def test_offset_tool_offset_and_incremental_motions(tmp_path):
    body = ["PR[5,1]=0", "PR[5,2]=10", "PR[5,3]=0", "PR[6,1]=0", "PR[6,3]=-50", "J P[1] 50% FINE",
            "L P[2] 100mm/sec FINE Offset,PR[5]", "L P[2] 100mm/sec FINE Tool_Offset,PR[6]",
            "OFFSET CONDITION PR[5]", "L P[1] 100mm/sec FINE Offset", "L P[3] 100mm/sec FINE INC"]
    tp = run(ls(body, {**P, 3: (5, 0, 0, 0, 0, 0)}), tmp_path)
    ends = [list(at(m)) for m in tp.moves[1:]]
    assert ends[0] == [600, 10, 300]
    assert ends[1] == [600, 0, 350]  # tool z points down: -50 along it is up
    assert ends[2] == [500, 10, 300] and ends[3] == [505, 10, 300]


def test_labels_jumps_and_if(tmp_path):
    body = ["R[1]=0", "J P[1] 50% FINE", "LBL[1:loop]", "R[1]=R[1]+1", "L P[2] 100mm/sec CNT50",
            "L P[1] 100mm/sec CNT50", "IF R[1]<3,JMP LBL[1]", "IF (R[1]=3 AND !DO[4]) THEN", "L P[3] 100mm/sec FINE",
            "ELSE", "L P[4] 100mm/sec FINE", "ENDIF"]
    tp = run(ls(body, P), tmp_path)
    assert len(tp.moves) == 1 + 6 + 1 and list(at(tp.moves[-1])) == [650, 50, 300]


def test_select_and_for(tmp_path):
    body = ["R[2]=2", "SELECT R[2]=1,JMP LBL[1]", "       =2,JMP LBL[2]", "       ELSE,JMP LBL[3]", "LBL[1]",
            "J P[1] 50% FINE", "LBL[2]", "J P[2] 50% FINE", "FOR R[5]=1 TO 3", "L P[3] 100mm/sec FINE",
            "L P[2] 100mm/sec FINE", "ENDFOR", "FOR R[5]=3 DOWNTO 4", "L P[4] 100mm/sec FINE", "ENDFOR", "LBL[3]"]
    tp = run(ls(body, P), tmp_path)
    assert len(tp.moves) == 1 + 6 and list(at(tp.moves[0])) == [600, 0, 300]


def test_call_runs_a_program_from_another_file_with_arguments(tmp_path):
    main = tmp_path / "MAIN.LS"
    main.write_text(ls(["J P[1] 50% FINE", "CALL SIDE(2,150)", "L P[1] 100mm/sec FINE"], P))
    side = tmp_path / "SIDE.LS"
    side.write_text(ls(["L P[2] AR[2]mm/sec FINE", "IF AR[1]=2,JMP LBL[9]", "L P[3] 100mm/sec FINE", "LBL[9]", "END",
                        "L P[4] 100mm/sec FINE"], P, name="SIDE"))
    tp = FANUC_TP.read([main, side], ReadOptions())
    assert [list(at(m)) for m in tp.moves] == [[500, 0, 300], [600, 0, 300], [500, 0, 300]]
    assert tp.moves[1].settings.speed_mm_s == 150.0
    with pytest.raises(InputError, match="CALL SIDE: no program SIDE among the files read"):
        FANUC_TP.read([main], ReadOptions())
    with pytest.raises(InputError, match=r"SIDE.LS:22: AR\[2\]: the CALL gives no number"):
        FANUC_TP.read([main, side], ReadOptions(program="side"))  # run on its own: no arguments


def test_abort_ends_the_run(tmp_path):
    tp = run(ls(["J P[1] 50% FINE", "ABORT", "J P[2] 50% FINE"], P), tmp_path)
    assert len(tp.moves) == 1


def test_wait_for_time_and_for_signals(tmp_path):
    body = ["J P[1] 50% FINE", "L P[2] 100mm/sec CNT100", "WAIT 1.50(sec)", "L P[3] 100mm/sec CNT100",
            "WAIT DI[3]=ON", "L P[4] 100mm/sec CNT100", "WAIT DI[4]=ON", "L P[1] 100mm/sec FINE"]
    tp = run(ls(body, P), tmp_path, inputs={3: True})
    assert [(d.after, d.seconds) for d in tp.dwells] == [(1, 1.5)]
    assert tp.moves[1].settings.stop_at_end and not tp.moves[2].settings.stop_at_end
    assert any("DI[4] is not set" in w for w in tp.warnings) and any("taken as met" in w for w in tp.warnings)


def test_a_wait_that_can_never_be_met(tmp_path):
    with pytest.raises(ExecutionError, match=r"MAIN.ls:23: WAIT can never be met"):
        path = tmp_path / "MAIN.ls"
        path.write_text(ls(["J P[1] 50% FINE", "WAIT DI[3]=ON"], P))
        FANUC_TP.read([path], ReadOptions(inputs={3: False}))
    tp = run(ls(["J P[1] 50% FINE", "WAIT DI[3]=ON TIMEOUT,LBL[2]", "J P[2] 50% FINE", "LBL[2]"], P), tmp_path,
             inputs={3: False})
    assert len(tp.moves) == 1


def test_do_switches_the_gun_from_the_next_motion(tmp_path):
    body = ["J P[1] 50% FINE", "DO[1]=ON", "L P[2] 100mm/sec CNT100", "DO[2]=ON", "L P[3] 100mm/sec CNT100",
            "DO[1]=OFF", "L P[4] 100mm/sec FINE"]
    tp = run(ls(body, P), tmp_path)
    assert [m.spray for m in tp.moves] == [False, True, True, False]
    with pytest.raises(InputError, match=r"gun \(DO\[3\]\) is never on during a motion; the program switches "
                                         r"DO\[1\], DO\[2\]"):
        run(ls(body, P), tmp_path, gun_signal=3, needs_spray=True)


def test_remarks_carry_the_process_record_and_disabled_lines_are_skipped(tmp_path):
    body = ["!coatsim: variant=polyline-blend", "!coatsim: speed_limits=0.0000:1.0000:", "!coatsim& 50.0000",
            "J P[1] 50% FINE", "//L P[2] 100mm/sec FINE"]
    tp = run(ls(body, P), tmp_path)
    assert tp.process.variant == "polyline-blend" and len(tp.moves) == 1
    assert tp.process.contours[0].speed_limits[0].v_max_mm_s == 50.0


@pytest.mark.parametrize("body, message", [
    (["L P[9] 100mm/sec FINE"], r"P\[9\] is not in the program's /POS"),
    (["J P[1] 50% CNT150"], "CNT150: from 0 to 100"),
    (["J P[1] 50%"], "a motion ends FINE"),
    (["L P[1] 100 FINE"], "needs a unit"),
    (["JMP LBL[3]"], r"has no LBL\[3\]"),
    (["ENDIF"], "ENDIF without its IF"),
    (["R[1]=1/0"], "no finite value"),
    (["L PR[3] 100mm/sec FINE"], r"it depends on PR\[3\], which the program never sets"),
])
def test_defects_are_one_line_input_errors_naming_the_line(tmp_path, body, message):
    with pytest.raises(InputError, match=message) as info:
        run(ls(body, P), tmp_path)
    assert "prog.ls:2" in str(info.value) and "\n" not in str(info.value)


def test_an_instruction_without_its_semicolon(tmp_path):
    with pytest.raises(InputError, match="does not end with ';'"):
        run(ls(["J P[1] 50% FINE"], P).replace("FINE ;", "FINE"), tmp_path)


@pytest.mark.parametrize("body, what", [(["J P[1] 50% FINE", "A P[2] 100mm/sec CNT100"], "the A motion"),
                                        (["J P[1] 50% FINE", "L P[2] 30deg/sec FINE"], "deg/sec"),
                                        (["J P[1] 50% FINE", "L P[2] WELD_SPEED FINE"], "WELD_SPEED")])
def test_what_the_twin_cannot_run_is_exit_3(tmp_path, body, what):
    with pytest.raises(ExecutionError, match=what) as info:
        run(ls(body, P), tmp_path)
    assert info.value.exit_code == 3


def test_application_instructions_and_options_are_noted(tmp_path):
    tp = run(ls(["J P[1] 50% FINE", "L P[2] 100mm/sec CNT100 TB .50sec,CALL GUN_ON", "Arc Start[1]",
                 "RUN MONITOR", "L P[3] 100mm/sec FINE ACC80 Wjnt"], P), tmp_path)
    assert len(tp.moves) == 3 and len(tp.warnings) == 3


def test_joint_positions_need_the_cell(tmp_path):
    text = ls(["J P[1] 50% FINE"], {}).replace("/POS\n", "/POS\nP[1]{\n   GP1:\n\tUF : 0, UT : 0,\n"
                                                  "\tJ1= 0 deg, J2= 0 deg, J3= 0 deg, J4= 0 deg, J5= -90 deg, "
                                                  "J6= 0 deg\n};\n")
    with pytest.raises(InputError, match=r"P\[1\] holds joint values; reading it needs the cell"):
        run(text, tmp_path)
    from coatsim.robot.cell import load_cell
    from coatsim.robot.kinematics import CellKinematics

    tp = run(text, tmp_path, kinematics=CellKinematics(load_cell()))
    assert np.allclose(np.degrees(tp.moves[0].joints_rad), [0, 0, 0, 0, -90, 0])


def test_an_application_speed_is_read_but_not_run(tmp_path):
    """check-program reads a motion at a speed an application sets (WELD_SPEED) and lists it as a
    statement not simulated; running the program refuses it in one line (exit 3)."""
    from coatsim.core.errors import ExecutionError
    from coatsim.languages.fanuc_tp.language import FANUC_TP
    from coatsim.path.language import ReadOptions

    path = tmp_path / "prog.ls"
    path.write_text(ls(["J P[1] 50% FINE", "DO[1]=ON", "L P[2] WELD_SPEED CNT100", "DO[1]=OFF"], P))
    reading = FANUC_TP.reading([path], ReadOptions())
    assert len(reading.toolpath.moves) == 2 and reading.toolpath.moves[1].spray
    assert reading.unsimulated == reading.skipped and len(reading.skipped) == 1
    assert "prog.ls:" in reading.skipped[0] and "WELD_SPEED" in reading.skipped[0]
    assert [s.text for s in reading.switches] == ["DO[1]=ON (gun on)", "DO[1]=OFF (gun off)"]
    with pytest.raises(ExecutionError, match=r"WELD_SPEED .*not simulated"):
        FANUC_TP.read([path], ReadOptions())
