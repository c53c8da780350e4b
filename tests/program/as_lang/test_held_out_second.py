"""Regressions from a second round of programs written in other cells' styles: unit words as
variable names, program names with characters AS does not allow, error-program returns."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from coatsim.program.as_lang import ast
from coatsim.program.as_lang.interpreter import Interpreter
from coatsim.program.as_lang.parser import parse_as
from coatsim.program.as_lang.source import AsSyntaxError


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
