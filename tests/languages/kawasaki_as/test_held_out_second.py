"""Regressions from a second round of programs written in other cells' styles: unit words as
variable names, program names with characters AS does not allow, error-program returns."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from coatsim.languages.kawasaki_as import ast
from coatsim.languages.kawasaki_as.interpreter import Interpreter
from coatsim.languages.kawasaki_as.parser import parse_as
from coatsim.languages.kawasaki_as.source import AsSyntaxError


def run_globals(text: str) -> Interpreter:
    f = parse_as(text, "t.as")
    run = Interpreter((f,), 1, {}, None, 1000.0, 100_000)
    run.run(f.programs[0])
    return run


@pytest.mark.parametrize("word", ["s", "S", "mm", "cm", "deg", "Mm"])
def test_unit_words_are_variable_names_where_an_operand_is_expected(word):
    """`s[1]` is a pose array in a backup; `SPEED mm MM/S` a real named mm: the unit words end an
    expression only where an operator could follow."""
    text = (f".PROGRAM t()\n  {word} = 120\n  SPEED {word} MM/S\n  SPEED {word} * 2 S ALWAYS\n"
            f"  POINT {word}[1] = TRANS({word}, 0, 300)\n  JMOVE {word}[1]\n  JAPPRO {word}[1], {word}\n.END\n")
    body = parse_as(text, "t.as").programs[0].body
    assert body[1] == ast.Speed(3, ast.Name(word), "MM/S", False)
    assert body[2].unit == "S" and body[2].always
    assert isinstance(body[4].target, ast.Name) and body[4].target.name == word
    assert run_globals(text).globals.get("real", word.lower()) == 120.0


@pytest.mark.parametrize("header,col", [
    (".PROGRAM peinture_t\u00e9()", 20), (".PROGRAM a-b()", 11), ("  .PROGRAM a-b()", 13),
    (".PROGRAM main!", 14), (".PROGRAM x$()", 11),
])
def test_a_program_name_with_a_character_as_does_not_allow_is_an_error_at_it(header, col):
    """The name was cut at the first such character and the rest taken for a controller suffix:
    `peinture_té` ran as `peinture_t`."""
    with pytest.raises(AsSyntaxError, match=rf"t\.as:1:{col}: program name '.+' is followed by"):
        parse_as(header + "\n.END\n", "t.as")


@given(st.sampled_from(["", "()", " ()", "\t( )", "() #12", "()@21/03/02 10:11 #2345 ; x", " #0", ";c", "(.a)"]))
@settings(max_examples=20, deadline=None)
def test_controller_suffixes_after_a_program_name_are_still_read(suffix):
    assert parse_as(f".PROGRAM abc.d_1{suffix}\n.END\n", "t.as").programs[0].name == "abc.d_1"


def test_returne_returns_from_an_error_program():
    run = run_globals(".PROGRAM t()\n  CALL trap\n  a = 2\n.END\n.PROGRAM trap()\n  b = 1\n  RETURNE\n  b = 3\n.END\n")
    assert (run.globals.get("real", "a"), run.globals.get("real", "b")) == (2.0, 1.0)


def test_a_sprayed_stretch_traced_by_a_goto_loop_spans_all_its_lines(tmp_path):
    """The stretch of a GOTO raster ends on the loop's first line: it was reported as lines
    13-13 although its moves are on lines 13, 17 and 19."""
    from program_helpers import check_as as check_program

    text = (".PROGRAM r()\n  TOOL TRANS(0,0,250)\n  POINT .a = TRANS(560,-40,300,0,180,0)\n"
            "  POINT .b = TRANS(640,-40,300,0,180,0)\n  .n = 0\n  JMOVE .a\n  BREAK\n  SIGNAL 1\n"
            "10 LMOVE .b\n  .n = .n + 1\n  IF .n >= 3 GOTO 20\n  POINT .b = SHIFT(.b BY 0, 20)\n  LMOVE .b\n"
            "  POINT .a = SHIFT(.a BY 0, 20)\n  LMOVE .a\n  POINT .c = .a\n  POINT .a = .b\n  POINT .b = .c\n"
            "  GOTO 10\n20 BREAK\n  SIGNAL -1\n.END\n")
    path = tmp_path / "r.as"
    path.write_text(text)
    (stretch,) = check_program(path).spray_runs
    assert (stretch.first_line, stretch.last_line, stretch.moves) == (9, 15, 7)
    assert stretch.length_mm == pytest.approx(3 * 80 + 2 * 20)  # after a swap, LMOVE .b is where the arm is


@pytest.mark.parametrize("before,after,dropped", [
    ("", "", ()), ("  JMOVE up\n  SIGNAL 1\n  LMOVE a\n", "", ("first",)),
    ("  JMOVE a\n  BREAK\n  SIGNAL 1\n", "  LMOVE up\n", ("last",)),
    ("  JMOVE up\n  SIGNAL 1\n  LMOVE a\n", "  LMOVE up\n", ("first", "last")),
])
def test_a_user_path_leaves_out_sprayed_moves_to_and_from_its_plane(before, after, dropped):
    """The gun switched on before the approach ends (SIGNAL without BREAK) sprays the descent;
    flattened into the plane it added a line the program sprays in the air to the compared path."""
    from coatsim.geometry.space.xyzoat import parse_xyzoat
    from coatsim.path.user import user_program

    start = before or "  JMOVE a\n  BREAK\n  SIGNAL 1\n"
    text = (".PROGRAM t()\n" + start + "  LMOVE b\n  LMOVE c\n" + after + "  BREAK\n  SIGNAL -1\n.END\n"
            ".TRANS\nup 560 -40 420 0 180 0\na 600 0 300 0 180 0\nb 700 0 300 0 180 0\nc 700 100 300 0 180 0\n.END\n")
    f = parse_as(text, "t.as")
    user = user_program(Interpreter((f,), 1, {}, None, 1000.0, 100_000).run(f.programs[0]),
                        parse_xyzoat("0,0,200,0,0,0", "frame"), "")
    assert user.curve.length == pytest.approx(200.0) and user.height_mm == pytest.approx(100.0)
    assert tuple(n.split(": the ")[1].split()[0] for n in user.notes) == dropped
