"""AS files: sections of every kind, line ends, encodings, headers, several programs, data-only
files, and a syntax error naming line and column for every class of defect."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from coatsim.core.errors import InputError
from coatsim.languages.kawasaki_as import ast
from coatsim.languages.kawasaki_as.lexer import tokenize
from coatsim.languages.kawasaki_as.parser import parse_as, parse_as_bytes
from coatsim.core.fileio import decode_text as decode
from coatsim.languages.kawasaki_as.source import AsSyntaxError

from as_samples import ARC_POLISHING, BACKUP, DRAWING, MACHINE_TENDING, PALLETISING

GOLDEN = Path(__file__).resolve().parents[2] / "path" / "data" / "roundrect_polysegment.as"


def test_controller_backup_sections_and_header():
    f = parse_as_bytes(BACKUP, "backup.as")
    assert [p.name for p in f.programs] == ["autostart.pc", "main"]
    assert [s.name for s in f.sections] == ["NETCONF", "LANGUAGE", "ROBOTDATA1", "AUXDATA", "SYSDATA",
                                            "INTER_PANEL_D", "SIG_COMMENT"]
    raw = {s.name: s for s in f.sections}
    assert raw["ROBOTDATA1"].lines[0].startswith("ZROBOT.TYPE") and raw["NETCONF"].lines == ()
    assert raw["SIG_COMMENT"].lines == ('N_OX1 "gun \xf6ffnen"',)
    assert f.trans["home1"].extra == (1200.0,) and f.strings["$cell"].value == "Zelle 3; Halle B"
    main = f.programs[1]
    assert main.line == 25 and main.end_line == 30 and len(main.body) == 4   # leading blanks before .END


def test_program_headers():
    f = parse_as(".PROGRAM a\n.END\n.PROGRAM b() #1234\n.END\n.PROGRAM c(.x, .&y, .$s); #0;comment\n.END\n"
                 ".PROGRAM d ( .p )  @25/11/13 12:08\n.END\n")
    assert [p.name for p in f.programs] == ["a", "b", "c", "d"]
    assert f.programs[2].params == (ast.Param(".x", False), ast.Param(".y", True), ast.Param(".$s", False))
    assert f.programs[3].params == (ast.Param(".p", False),)


def test_data_only_file_and_data_sections():
    f = parse_as(".TRANS\np[3] 1, 2, 3, 0, 90, 0\nP2 1 2 3 4 5 6 7 8 9\n.END\n.JOINTS\n#j 1 2 3 4\n#k[1] 0 0 0 0 0 0 100\n"
                 ".END\n.REALS\nspeed1 = -250\nacc[1,2] = 1.5e2\n.END\n.STRINGS\n$a = \"x ; y\"\n$b[2] = \"\"\n.END\n")
    assert f.programs == ()
    assert f.trans["p[3]"].values == (1, 2, 3, 0, 90, 0) and f.trans["p2"].extra == (7, 8, 9)
    assert f.joints["#j"].values == (1, 2, 3, 4) and f.joints["#k[1]"].values[-1] == 100
    assert f.reals["speed1"].value == -250 and f.reals["acc[1,2]"].value == 150
    assert f.strings["$a"].value == "x ; y" and f.strings["$b[2]"].value == ""


@pytest.mark.parametrize("text", [MACHINE_TENDING, PALLETISING, ARC_POLISHING, DRAWING])
def test_sample_programs_parse(text):
    f = parse_as(text)
    assert f.programs and all(p.body for p in f.programs)


def test_line_ends_case_bom_and_code_pages():
    text = ".program x()\r\n  lmove p1 ; caf\xe9 \xd0\xb1\r  Jmove P1\n .end\r\n"
    f = parse_as_bytes(b"\xef\xbb\xbf" + text.encode("cp1252", errors="replace"))
    assert [s.line for s in f.programs[0].body] == [2, 3]
    utf8 = ".PROGRAM x()\n  TYPE \"Gr\u00fc\u00dfe \u65e5\u672c\"  ; \u30b3\u30e1\u30f3\u30c8\n.END\n".encode("utf-8")
    assert parse_as_bytes(b"\xef\xbb\xbf" + utf8).programs[0].body[0].items == (ast.Str("Gr\u00fc\u00dfe \u65e5\u672c"),)
    shift_jis = ".PROGRAM x()\n  LMOVE p ; \u7d4c\u8def\n.END\n".encode("shift_jis")
    assert len(parse_as_bytes(shift_jis).programs[0].body) == 1
    assert decode(b"\xef\xbb\xbfab") == "ab" and decode(b"a\xe9") == "a\xe9"


def test_trailing_ctrl_z_ends_the_file():
    for tail in (b"\x1a", b"\r\n\x1a", b"\r\n\x1a\x1a\x1a", b"\r\n\x1a\r\n\x1a"):
        f = parse_as_bytes(b".PROGRAM a()\r\n  TWAIT 1\r\n.END" + tail)
        assert [p.name for p in f.programs] == ["a"] and f.programs[0].end_line == 3


def test_metadata_comments():
    f = parse_as(".PROGRAM x()\n  ; coatsim: lead_in_mm=30\n  ;coatsim:variant= polyline-stop \n  ; coatsim prose\n.END\n")
    assert f.programs[0].metadata == (("lead_in_mm", "30"), ("variant", "polyline-stop"))


def test_tokens():
    kinds = [(t.kind, t.text) for t in tokenize('10 .&x $s #j .y ^HFF ^B101 125. .5 1e3 "a;b" <> == <= ; x', "t", 1)]
    assert kinds == [("num", "10"), ("name", ".&x"), ("name", "$s"), ("name", "#j"), ("name", ".y"), ("num", "^HFF"),
                     ("num", "^B101"), ("num", "125."), ("num", ".5"), ("num", "1e3"), ("str", '"a;b"'), ("op", "<>"),
                     ("op", "=="), ("op", "<=")]
    values = [t.value for t in tokenize("^HFF ^B101 125. .5", "t", 1)]
    assert values == [255.0, 5.0, 125.0, 0.5]


# (program text, line, column, words the message must contain)
SYNTAX_ERRORS = [
    (".PROGRAM x()\n  LMOVE p1 ?\n.END\n", 2, 12, "unexpected character"),
    (".PROGRAM x()\n  PRINT \"abc\n.END\n", 2, 9, "string is not closed"),
    (".PROGRAM x()\n  SPEED 1e999\n.END\n", 2, 9, "out of range"),
    (".PROGRAM x()\n  LMOVE p\xe91\n.END\n", 2, 10, "only comments and strings"),
    (".PROGRAM x()\n  FOO p1\n.END\n", 2, 3, "is not an AS instruction"),
    (".PROGRAM x()\n  (LMOVE p1\n.END\n", 2, 3, "expected a statement keyword"),
    (".PROGRAM x()\n  LMOVE\n.END\n", 2, 8, "expected a pose"),
    (".PROGRAM x()\n  LMOVE p1 p2\n.END\n", 2, 12, "expected end of line"),
    (".PROGRAM x()\n  LMOVE SHIFT(p1 1,2,3)\n.END\n", 2, 18, "expected BY"),
    (".PROGRAM x()\n  JAPPRO p1\n.END\n", 2, 12, "expected ','"),
    (".PROGRAM x()\n  SPEED fast MM/H\n.END\n", 2, 17, "expected 'S' or 'MIN'"),
    (".PROGRAM x()\n  SPEED 10 MM/S ALWAYS NOW\n.END\n", 2, 24, "SPEED"),
    # a second (rotation) speed: no AS reference confirms it, so it is refused, not guessed
    (".PROGRAM x()\n  SPEED 100 MM/S, 60 DEG/S\n.END\n", 2, 17, "SPEED with a second speed after ','"),
    (".PROGRAM x()\n  SPEED 100 MM/S, 60 DEG/S ALWAYS\n.END\n", 2, 17, "write SPEED v [unit] [ALWAYS]"),
    # AS has one one-line IF, IF ... GOTO; IF ... THEN opens a block
    (".PROGRAM x()\n  IF n == 1 THEN CALL sub END\n.END\n", 2, 18, "an AS IF ... THEN opens a block"),
    (".PROGRAM x()\n  ACCURACY 1 ALWAYS ALWAYS\n.END\n", 2, 21, "given twice"),
    (".PROGRAM x()\n  ACCURACY 1 SOON\n.END\n", 2, 14, "expected ALWAYS, FINE"),
    (".PROGRAM x()\n  CP MAYBE\n.END\n", 2, 6, "expected ON or OFF"),
    (".PROGRAM x()\n  LMOVE p[1\n.END\n", 2, 12, "expected ',' or ']'"),
    (".PROGRAM x()\n  x = " + "(" * 70 + "1" + ")" * 70 + "\n.END\n", 2, 72, "nested more than 64 deep"),
    (".PROGRAM x()\n  JMOVE p1\n", 2, 1, "end of file inside '.PROGRAM x'"),
    (".PROGRAM x()\n  JMOVE p1\n.PROGRAM y()\n.END\n", 3, 1, "'.PROGRAM' inside program 'x'"),
    (".PROGRAM x()\n.END\n.PROGRAM X()\n.END\n", 3, 1, "defined twice"),
    (".PROGRAM ()\n.END\n", 1, 10, "expected a program name"),
    (".PROGRAM x(.a,)\n.END\n", 1, 15, "parameter name"),
    ("  JMOVE p1\n", 1, 3, "outside a section"),
    ("\n\n.END\n", 3, 1, "without an open section"),
    (".PROGRAM x()\n.END junk\n", 2, 5, "after '.END'"),
    (".TRANS extra\n.END\n", 1, 7, "after '.TRANS'"),
    (". TRANS\n.END\n", 1, 1, "section name"),
    (".TRANS\np1 1 2 3 4 5\n.END\n", 2, 13, "expected 6"),
    (".TRANS\np1 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19\n.END\n", 2, 49, "too many numbers"),  # 6 + 12 external axes at most
    (".TRANS\np1 1 2 x 4 5 6\n.END\n", 2, 8, "expected a number"),
    (".TRANS\np1 1 2 3 4 5 6\nP1 1 2 3 4 5 6\n.END\n", 3, 1, "defined twice (first at line 2)"),
    (".TRANS\n1 2 3 4 5 6 7\n.END\n", 2, 1, "expected a pose name"),
    (".TRANS\np[1.5] 1 2 3 4 5 6\n.END\n", 2, 1, "whole-number array index"),
    (".JOINTS\nhome 0 0 0 0 0 0\n.END\n", 2, 1, "starting with '#'"),
    (".JOINTS\n#home\n.END\n", 2, 6, "has no values"),
    (".REALS\nx 5\n.END\n", 2, 3, "expected '='"),
    (".REALS\nx = 5 6\n.END\n", 2, 7, "too many numbers"),
    (".REALS\nx = five\n.END\n", 2, 5, "expected a number"),
    (".STRINGS\n$a = x\n.END\n", 2, 6, "string in quotes"),
    (".STRINGS\na = \"x\"\n.END\n", 2, 1, "starting with '$'"),
    (".STRINGS\n$a = \"x\"\n", 2, 1, "end of file inside '.STRINGS'"),
    (".AUXDATA\nTOOL1 0 0 0\n", 2, 1, "end of file inside '.AUXDATA'"),
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
    f = parse_as(GOLDEN.read_text(encoding="ascii"))
    assert len(f.trans) == 15 and len(f.programs[0].body) == 26
    assert dict(f.programs[0].metadata)["n_arcs"] == "4"
