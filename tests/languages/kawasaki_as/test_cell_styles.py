"""Regressions found by running programs written the way cells write them (plain
``$DECODE($s, ...)``, any system switch set by name, ...): each parses and means what it says."""

from __future__ import annotations

import pytest

from coatsim.languages.kawasaki_as import ast
from coatsim.languages.kawasaki_as.interpreter import Interpreter
from coatsim.languages.kawasaki_as.parser import parse_as


def run_globals(body: str) -> Interpreter:
    """Interpret a program body without a cell model; the interpreter with its globals."""
    f = parse_as(".PROGRAM t()\n" + body + "\n.END\n", "t.as")
    run = Interpreter((f,), 1, {}, None, 1000.0, 100_000)
    run.run(f.programs[0])
    return run


def test_decode_of_a_plain_string_variable_takes_the_text_off_it():
    run = run_globals('  $ids = "12;7,3"\n  a = VAL($DECODE($ids, ";,", 0))\n  $sep = $DECODE($ids, ";,", 1)\n'
                      '  b = VAL($DECODE($ids, ";,"))\n  .$l = "x y"\n  $w = $DECODE(.$l, " ")')
    g = run.globals
    assert (g.get("real", "a"), g.get("string", "$sep"), g.get("real", "b")) == (12.0, ";", 7.0)
    assert g.get("string", "$ids") == ",3" and g.get("string", "$w") == "x"


@pytest.mark.parametrize("line,name,on", [
    ("DISP.EXESTEP ON", "DISP.EXESTEP", True), ("PROG.DATE ON", "PROG.DATE", True),
    ("autostart.pc ON", "AUTOSTART.PC", True), ("errstart.pc OFF  ;", "ERRSTART.PC", False),
    ("ZREPEAT on", "ZREPEAT", True), ("SWITCH DISPIO_01 = OFF", "DISPIO_01", False),
])
def test_any_system_switch_set_by_name_parses(line, name, on):
    st = [s for s in parse_as(f".PROGRAM t()\n  {line}\n.END\n", "t.as").programs[0].body][0]
    assert st == ast.Switch(2, name, on)
    assert run_globals("  " + line).switches == {name: on}


def _check(tmp_path, text: str):
    from program_helpers import check_as as check_program

    path = tmp_path / "cell.as"
    path.write_text(text)
    return check_program(path)


POSES = ".TRANS\na 600 0 300 0 180 0\nb 700 0 300 0 180 0\nc 700 100 300 0 180 0\n.END\n"


def test_gun_switched_off_after_the_last_motion_is_off_at_the_end(tmp_path):
    done = _check(tmp_path, ".PROGRAM t()\n  JMOVE a\n  BREAK\n  SIGNAL 1\n  LMOVE b\n  BREAK\n  SIGNAL -1\n.END\n" + POSES)
    assert done.toolpath.moves[-1].spray and not any("still on" in p for p in done.problems)
    left_on = _check(tmp_path, ".PROGRAM t()\n  JMOVE a\n  BREAK\n  SIGNAL 1\n  LMOVE b\n.END\n" + POSES)
    assert any("the gun (output 1) is still on at the end" in p for p in left_on.problems)


@pytest.mark.parametrize("moves,words", [
    ("  CVLMOVE b\n  CVLMOVE c\n", "every motion while the gun (output 1) is on is skipped ({f}:5, {f}:6): the "
                                  "program's sprayed path is not read"),
    ("  LMOVE b\n  CVLMOVE c\n", "1 motion while the gun (output 1) is on is skipped ({f}:6): the sprayed path "
                                "read lacks it"),
])
def test_motions_skipped_while_the_gun_is_on_are_a_problem(tmp_path, moves, words):
    """Conveyor tracking (CVLMOVE) is not simulated: its motions are skipped; with the gun on the
    sprayed path read lacks them, which is a problem, not 'no problems found'."""
    done = _check(tmp_path, ".PROGRAM t()\n  JMOVE a\n  BREAK\n  SIGNAL 1\n" + moves + "  BREAK\n  SIGNAL -1\n  CVLMOVE a\n"
                  ".END\n" + POSES)
    assert done.problems == (words.format(f=tmp_path / "cell.as"),)


def test_block_if_and_elseif_without_then():
    run = run_globals('  $ids = "4,5"\n  IF INSTR($ids, ",")\n    a = 1\n  ELSEIF 1\n    a = 2\n  ELSE\n    a = 3\n  END\n'
                      '  IF 0\n    b = 1\n  ELSEIF 1 == 1\n    b = 2\n  END')
    assert (run.globals.get("real", "a"), run.globals.get("real", "b")) == (1.0, 2.0)


def test_an_arc_pair_beyond_a_half_circle_is_a_problem_naming_its_file_and_line(tmp_path):
    """One C1MOVE/C2MOVE pair may sweep up to 180 deg (the manual's split), a half circle within
    rounding of the poses included; more is a problem."""
    half = _check(tmp_path, ".PROGRAM t()\n  JMOVE a\n  C1MOVE b\n  C2MOVE c\n.END\n"
                  ".TRANS\na 600 0 300 0 180 0\nb 650 50 300 0 180 0\nc 600 100.001 300 0 180 0\n.END\n")
    assert not any("arc sweeps" in p for p in half.problems), half.problems
    done = _check(tmp_path, ".PROGRAM t()\n  JMOVE a\n  C1MOVE b\n  C2MOVE c\n.END\n"
                  ".TRANS\na 600 0 300 0 180 0\nb 550 50 300 0 180 0\nc 635.355 85.355 300 0 180 0\n.END\n")
    assert f"{tmp_path / 'cell.as'}:4: arc sweeps 225.0 deg; keep one C1MOVE/C2MOVE pair within 180 deg" \
        in " ".join(done.problems)


def test_a_halt_that_ends_the_program_is_reported(tmp_path):
    from coatsim.core.errors import ExecutionError

    guard = ".PROGRAM t()\n  IF NOT SIG(1001) THEN\n    HALT\n  END\n  JMOVE a\n.END\n" + POSES
    with pytest.raises(ExecutionError, match=r"cell.as:1: program t has no motion \(.*cell.as:3: HALT ends it"):
        _check(tmp_path, guard)
    late = _check(tmp_path, ".PROGRAM t()\n  JMOVE a\n  STOP\n  LMOVE b\n.END\n" + POSES)
    assert len(late.toolpath.moves) == 1 and any("cell.as:3: STOP ends the program here" in w for w in late.warnings)


def test_external_axes_in_poses_are_read_and_ignored_with_a_warning():
    """A 7th axis (a rail, a positioner): POINT/7, TRANS with 7 values, 8-axis .TRANS lines, GROUP."""
    f = parse_as(".PROGRAM t()\n  GROUP -1\n  POINT .c = p\n  POINT/7 .c = TRANS(,,,,,,1200)\n"
                 "  POINT q = TRANS(1, 2, 3, 0, 180, 0, 500, 20)\n  x = DX(.c) + DX(q) + DX(r)\n  JMOVE .c\n.END\n"
                 ".TRANS\np 600 0 300 0 180 0 1500\nr 10 0 0 0 0 0 1 2 3 4 5 6\n.END\n", "t.as")
    run = Interpreter((f,), 1, {}, None, 1000.0, 100_000)
    tp = run.run(f.programs[0])
    assert run.globals.get("real", "x") == 611.0 and len(tp.moves) == 1
    assert tp.moves[0].target.translation_mm.tolist() == [600.0, 0.0, 300.0]
    text = "\n".join(tp.warnings)
    assert "POINT/7: external axes are not simulated" in text and "TRANS values beyond the 6th" in text
    assert "GROUP" in text


def test_a_user_program_with_several_sprayed_stretches_says_which_one_is_compared():
    from coatsim.geometry.space.xyzoat import parse_xyzoat
    from coatsim.path.user import user_program

    two = parse_as(".PROGRAM t()\n  JMOVE a\n  BREAK\n  SIGNAL 1\n  LMOVE b\n  LMOVE c\n  BREAK\n  SIGNAL -1\n"
                   "  LMOVE a\n  BREAK\n  SIGNAL 1\n  LMOVE b\n  BREAK\n  SIGNAL -1\n.END\n" + POSES, "t.as")
    run = Interpreter((two,), 1, {}, None, 1000.0, 100_000)
    user = user_program(run.run(two.programs[0]), parse_xyzoat("0,0,200,0,0,0", "frame"), "")
    assert user.curve.length == pytest.approx(200.0)
    assert user.notes == ("t sprays 2 stretches (300.0 mm in all); its path here is the longest, lines 5-6 "
                          "(200.0 mm), which the other variants spray alone",)


def test_xmove_till_a_signal_already_on_is_not_run_to_its_end():
    from coatsim.core.errors import ExecutionError

    from coatsim.languages.kawasaki_as import interpret_run

    f = parse_as(".PROGRAM t()\n  JMOVE a\n  XMOVE b TILL 1005\n.END\n" + POSES, "t.as")
    run = interpret_run(f, inputs={1005: True})  # skipped with a note; a simulation refuses it (exit 3)
    assert len(run.toolpath.moves) == 1
    with pytest.raises(ExecutionError, match=r"t.as:3: XMOVE skipped: XMOVE \.\.\. TILL 1005: the signal is already"):
        run.require_complete()
    tp = Interpreter((f,), 1, {1005: False}, None, 1000.0, 100_000).run(f.programs[0])
    assert len(tp.moves) == 2 and any("runs to its end" in w for w in tp.warnings)


def test_a_sprayed_stretch_names_the_file_its_lines_are_in(tmp_path):
    from program_helpers import check_as as check_program

    (tmp_path / "main.as").write_text(".PROGRAM m()\n  JMOVE a\n  CALL sprayit\n.END\n")
    (tmp_path / "sub.as").write_text(".PROGRAM sprayit()\n  BREAK\n  SIGNAL 1\n  LMOVE b\n  LMOVE c\n  BREAK\n"
                                     "  SIGNAL -1\n.END\n" + POSES)
    (run,) = check_program([tmp_path / "main.as", tmp_path / "sub.as"]).spray_runs
    assert (run.source, run.first_line, run.last_line, run.moves) == (str(tmp_path / "sub.as"), 4, 5, 2)
