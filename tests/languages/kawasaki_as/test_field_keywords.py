"""Keywords as field programs hold them: abbreviated instruction words (``ty "pass"``), variables
named like keywords (``value[i] = VAL($temp)``), and every entry of the manual's instruction
and function index parsing, in every author's style."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from coatsim.core.errors import ExecutionError
from coatsim.languages.kawasaki_as import ast, parse_as
from coatsim.languages.kawasaki_as.instructions import COMMANDS, DISPLAY
from coatsim.languages.kawasaki_as.interpreter import Interpreter
from coatsim.languages.kawasaki_as.source import AsSyntaxError
from coatsim.languages.kawasaki_as.statements import KEYWORDS, PARSERS

from styles import STYLES, notes, run_text, styled

POSES = ".TRANS\npick 640 -220 300 0 180 0\nplace 640 220 320 0 180 0\n.END\n"


# --- abbreviations ---------------------------------------------------------------------------
@pytest.mark.parametrize("short,full", [
    ("TY", "TYPE"), ("SPE", "SPEED"), ("ACCU", "ACCURACY"), ("JM", "JMOVE"), ("LM", "LMOVE"), ("TWA", "TWAIT"),
    ("TW", "TWAIT"), ("BRE", "BREAK"), ("LDEP", "LDEPART"), ("JAPP", "JAPPRO"), ("SWAI", "SWAIT"), ("SIGN", "SIGNAL"),
    ("RET", "RETURN"), ("HOM", "HOME"), ("BIT", "BITS"), ("DECO", "DECOMPOSE"), ("POI", "POINT"), ("PROM", "PROMPT"),
])
def test_an_abbreviation_is_the_one_instruction_it_starts(short, full):
    full_word, matches = KEYWORDS.expand(short)
    assert full_word == full and all(m.startswith(full) for m in matches)


@pytest.mark.parametrize("style", STYLES)
def test_abbreviated_keywords_read_as_written_out(style):
    short = ('TY "pass"\nSPE 60 ALWAYS\nACCU 10 ALWAYS\nJM pick\nSIGN 10, -9\nLM place\nBRE\nTWA 0.3\nLDEP 80\n'
             'JAPP pick, 50')
    full = ('TYPE "pass"\nSPEED 60 ALWAYS\nACCURACY 10 ALWAYS\nJMOVE pick\nSIGNAL 10, -9\nLMOVE place\nBREAK\n'
            'TWAIT 0.3\nLDEPART 80\nJAPPRO pick, 50')
    a, b = parse_as(styled(short, style, POSES), "f.as"), parse_as(styled(full, style, POSES), "f.as")
    assert a.programs[0].body == b.programs[0].body
    run = run_text(styled(short, style, POSES))
    assert [m.kind for m in run.toolpath.moves] == ["joint", "line", "line", "joint"] and run.outputs == (9, 10)


@pytest.mark.parametrize("line,words", [
    ("ACC 10", "'ACC' abbreviates several AS instructions (ACCEL, ACCEPT, ACCURACY); write the one meant in full"),
    ("s 10", "'s' abbreviates several AS instructions (SAVE, SC2RECEIVE, SC2SEND, SCALL, SCASE, SCNT, ...)"),
    ("frob 1", "'frob' is not an AS instruction coatsim knows"),
])
def test_an_ambiguous_or_unknown_word_is_one_line_naming_the_candidates(line, words):
    with pytest.raises(AsSyntaxError, match="f.as:2:3: ") as info:
        parse_as(f".PROGRAM t()\n  {line}\n.END\n", "f.as")
    assert words in str(info.value) and "\n" not in str(info.value)


def test_an_abbreviation_of_several_instructions_is_the_one_the_line_reads_as():
    body = parse_as(".PROGRAM t()\n  SW 1001\n  sw repeat ON\n.END\n", "f.as").programs[0].body
    assert body == (ast.Swait(2, (ast.Num(1001.0),)), ast.Switch(3, "REPEAT", True))


@pytest.mark.parametrize("style", STYLES)
def test_qualifiers_read_shortened_as_typed_on_the_pendant(style):
    short = "SPE 60 MM/S ALW\nACCU 10 al FI\nACCEL 50 ALWA\nJM pick\nLM place"
    full = "SPEED 60 MM/S ALWAYS\nACCURACY 10 ALWAYS FINE\nACCEL 50 ALWAYS\nJMOVE pick\nLMOVE place"
    a, b = parse_as(styled(short, style, POSES), "f.as"), parse_as(styled(full, style, POSES), "f.as")
    assert a.programs[0].body == b.programs[0].body


@pytest.mark.parametrize("line", ["SPEED 60 A", "SPEED 60 ALWAYSX", "ACCURACY 1 F", "ACCURACY 1 ALWAYS ALW"])
def test_a_qualifier_shortened_to_one_letter_or_misspelt_is_refused(line):
    with pytest.raises(AsSyntaxError, match="f.as:2:"):
        parse_as(f".PROGRAM t()\n  {line}\n.END\n", "f.as")


def test_an_abbreviation_never_takes_an_assignment_a_label_or_a_switch():
    body = parse_as(".PROGRAM t()\n  ty = 5\n  lm[2] = 1\n  start:\n  disp.exestep ON\n  10 ty ty\n.END\n", "f.as")
    st0, st1, label, switch, step, out = body.programs[0].body
    assert isinstance(st0, ast.Assign) and st0.target.name == "ty"
    assert isinstance(st1, ast.Assign) and st1.target.name == "lm"
    assert label == ast.Label(4, "start") and switch == ast.Switch(5, "DISP.EXESTEP", True)
    assert step == ast.Label(6, "10") and out == ast.Output(6, "TYPE", (ast.Name("ty"),))


KEYWORD_LINES = {"TYPE": '"x"', "SPEED": "50 ALWAYS", "ACCURACY": "1 FINE", "LMOVE": "place", "JMOVE": "pick",
                 "TWAIT": "0.5", "SIGNAL": "-9", "LDEPART": "30", "LAPPRO": "pick, 40", "SWAIT": "1001",
                 "DECOMPOSE": "d[1] = pick", "PULSE": "9, 0.2", "DRAW": "10, 0, 0", "CALL": "sub"}


@settings(max_examples=60, deadline=None)
@given(st.sampled_from(sorted(KEYWORD_LINES)), st.data())
def test_every_unambiguous_start_of_an_instruction_parses_as_the_instruction(word, data):
    cut = data.draw(st.integers(1, len(word)))
    prefix = data.draw(st.sampled_from([word[:cut], word[:cut].lower()]))
    full, _ = KEYWORDS.expand(prefix.upper())
    text = ".PROGRAM t()\n  {} {}\n.END\n.PROGRAM sub()\n.END\n"
    if full is None:  # ambiguous, unless the line reads as only one of the instructions it starts: this one
        try:
            body = parse_as(text.format(prefix, KEYWORD_LINES[word]), "f.as").programs[0].body
        except AsSyntaxError as e:
            assert "abbreviates several AS instructions" in str(e)
        else:
            assert body == parse_as(text.format(word, KEYWORD_LINES[word]), "f.as").programs[0].body
    elif full == word:
        assert parse_as(text.format(prefix, KEYWORD_LINES[word]), "f.as").programs[0].body == \
            parse_as(text.format(word, KEYWORD_LINES[word]), "f.as").programs[0].body


# --- variables named like keywords ------------------------------------------------------------
@pytest.mark.parametrize("style", STYLES)
def test_variables_named_like_keywords(style):
    body = ('$temp = "12"\nFOR i = 1 TO 2\nvalue[i] = VAL($temp) + i\nEND\nstep = 2\nlen = 0\nto = 5\n'
            "FOR i = 1 TO to STEP step\nlen = len + 1\nEND\ntype = len * 10 + value[2]")
    f = parse_as(styled(body, style), "f.as")
    interp = Interpreter((f,), 1, {}, None, 1000.0, 100_000)
    interp.run(f.programs[0])
    get = lambda k: interp.globals.get("real", k)  # noqa: E731
    assert (get("value[1]"), get("value[2]"), get("len"), get("type")) == (13.0, 14.0, 3.0, 44.0)
    assert interp.warnings.lines == [] and interp.unknowns.first == {}


def test_a_value_statement_is_still_a_case_branch():
    f = parse_as(".PROGRAM t()\n  CASE x OF\n    VALUE 1, 2:\n      value = 1\n    ANY :\n      value[1] = 2\n  END\n"
                 ".END\n", "f.as")
    (case,) = f.programs[0].body
    assert isinstance(case, ast.Case) and case.branches[0][0] == (ast.Num(1.0), ast.Num(2.0))
    assert isinstance(case.default[0], ast.Assign) and case.default[0].target.index == (ast.Num(1.0),)


# --- the manual's index ------------------------------------------------------------------------
def test_no_command_group_hides_an_instruction_parser():
    specific = set(PARSERS) - COMMANDS
    assert not (specific & COMMANDS)
    assert {"L3ACCURACY", "MVWAIT", "HSENSESET", "SETPICK", "CVSET", "SJUMP", "USB_SAVE"} <= COMMANDS


@pytest.mark.parametrize("line", [
    "WEIGHT 12.5, 0, 0, 80", "ULIMIT 170, 130, 90, 270, 120, 360", "L3ACCURACY 1", "ON 1010 CALL stop.cycle",
    "IGNORE 1010", "RUNMASK 9, 4", "SETHOME 1, #[0, 0, 35, 0, 55, 0]", "HSENSESET 2 = 1001, 3", "MVWAIT 10 MM",
    "SIGPOINT", "OPEINFOCLR", "TIMER 1 = 0", "UTIMER @t1 = 0", "SOUT 9 = 1001", "CVSET 1, 2", "FFSET 1",
    "SAVE/S file.as", "PRIME main, 1", "COLMVON", "STRGSTART", "PLCAOUT 1, 2", "FB_SET_WORD 1, 2",
])
def test_instructions_of_the_index_parse_and_are_noted(line):
    run = run_text(f".PROGRAM t()\n  {line}\n  JMOVE pick\n.END\n.PROGRAM stop.cycle()\n.END\n" + POSES)
    assert len(run.toolpath.moves) == 1 and run.skipped == ()
    if line.split()[0] in DISPLAY:
        assert notes(run) == ""
    else:
        assert notes(run).startswith("f.as:2: ") and "not simulated" in notes(run) and "\n" not in notes(run)


@pytest.mark.parametrize("line,words", [
    ("ALIGN", "ALIGN skipped: ALIGN moves the arm in a way coatsim does not simulate"),
    ("DRIVE 1, 10, 50", "DRIVE skipped: DRIVE after a motion to a transformation (line 2) is not simulated"),
    ("SJUMP place", "SJUMP skipped"),
    ("LINEAR 125. ACCU1 TIMER0", "LINEAR skipped: a teach-pendant block step"),
])
def test_motions_the_twin_does_not_simulate_are_skipped_with_a_note(line, words):
    run = run_text(f".PROGRAM t()\n  JMOVE pick\n  {line}\n  LMOVE place\n.END\n" + POSES)
    assert len(run.toolpath.moves) == 2 and words in run.skipped[0]
    with pytest.raises(ExecutionError, match="a simulation runs every statement, and the twin does not simulate"):
        run.require_complete()


@pytest.mark.parametrize("text, always", [("ACCEL 50.0 50.0", False), ("ACCEL 50 50 ALWAYS", True),
                                          ("DECEL 30", False), ("ACCEL 80 ALWAYS", True)])
def test_accel_with_robodk_s_second_percentage_is_read(text, always):
    """RoboDK's post writes ``ACCEL a a``: it was refused ("unexpected '50.0' after the ACCEL
    statement"); the first percentage is read, the second left (the cell's limits apply to both)."""
    (st,) = parse_as(f".PROGRAM a()\n  {text}\n.END\n").programs[0].body
    assert isinstance(st, ast.Accel) and st.always is always


def test_accel_with_a_dangling_comma_is_refused():
    with pytest.raises(AsSyntaxError, match="expected a percentage"):
        parse_as(".PROGRAM a()\n  DECEL 30,\n.END\n")
