"""Kawasaki AS reader: sections, statements, and a syntax error with its line for every class."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from coatsim.errors import InputError
from coatsim.program.as_lang import ast
from coatsim.program.as_lang.source import AsSyntaxError
from coatsim.program.as_lang.parser import parse_as, parse_as_bytes

REFERENCE_B = """\
.PROGRAM sq_named()
  BASE NULL
  TOOL TRANS(0,0,150,0,0,0)
  SPEED 100 MM/S ALWAYS
  ACCURACY 1 ALWAYS
  LAPPRO e1s, 50        ; 50 mm above e1s along tool Z
  LMOVE e1s
  BREAK
  SIGNAL 5
  LMOVE e1e
  C1MOVE c1v
  C2MOVE e1s
  BREAK
  SIGNAL -5
  LDEPART 50
.END
.TRANS
e1s 520.000 -100.000 200.000 0.000 180.000 0.000
e1e 680.000 -100.000 200.000 0.000 180.000 0.000
c1v 694.142 -94.142 200.000 0.000 180.000 0.000
.END
"""


def test_reference_example_with_trans_section():
    f = parse_as(REFERENCE_B, "b.as")
    (prog,) = f.programs
    assert prog.name == "sq_named" and prog.line == 1
    assert [type(s).__name__ for s in prog.statements] == [
        "Base", "Tool", "Speed", "Accuracy", "Appro", "Move", "Break", "Signal", "Move", "Move", "Move",
        "Break", "Signal", "Depart"]
    assert prog.statements[2] == ast.Speed(4, 100.0, "MM/S", True)
    assert prog.statements[4] == ast.Appro(6, "LAPPRO", ast.PoseName("e1s"), 50.0)
    assert prog.statements[12] == ast.Signal(14, (-5,))
    assert f.trans["c1v"] == ast.TransDef("c1v", (694.142, -94.142, 200.0, 0.0, 180.0, 0.0), (), 20)


def test_all_statement_forms():
    text = """\
.PROGRAM all(a, b) ; header comment
  10 JMOVE #home
  LMOVE p1, 1
  start: LMOVE SHIFT(p1 BY 1, -2, 3.5)
  lmove TRANS(1,2,3,4,5,6) + p[2]
  JAPPRO p1, d
  JDEPART -5
  DRAW 1, 2, 3
  TDRAW 1, 2, 3, 0, 0, 0
  HOME 2
  HOME
  DELAY 0.5
  SPEED 30
  SPEED 20 %
  SPEED 600 mm/min
  SPEED 2 S ALWAYS
  ACCURACY 0.5 FINE
  ACCURACY 3 ALWAYS FINE
  ACCEL 80 ALWAYS
  DECEL 50
  CP OFF
  SIGNAL 1, -2, 25
  TWAIT .2
  TOOL NULL
  BASE TRANS(0,0,100,0,0,0)
  POINT q = SHIFT(SHIFT(p1 BY 1,0,0) BY 0,1,0)
  JMOVE #[0, 10, 20, 0, 30, 0]
  20
.END
"""
    st = parse_as(text).programs[0].statements
    assert st[0] == ast.Move(2, "JMOVE", ast.JointName("#home"))
    assert st[1] == ast.Move(3, "LMOVE", ast.PoseName("p1"), 1.0)
    assert st[2].target == ast.Shift(ast.PoseName("p1"), (1.0, -2.0, 3.5))
    assert st[3].target == ast.Compose(ast.TransLiteral((1.0, 2.0, 3.0, 4.0, 5.0, 6.0)), ast.PoseName("p[2]"))
    assert st[4].distance == ast.RealRef("d")
    assert st[5] == ast.Depart(7, "JDEPART", -5.0)
    assert st[7].deltas == (1.0, 2.0, 3.0, 0.0, 0.0, 0.0)
    assert (st[8].number, st[9].number) == (2, None)
    assert [(s.value, s.unit, s.always) for s in st[11:15]] == [
        (30.0, "%", False), (20.0, "%", False), (600.0, "MM/MIN", False), (2.0, "S", True)]
    assert (st[15].fine, st[15].always, st[16].fine, st[16].always) == (True, False, True, True)
    assert st[17] == ast.Accel(19, "ACCEL", 80.0, True)
    assert st[19] == ast.Cp(21, False)
    assert st[20].outputs == (1, -2, 25)
    assert st[21].seconds == 0.2
    assert st[22].pose == ast.NullPose()
    assert isinstance(st[24].pose.base, ast.Shift)
    assert st[25].target == ast.JointLiteral((0.0, 10.0, 20.0, 0.0, 30.0, 0.0))
    assert len(st) == 26   # the label-only line adds nothing


def test_data_sections_unknown_sections_and_header_lines():
    text = (".* controller backup header\n"
            ".NETCONF\n  anything goes here ; even @#!\n.END\n"
            ".PROGRAM main(); #0;comment\n  JMOVE p1\n.END\n"
            ".PROGRAM id4()@25/11/13 12:08 #4; text\n  JMOVE p1\n.END\n"
            ".TRANS\np1 1 2 3 4 5 6 7\narr[3] -1 -2 -3 0 90 0\n.END\n"
            ".JOINTS\n#home 0 10 20 30 40 50\n#tx1[2] 0 0 0 0 0 0 100\n.END\n"
            ".REALS\nspeed1 = 250\nacc[1,2] = -0.5\n.END\n"
            ".STRINGS\n$msg = \"hello ; there\"\n.END\n")
    f = parse_as(text)
    assert [p.name for p in f.programs] == ["main", "id4"]
    assert f.trans["p1"].values == (1, 2, 3, 4, 5, 6) and f.trans["p1"].extra == (7.0,)
    assert f.trans["arr[3]"].values[4] == 90.0
    assert f.joints["#tx1[2]"].values[-1] == 100.0
    assert f.reals["acc[1,2]"].value == -0.5 and f.reals["speed1"].value == 250.0
    assert f.skipped == (("NETCONF", 2), ("STRINGS", 23))


def test_line_ends_case_and_non_ascii_comments():
    text = ".program x()\r\n  lmove p1 ; caf\xe9 \xd0\xb1\r  Jmove P1\n.end\r\n"
    f = parse_as_bytes(text.encode("latin-1"))
    assert [s.line for s in f.programs[0].statements] == [2, 3]


def test_metadata_comments():
    f = parse_as(".PROGRAM x()\n  ; coatsim: lead_in_mm=30\n  ;coatsim:variant= polyline-stop \n  ; coatsim prose\n.END\n")
    assert f.programs[0].metadata == (("lead_in_mm", "30"), ("variant", "polyline-stop"))


# (program text, line, column, words the message must contain)
SYNTAX_ERRORS = [
    (".PROGRAM x()\n  LMOVE p1 ?\n.END\n", 2, 12, "unexpected character"),
    (".PROGRAM x()\n  PRINT \"abc\n.END\n", 2, 9, "string is not closed"),
    (".PROGRAM x()\n  SPEED 1e999\n.END\n", 2, 9, "out of range"),
    (".PROGRAM x()\n  FOO p1\n.END\n", 2, 3, "is not an AS statement"),
    (".PROGRAM x()\n  CALL sub\n.END\n", 2, 3, "not in the AS subset"),
    (".PROGRAM x()\n  x = 5\n.END\n", 2, 3, "assignment"),
    (".PROGRAM x()\n  (LMOVE p1\n.END\n", 2, 3, "expected a statement keyword"),
    (".PROGRAM x()\n  LMOVE\n.END\n", 2, 8, "expected a pose"),
    (".PROGRAM x()\n  LMOVE p1 p2\n.END\n", 2, 12, "expected end of line"),
    (".PROGRAM x()\n  LMOVE TRANS(1,2,3)\n.END\n", 2, 20, "expected ','"),
    (".PROGRAM x()\n  LMOVE SHIFT(p1 1,2,3)\n.END\n", 2, 18, "expected 'BY'"),
    (".PROGRAM x()\n  JAPPRO p1\n.END\n", 2, 12, "expected ','"),
    (".PROGRAM x()\n  SPEED fast MM/H\n.END\n", 2, 17, "expected 'S' or 'MIN'"),
    (".PROGRAM x()\n  SPEED 10 MM/S ALWAYS NOW\n.END\n", 2, 24, "SPEED"),
    (".PROGRAM x()\n  ACCURACY 1 ALWAYS ALWAYS\n.END\n", 2, 21, "given twice"),
    (".PROGRAM x()\n  ACCURACY 1 SOON\n.END\n", 2, 14, "expected ALWAYS, FINE"),
    (".PROGRAM x()\n  CP MAYBE\n.END\n", 2, 6, "expected ON or OFF"),
    (".PROGRAM x()\n  SIGNAL 1.5\n.END\n", 2, 10, "whole number"),
    (".PROGRAM x()\n  SIGNAL 0\n.END\n", 2, 10, "signal number 0"),
    (".PROGRAM x()\n  POINT #j = p1\n.END\n", 2, 9, "joint variable"),
    (".PROGRAM x()\n  LMOVE p[1.5]\n.END\n", 2, 11, "array index"),
    (".PROGRAM x()\n  LMOVE p[1\n.END\n", 2, 12, "expected ']'"),
    (".PROGRAM x()\n  LMOVE " + "SHIFT(" * 20 + "p" + " BY 0,0,0)" * 20 + "\n.END\n", 2, 99, "nested"),
    (".PROGRAM x()\n  JMOVE p1\n", 2, 1, "end of file inside '.PROGRAM x'"),
    (".PROGRAM x()\n  JMOVE p1\n.PROGRAM y()\n.END\n", 3, 1, "'.PROGRAM' inside program 'x'"),
    (".PROGRAM x()\n.END\n.PROGRAM X()\n.END\n", 3, 1, "defined twice"),
    (".PROGRAM ()\n.END\n", 1, 10, "expected a program name"),
    ("  JMOVE p1\n", 1, 3, "outside a section"),
    ("\n\n.END\n", 3, 1, "without an open section"),
    (".PROGRAM x()\n.END junk\n", 2, 5, "after '.END'"),
    (".TRANS extra\n.END\n", 1, 7, "after '.TRANS'"),
    (". TRANS\n.END\n", 1, 1, "dot-section name"),
    (".TRANS\np1 1 2 3 4 5\n.END\n", 2, 13, "expected 6"),
    (".TRANS\np1 1 2 3 4 5 6 7 8\n.END\n", 2, 18, "too many numbers"),
    (".TRANS\np1 1 2 x 4 5 6\n.END\n", 2, 8, "expected a number"),
    (".TRANS\np1 1 2 3 4 5 6\np1 1 2 3 4 5 6\n.END\n", 3, 1, "defined twice (first at line 2)"),
    (".TRANS\n1 2 3 4 5 6 7\n.END\n", 2, 1, "expected a pose name"),
    (".JOINTS\nhome 0 0 0 0 0 0\n.END\n", 2, 1, "starting with '#'"),
    (".JOINTS\n#home 0 0 0\n.END\n", 2, 12, "expected 6 to 9"),
    (".REALS\nx 5\n.END\n", 2, 3, "expected '='"),
    (".REALS\nx = 5 6\n.END\n", 2, 7, "expected end of line"),
    (".REALS\nx = five\n.END\n", 2, 5, "expected a number"),
    (".STRINGS\n$a = \"x\"\n", 2, 1, "end of file inside '.STRINGS'"),
]


@pytest.mark.parametrize("text,line,col,words", SYNTAX_ERRORS)
def test_syntax_errors_name_line_and_column(text, line, col, words):
    with pytest.raises(AsSyntaxError) as info:
        parse_as(text, "prog.as")
    message = str(info.value)
    assert isinstance(info.value, InputError) and "\n" not in message
    m = re.match(r"prog\.as:(\d+):(\d+): ", message)
    assert m is not None, message
    assert int(m.group(1)) == line, message
    if col != 99:
        assert int(m.group(2)) == col, message
    assert words in message


def test_golden_program_parses():
    text = (Path(__file__).parent / "data" / "roundrect_polysegment.as").read_text(encoding="ascii")
    f = parse_as(text)
    assert len(f.trans) == 15 and len(f.programs[0].statements) == 26
    assert dict(f.programs[0].metadata)["n_arcs"] == "4"
