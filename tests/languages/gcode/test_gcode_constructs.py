"""One test per G-code construct the reader runs: motions, planes, path control, units, distance
modes, modal state, comments, gun codes, work offsets, parameters, and what it refuses."""

from __future__ import annotations

import math

import numpy as np
import pytest

from coatsim.core.errors import ExecutionError, InputError
from coatsim.geometry.space.primitives import arc_through
from coatsim.geometry.space.rotations import rot_y, rot_z
from coatsim.languages.gcode import flow
from coatsim.languages.gcode.gun import GunCodes
from coatsim.languages.gcode.language import GCode
from coatsim.path.arcs import move_length
from coatsim.languages.registry import language
from coatsim.path.language import ReadOptions

from language_plans import read_text

HEAD = "G21 G90 G17\nG0 X0 Y0 Z100\n"


def run(text, tmp_path, **options):
    return read_text("gcode", text, tmp_path, **options)


def ends(tp):
    return [np.round(getattr(m, "end", None).translation_mm if m.kind != "joint" else m.target.translation_mm, 9)
            for m in tp.moves]


def test_g0_is_a_joint_move_and_g1_a_line_at_the_feed(tmp_path):
    tp = run(HEAD + "G1 X10 F600\n", tmp_path)
    rapid, line = tp.moves
    assert rapid.kind == "joint" and rapid.start is None and rapid.settings.stop_at_end
    assert np.allclose(rapid.target.translation_mm, [0, 0, 100])
    assert line.kind == "line" and np.allclose(line.end.translation_mm, [10, 0, 100])
    assert line.settings.speed_mm_s == pytest.approx(10.0)  # 600 mm/min
    # no tool orientation in G-code: the spray axis is -Z, tool x along -X (Ry(180 deg))
    assert np.allclose(line.end.rotation, rot_y(math.pi))


def test_g2_g3_in_g17_turn_clockwise_and_counter_clockwise_about_z(tmp_path):
    tp = run(HEAD + "G1 X10 F600\nG3 X20 Y10 I0 J10\nG2 X30 Y20 I10 J0\n", tmp_path)
    ccw, cw = tp.moves[2:]
    for move, centre, normal in ((ccw, [10, 10, 100], [0, 0, 1]), (cw, [30, 10, 100], [0, 0, -1])):
        arc = arc_through(move.start.translation_mm, move.via.translation_mm, move.end.translation_mm)
        assert np.allclose(arc.center, centre) and np.allclose(arc.normal, normal)
        assert arc.sweep == pytest.approx(math.pi / 2)


def test_a_full_circle_in_centre_format_is_two_half_turns(tmp_path):
    tp = run(HEAD + "G1 X10 F600\nG2 I-10\nG2 X10 Y0 I-10 J0 P2\n", tmp_path)
    first = tp.moves[2:4]
    assert len(tp.moves) == 2 + 2 + 4
    assert sum(move_length(m) for m in first) == pytest.approx(2 * math.pi * 10)
    assert sum(move_length(m) for m in tp.moves[4:]) == pytest.approx(4 * math.pi * 10)  # P2: two turns


@pytest.mark.parametrize("plane, words, normal", [
    ("G18", "G3 X10 Z110 I0 K10", [0, 1, 0]),   # ZX plane, counter-clockwise about +Y
    ("G18", "G2 X10 Z110 I0 K10", [0, -1, 0]),
    ("G19", "G3 Y10 Z110 J0 K10", [1, 0, 0]),   # YZ plane, counter-clockwise about +X
    ("G19", "G2 Y10 Z110 J0 K10", [-1, 0, 0]),
])
def test_g18_and_g19_arcs_turn_about_y_and_x(tmp_path, plane, words, normal):
    tp = run(HEAD + f"F600\n{plane}\n{words}\n", tmp_path)
    move = tp.moves[-1]
    arc = arc_through(move.start.translation_mm, move.via.translation_mm, move.end.translation_mm)
    assert np.allclose(arc.normal, normal, atol=1e-12)
    assert np.allclose(move.end.translation_mm, [10, 0, 110] if "X" in words else [0, 10, 110])


def test_r_format_arcs_take_the_short_or_the_long_way(tmp_path):
    short = run(HEAD + "G1 X10 F600\nG3 X20 Y10 R10\n", tmp_path).moves[-1]
    long_ = run(HEAD + "G1 X10 F600\nG3 X20 Y10 R-10\n", tmp_path).moves[-2:]
    assert move_length(short) == pytest.approx(math.pi * 5)
    assert sum(move_length(m) for m in long_) == pytest.approx(3 * math.pi * 5)


def test_an_arc_whose_end_is_off_its_circle_is_refused_at_its_line(tmp_path):
    with pytest.raises(InputError, match=r"prog.ngc:4: the start is 10.0000 and the end"):
        run(HEAD + "G1 X10 F600\nG3 X20 Y11 I0 J10\n", tmp_path)


def test_a_small_radius_mismatch_spirals_within_the_controls_tolerance(tmp_path):
    tp = run(HEAD + "G1 X10 F600\nG3 X20 Y10.004 I0 J10\n", tmp_path)
    assert np.allclose(tp.moves[-1].end.translation_mm, [20, 10.004, 100])


def test_path_control_modes(tmp_path):
    corner = "G1 X10 F600\nG1 Y10\nG3 X0 Y20 I-10 J0\nG1 X-10\n"  # a corner, then two tangent junctions
    stop = run(HEAD + "G61.1\n" + corner, tmp_path).moves[1:]
    assert all(m.settings.stop_at_end for m in stop)
    path = run(HEAD + "G61\n" + corner, tmp_path).moves[1:]
    assert [m.settings.stop_at_end for m in path] == [True, False, False, True]
    blend = run(HEAD + "G64 P0.25\n" + corner, tmp_path).moves[1:]
    assert [m.settings.accuracy_mm for m in blend] == [0.25] * 4 and not blend[0].settings.stop_at_end
    free = run(HEAD + "G64\n" + corner, tmp_path).moves[1:]  # as far as the twin rounds: half the shorter move
    assert free[0].settings.accuracy_mm == pytest.approx(5.0)
    once = run(HEAD + "G64 P1\nG1 X10 F600\nG9 G1 Y10\nG1 X0\n", tmp_path).moves[1:]
    assert [m.settings.stop_at_end for m in once] == [False, True, True]


def test_feed_in_mm_per_minute_and_inches_under_g20(tmp_path):
    tp = run("G20 G90\nG0 X0 Y0 Z4\nG1 X1 F60\nG21\nG1 X30 F1200\n", tmp_path)
    inch, mm = tp.moves[1:]
    assert np.allclose(inch.end.translation_mm, [25.4, 0, 101.6])
    assert inch.settings.speed_mm_s == pytest.approx(25.4)
    assert np.allclose(mm.end.translation_mm, [30, 0, 101.6]) and mm.settings.speed_mm_s == pytest.approx(20.0)


def test_g91_moves_are_increments_and_g90_absolute(tmp_path):
    tp = run(HEAD + "G91\nG1 X10 Y5 F600\nX10\nG90\nX0\n", tmp_path)
    assert [list(e) for e in ends(tp)[1:]] == [[10, 5, 100], [20, 5, 100], [0, 5, 100]]


def test_modal_motion_feed_and_plane_persist(tmp_path):
    tp = run(HEAD + "G1 F600 X10\nY10\nZ90\nG18\nG3 X20 Z100 I0 K10\nX30 Z110 I10\n", tmp_path)
    kinds = [m.kind for m in tp.moves]
    assert kinds[:4] == ["joint", "line", "line", "line"] and set(kinds[4:]) == {"arc"}
    assert np.allclose(tp.moves[-1].end.translation_mm, [30, 10, 110])
    assert {m.settings.speed_mm_s for m in tp.moves[1:]} == {10.0}


def test_axis_words_need_a_motion_mode(tmp_path):
    with pytest.raises(InputError, match="prog.ngc:1: axis words without a motion mode"):
        run("X10 Y10\n", tmp_path)


def test_g1_needs_a_feed(tmp_path):
    with pytest.raises(InputError, match="prog.ngc:3: G1 without a feed rate"):
        run(HEAD + "G1 X10\n", tmp_path)


def test_comments_in_both_styles_and_the_process_record(tmp_path):
    text = ("(coatsim: variant=polysegment) ; a note\n; coatsim: lead_in_mm=12\nG21 (mm) G90 ; absolute\n"
            "G0 X0 Y0 Z100 (above) (twice)\nG1 X10 F600 ; feed (with parentheses inside a ; comment)\n")
    tp = run(text, tmp_path)
    assert tp.process.variant == "polysegment" and tp.process.lead_in_mm == 12.0
    assert len(tp.moves) == 2


def test_an_unclosed_comment_is_refused(tmp_path):
    with pytest.raises(InputError, match=r"prog.ngc:2: a comment '\(' is not closed"):
        run("G21\nG0 X0 (oops\n", tmp_path)


def test_the_gun_on_the_default_m3_m5(tmp_path):
    tp = run(HEAD + "G1 X10 F600\nM3\nG1 X20\nG1 X30\nM5\nG1 X40\n", tmp_path)
    assert [m.spray for m in tp.moves] == [False, False, True, True, False]


def test_the_gun_on_m7_m9_as_an_option(tmp_path):
    path = tmp_path / "p.nc"
    path.write_text(HEAD + "M7\nG1 X10 F600\nM9\nG1 X20\nM3\nG1 X30\n")
    tp = GCode(GunCodes(7, 9)).read([path], ReadOptions())
    assert [m.spray for m in tp.moves] == [False, True, False, False]
    assert any("M3 is not the gun (M7/M9)" in w for w in tp.warnings)


def test_motion_synchronised_outputs_are_the_gun_when_they_name_its_output(tmp_path):
    tp = run(HEAD + "M62 P2\nG1 X10 F600\nM63 P2\nM64 P5\nG1 X20\n", tmp_path, gun_signal=2)
    assert [m.spray for m in tp.moves] == [False, True, False]


def test_a_program_that_never_opens_the_gun_says_what_it_switches(tmp_path):
    with pytest.raises(InputError, match=r"never on during a motion; the program switches M8, M9"):
        run(HEAD + "M8\nG1 X10 F600\nM9\n", tmp_path, needs_spray=True)


def test_work_offsets_g10_l2_and_g54_g55(tmp_path):
    tp = run("G21 G90\nG10 L2 P1 X700 Y0 Z200\nG10 L2 P2 X100 R90\nG54\nG0 X0 Y0 Z100\nG55\nG0 X10 Y0 Z0\n", tmp_path)
    first, second = tp.moves
    assert np.allclose(first.target.translation_mm, [700, 0, 300])
    assert np.allclose(second.target.translation_mm, [100, 10, 0])  # G55 turned 90 deg about Z
    assert np.allclose(second.target.rotation, rot_z(math.pi / 2) @ rot_y(math.pi))


def test_work_offsets_the_cell_keeps_come_as_parameters(tmp_path):
    tp = run("G21 G90 G54\nG0 X0 Y0 Z100\n", tmp_path, variables={"5221": 700, "#5223": 200})
    assert np.allclose(tp.moves[0].target.translation_mm, [700, 0, 300])


def test_g10_l20_and_g92_make_the_current_point_read_as_given(tmp_path):
    tp = run(HEAD + "G92 X0 Y0 Z0\nG1 X5 F600\nG92.1\nG10 L20 P1 X0\nG1 X1\n", tmp_path)
    assert np.allclose(tp.moves[1].end.translation_mm, [5, 0, 100])
    assert np.allclose(tp.moves[2].end.translation_mm, [6, 0, 100])


def test_parameters_and_expressions(tmp_path):
    text = HEAD + "#1=10 #<len>=[2*3]\nG1 X[#1*2+#<len>] Y[SQRT[16]] F[ATAN[1]/[1]*10]\n#1=[#1 MOD 3]\nG1 X#1\n"
    tp = run(text, tmp_path)
    assert np.allclose(tp.moves[1].end.translation_mm, [26, 4, 100])
    assert tp.moves[1].settings.speed_mm_s == pytest.approx(450 / 60)
    assert np.allclose(tp.moves[2].end.translation_mm, [1, 4, 100])


def test_a_line_sets_its_parameters_after_reading_its_words(tmp_path):
    tp = run(HEAD + "#1=5\n#1=7 G1 X#1 F600\n", tmp_path)
    assert tp.moves[1].end.translation_mm[0] == 5.0


def test_dwell_and_units_warning(tmp_path):
    tp = run("G90\nG0 X0 Y0 Z100\nG1 X10 F600\nG4 P1.5\nG1 X20\n", tmp_path)
    assert len(tp.dwells) == 1 and tp.dwells[0].seconds == 1.5 and tp.dwells[0].after == 1
    assert tp.moves[1].settings.stop_at_end
    assert any("no G20/G21" in w for w in tp.warnings)


def test_the_first_move_must_say_where_it_goes(tmp_path):
    with pytest.raises(InputError, match="prog.ngc:2: G0 needs to know where the tool is"):
        run("G21 G90\nG0 Z100\n", tmp_path)


@pytest.mark.parametrize("line, what", [
    ("G1 X10 A15 F600", "axis A"), ("G41 D1", "G41"), ("G2 X10 Y10 Z110 I10 F600", "helical arc"),
    ("G81 X1 Y1 Z-1 R1", "G81"), ("M98 P1000", "M98"), ("G93", "inverse-time feed"),
])
def test_what_the_twin_cannot_follow_is_refused_with_exit_3(tmp_path, line, what):
    with pytest.raises(ExecutionError, match=f"prog.ngc:3: .*{what}.* not simulated") as info:
        run(HEAD + line + "\n", tmp_path)
    assert info.value.exit_code == 3


@pytest.mark.parametrize("line, message", [
    ("o100 sub", "o100 sub is never closed"), ("o100 endwhile", "closes no open block"), ("G123", "G123 is not a G-code"), ("G1 X10 X20 F600", "word X twice"),
    ("G1 X1..2 F600", "unexpected"), ("G1 X[1/0] F600", "no finite value"), ("G1 X#<nope> F600", "depends on #<nope>, which the program never sets"),
])
def test_malformed_blocks_are_one_line_input_errors(tmp_path, line, message):
    with pytest.raises(InputError, match=message) as info:
        run(HEAD + line + "\n", tmp_path)
    assert "\n" not in str(info.value) and "prog.ngc:3" in str(info.value)


def test_end_of_program_stops_reading_and_closes_the_gun(tmp_path):
    tp = run(HEAD + "M3\nG1 X10 F600\nM30\nG1 X99\n", tmp_path)
    assert len(tp.moves) == 2 and tp.moves[-1].spray


FLOW_HEAD = "G21 G90 G64 P0\nG0 X600 Y0 Z300\nG1 F600\n"


def _xs(tp) -> list[float]:
    return [round(float(m.end.translation_mm[0]), 6) for m in tp.moves[1:]]


@pytest.mark.parametrize("body, xs", [
    ("#1=0\no10 while [#1 LT 3]\n#1=[#1+1]\nG1 X[600+#1]\no10 endwhile\n", [601, 602, 603]),
    ("#1=0\no11 do\n#1=[#1+1]\nG1 X[600+#1]\no11 while [#1 LT 2]\n", [601, 602]),
    ("o12 repeat [3]\nG91 G1 X5\nG90\no12 endrepeat\n", [605, 610, 615]),
    ("#1=2\no13 if [#1 EQ 1]\nG1 X601\no13 elseif [#1 EQ 2]\nG1 X602\no13 else\nG1 X603\no13 endif\n", [602]),
    ("#1=0\no14 while [1]\n#1=[#1+1]\no15 if [#1 EQ 2]\no14 continue\no15 endif\no16 if [#1 GT 3]\no14 break\no16 endif\n"
     "G1 X[600+#1]\no14 endwhile\n", [601, 603]),
    ("#1=7\no20 sub\nG1 X[600+#1]\n#1=99\no20 endsub\no20 call [3]\no20 call [4]\nG1 X[600+#1]\n", [603, 604, 607]),
    ("#1=0\nWHILE [#1 LT 2] DO1\n#1=#1+1\nG1 X[600+#1*10]\nEND1\n", [610, 620]),
    ("#1=0\nN5 #1=#1+1\nG1 X[600+#1]\nIF [#1 LT 3] GOTO 5\nGOTO 9\nG1 X700\nN9 IF [#1 EQ 3] THEN #2=50\nG1 X[600+#2]\n",
     [601, 602, 603, 650]),
    ("M98 P100 L2\nG1 X650\nM30\nO100\nG91 G1 X10\nG90\nM99\n", [610, 620, 650]),
])
def test_program_flow_o_words_fanuc_macros_and_subprograms(tmp_path, body, xs):
    assert _xs(run(FLOW_HEAD + body, tmp_path)) == xs


def test_a_loop_whose_condition_is_unknown_is_skipped_and_listed(tmp_path):
    path = tmp_path / "prog.ngc"
    path.write_text(FLOW_HEAD + "o10 while [#<count> GT 0]\nG1 X700\no10 endwhile\nG1 X610\n")
    r = language("gcode").reading([path], ReadOptions())
    assert _xs(r.toolpath) == [610] and "#<count>" in r.unknowns[0] and r.skipped


def test_g4_x_is_a_dwell_in_seconds_not_a_motion(tmp_path):
    tp = run(FLOW_HEAD + "G1 X610\nG4 X0.5\nG1 X620\n", tmp_path)
    assert _xs(tp) == [610, 620] and tp.dwells[-1].seconds == 0.5


def test_a_program_that_never_ends_stops_at_the_block_budget(tmp_path, monkeypatch):
    monkeypatch.setattr(flow, "MAX_STEPS", 2_000)  # the budget's size is not the point: it stops, in one line
    with pytest.raises(ExecutionError, match="more than 2000 blocks run: a loop that never ends") as info:
        run(FLOW_HEAD + "#1=0\no10 while [1]\n#1=[#1+1]\no10 endwhile\n", tmp_path)
    assert "\n" not in str(info.value)


@pytest.mark.parametrize("body, words", [
    ("o10 call\n", "no o10 sub"),
    ("GOTO 77\n", "no block N77"),
])
def test_program_flow_errors_are_one_line(tmp_path, body, words):
    with pytest.raises((InputError, ExecutionError), match=words) as info:
        run(FLOW_HEAD + body, tmp_path)
    assert "\n" not in str(info.value)
