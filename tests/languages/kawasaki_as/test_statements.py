"""One test per statement construct of issue 10: each line parses into its typed node."""

from __future__ import annotations

import pytest

from coatsim.languages.kawasaki_as import ast
from coatsim.languages.kawasaki_as.parser import parse_as
from coatsim.languages.kawasaki_as.source import AsSyntaxError

N, S = ast.Num, ast.Str


def V(name: str, *index) -> ast.Name:
    return ast.Name(name, tuple(index))


def body(text: str) -> tuple:
    return parse_as(".PROGRAM t()\n" + text + "\n.END\n", "t.as").programs[0].body


def one(text: str):
    statements = [s for s in body(text) if not isinstance(s, ast.Label)]
    assert len(statements) == 1, statements
    return statements[0]


CASES = [
    # motion
    ("JMOVE #home", ast.Move(2, "JMOVE", V("#home"))),
    ("jmove p1, 1", ast.Move(2, "JMOVE", V("p1"), N(1.0))),
    ("LMOVE a + b", ast.Move(2, "LMOVE", ast.Binary("+", V("a"), V("b")))),
    ("LMOVE -a + b", ast.Move(2, "LMOVE", ast.Binary("+", ast.Unary("-", V("a")), V("b")))),
    ("C1MOVE v[2]", ast.Move(2, "C1MOVE", V("v", N(2.0)))),
    ("C2MOVE .e", ast.Move(2, "C2MOVE", V(".e"))),
    ("XMOVE p TILL 1001", ast.Move(2, "XMOVE", V("p"), till=N(1001.0))),
    ("JAPPRO p, 50", ast.Appro(2, "JAPPRO", V("p"), N(50.0))),
    ("LAPPRO p, .d", ast.Appro(2, "LAPPRO", V("p"), V(".d"))),
    ("JDEPART 20", ast.Depart(2, "JDEPART", N(20.0))),
    ("LDEPART -5", ast.Depart(2, "LDEPART", ast.Unary("-", N(5.0)))),
    ("HOME", ast.Home(2, None)),
    ("HOME 2", ast.Home(2, N(2.0))),
    ("HOME2", ast.Home(2, N(2.0))),
    ("DRAW ,,50", ast.Draw(2, "DRAW", (None, None, N(50.0)))),
    ("TDRAW 1, 2, 3, 0, 0, 5", ast.Draw(2, "TDRAW", (N(1.0), N(2.0), N(3.0), N(0.0), N(0.0), N(5.0)))),
    ("DELAY 0.5", ast.Delay(2, "DELAY", N(0.5))),
    ("STABLE .t", ast.Delay(2, "STABLE", V(".t"))),
    ("BREAK", ast.Break(2)),
    ("BRAKE", ast.Brake(2)),
    # settings
    ("SPEED 30", ast.Speed(2, N(30.0), "%", False)),
    ("SPEED 20 % ALWAYS", ast.Speed(2, N(20.0), "%", True)),
    ("SPEED 200MM/S", ast.Speed(2, N(200.0), "MM/S", False)),
    ("speed 600 mm/min always", ast.Speed(2, N(600.0), "MM/MIN", True)),
    ("SPEED 2 S", ast.Speed(2, N(2.0), "S", False)),
    ("SPEED 5 CM/S", ast.Speed(2, N(5.0), "CM/S", False)),
    ("SPEED v_fast MM/S ALWAYS", ast.Speed(2, V("v_fast"), "MM/S", True)),
    ("ACCURACY 1", ast.Accuracy(2, N(1.0), False, False)),
    ("ACCURACY 0.5 FINE ALWAYS", ast.Accuracy(2, N(0.5), True, True)),
    ("ACCEL 80 ALWAYS", ast.Accel(2, "ACCEL", N(80.0), True)),
    ("DECEL 50", ast.Accel(2, "DECEL", N(50.0), False)),
    ("CP ON", ast.Switch(2, "CP", True)),
    ("cp off", ast.Switch(2, "CP", False)),
    ("ABS.SPEED ON", ast.Switch(2, "ABS.SPEED", True)),
    ("QTOOL OFF", ast.Switch(2, "QTOOL", False)),
    ("SWITCH CP = OFF", ast.Switch(2, "CP", False)),
    ("TOOL tools[2]", ast.Tool(2, V("tools", N(2.0)))),
    ("TOOL TRANS(0, 0, 250)", ast.Tool(2, ast.Call("TRANS", (N(0.0), N(0.0), N(250.0))))),
    ("BASE NULL", ast.Base(2, ast.Call("NULL", ()))),
    # variables and poses
    ("x = 5", ast.Assign(2, V("x"), N(5.0))),
    (".i = .i + 1", ast.Assign(2, V(".i"), ast.Binary("+", V(".i"), N(1.0)))),
    ("a[.i, 2] = 0", ast.Assign(2, V("a", V(".i"), N(2.0)), N(0.0))),
    ("$s = \"text; not a comment\"", ast.Assign(2, V("$s"), S("text; not a comment"))),
    (".$msg = $MID($s, 2, 3)", ast.Assign(2, V(".$msg"), ast.Call("$MID", (V("$s"), N(2.0), N(3.0))))),
    ("flag = TRUE", ast.Assign(2, V("flag"), N(-1.0))),
    ("flag = OFF", ast.Assign(2, V("flag"), N(0.0))),
    ("POINT p = q", ast.PointAssign(2, V("p"), V("q"))),
    ("POINT .p = HERE", ast.PointAssign(2, V(".p"), ast.Call("HERE", ()))),
    ("POINT #j = #[0, 10, , 0, 30, 0]", ast.PointAssign(2, V("#j"), ast.JointLiteral(
        (N(0.0), N(10.0), None, N(0.0), N(30.0), N(0.0))))),
    ("POINT/X p = q", ast.PointAssign(2, V("p"), V("q"), "X")),
    ("POINT/OAT p = q", ast.PointAssign(2, V("p"), V("q"), "OAT")),
    ("POINT p = SHIFT(q BY ,,50)", ast.PointAssign(2, V("p"), ast.Shift(V("q"), (None, None, N(50.0))))),
    ("POINT f = FRAME(o, x, y, o)", ast.PointAssign(2, V("f"), ast.Call("FRAME", (V("o"), V("x"), V("y"), V("o"))))),
    ("POINT r = RZ(-180)", ast.PointAssign(2, V("r"), ast.Call("RZ", (ast.Unary("-", N(180.0)),)))),
    ("DECOMPOSE d[1] = p", ast.Decompose(2, V("d", N(1.0)), V("p"))),
    ("HERE .cur", ast.Here(2, V(".cur"))),
    ("HERE #now", ast.Here(2, V("#now"))),
    # I/O and tasks
    ("SIGNAL 1, -2, o_gun", ast.Signal(2, (N(1.0), ast.Unary("-", N(2.0)), V("o_gun")))),
    ("SIGNAL -o_gun", ast.Signal(2, (ast.Unary("-", V("o_gun")),))),
    ("PULSE 7, 0.5", ast.Pulse(2, "PULSE", N(7.0), N(0.5))),
    ("PULSE 7", ast.Pulse(2, "PULSE", N(7.0), None)),
    ("DLYSIG -7, 1", ast.Pulse(2, "DLYSIG", ast.Unary("-", N(7.0)), N(1.0))),
    ("BITS 10, 4 = ^HF", ast.Bits(2, N(10.0), N(4.0), N(15.0))),
    ("SWAIT 1001, -1002", ast.Swait(2, (N(1001.0), ast.Unary("-", N(1002.0))))),
    ("WAIT SIG(1001) OR .go", ast.Wait(2, ast.Binary("OR", ast.Call("SIG", (N(1001.0),)), V(".go")))),
    ("TWAIT 1", ast.Twait(2, N(1.0))),
    ("TWAIT(1)", ast.Twait(2, N(1.0))),
    ("TWAIT .t * 2", ast.Twait(2, ast.Binary("*", V(".t"), N(2.0)))),
    ("TYPE \"x=\", .x, /F8.3", ast.Output(2, "TYPE", (S("x="), V(".x"), ast.Format("F8.3")))),
    ("PRINT 2: \"done\"", ast.Output(2, "PRINT", (S("done"),))),
    ("PROMPT \"how many?\", .n", ast.Output(2, "PROMPT", (S("how many?"),), V(".n"))),
    ("PCEXECUTE 2: log_task", ast.Command(2, "PCEXECUTE", (), "2: log_task")),
    ("MC EXECUTE main, -1", ast.Command(2, "MC", (), "EXECUTE main, -1")),
    ("TCP_SEND .ret, .sock, $out[1], 1, 5", ast.Command(2, "TCP_SEND", (V(".ret"), V(".sock"), V("$out", N(1.0)),
                                                                         N(1.0), N(5.0)), ".ret, .sock, $out[1], 1, 5")),
    ("UDP_SENDTO .ret, ip[1], 49152, $s[1], 1, 2", ast.Command(2, "UDP_SENDTO", (
        V(".ret"), V("ip", N(1.0)), N(49152.0), V("$s", N(1.0)), N(1.0), N(2.0)), ".ret, ip[1], 49152, $s[1], 1, 2")),
    ("RUNMASK 1, 8", ast.Command(2, "RUNMASK", (N(1.0), N(8.0)), "1, 8")),
    ("CLAMP 1", ast.Command(2, "CLAMP", (N(1.0),), "1")),
    ("OPENI", ast.Command(2, "OPENI", (), "")),
    ("CLOSEI 2", ast.Command(2, "CLOSEI", (N(2.0),), "2")),
    ("ON -1001 CALL stop_all", ast.Command(2, "ON", (), "-1001 CALL stop_all")),
    ("LINEAR 125. ACCU1 TIMER0 TOOL3", ast.BlockStep(2, "LINEAR", "LINEAR 125. ACCU1 TIMER0 TOOL3")),
    # control
    ("GOTO 10", ast.Goto(2, "10")),
    ("goto re_connect", ast.Goto(2, "re_connect")),
    ("IF .n > 3 GOTO 20", ast.Goto(2, "20", ast.Binary(">", V(".n"), N(3.0)))),
    ("CALL sub", ast.CallProgram(2, "sub", ())),
    ("CALL sub(1, .&x, &g, .y + 1)", ast.CallProgram(2, "sub", (N(1.0), ast.Ref(V(".x")), ast.Ref(V("g")),
                                                                  ast.Binary("+", V(".y"), N(1.0))))),
    ("SCALL $prog", ast.CallProgram(2, V("$prog"), ())),
    ("RETURN", ast.Return(2)),
    ("STOP", ast.Stop(2, "STOP")),
    ("HALT", ast.Stop(2, "HALT")),
    ("PAUSE", ast.Stop(2, "PAUSE")),
]


@pytest.mark.parametrize("text,expected", CASES, ids=[c[0] for c in CASES])
def test_statement(text, expected):
    assert one(text) == expected


def test_labels_numeric_and_named():
    st = body("  10 JMOVE a\n  re_connect: LMOVE b\n  20\n  done:")
    assert st == (ast.Label(2, "10"), ast.Move(2, "JMOVE", V("a")), ast.Label(3, "re_connect"),
                  ast.Move(3, "LMOVE", V("b")), ast.Label(4, "20"), ast.Label(5, "done"))


def test_blocks_nest():
    st = body("IF a THEN\n  x = 1\nELSEIF b THEN\n  x = 2\nELSE\n  WHILE c DO\n    EXIT\n  END\nEND\n"
              "DO\n  FOR .i = 1 TO 3 STEP 2\n  END\nUNTIL d\n"
              "CASE x OF\n  VALUE 1, 2:\n    y = 1\n  ANY :\n    y = 2\nEND\n"
              "SCASE $s OF\n  SVALUE \"a\":\n    y = 3\nEND")
    if_, do, case, scase = st
    assert [c for c, _ in if_.branches] == [V("a"), V("b")] and if_.end_line == 10
    assert isinstance(if_.orelse[0], ast.While) and if_.orelse[0].body == (ast.Exit(8),)
    assert isinstance(do, ast.DoUntil) and do.condition == V("d")
    assert isinstance(do.body[0], ast.For) and do.body[0].step == N(2.0)
    assert case.branches[0][0] == (N(1.0), N(2.0)) and case.default == (ast.Assign(19, V("y"), N(2.0)),)
    assert scase.string and scase.branches[0][0] == (S("a"),)


BLOCK_ERRORS = [
    ("END", "END without an open block"),
    ("ELSE", "ELSE without an open IF"),
    ("IF a THEN\nELSE\nELSE\nEND", "ELSE without an open IF"),
    ("VALUE 1:", "VALUE outside a CASE"),
    ("UNTIL a", "UNTIL without an open DO"),
    ("DO\nEND", "ends with UNTIL"),
    ("WHILE a DO", "is not closed"),
    ("CASE x OF\n  y = 1\n  VALUE 1:\nEND", "statement before the first VALUE"),
    ("CASE x OF\n  SVALUE \"a\":\nEND", "expected VALUE"),
    ("CASE x OF\n ANY\n VALUE 2:\nEND", "after ANY"),
    ("IF a THEN x = 1\nEND", "an AS IF ... THEN opens a block"),
    ("IF a = 1 THEN\nEND", "compare with '=='"),
    ("FOR $s = 1 TO 2\nEND", "must be a real"),
    ("FOO p1", "is not an AS instruction"),
    ("#j = #[1]", "with POINT #j"),
    ("LMOVE .foo(1)", "is a local variable; an array element takes [ ]"),
    ("POINT $s = p", "assign the string"),
    ("CALL", "expected a program name"),
    ("LMOVE &p", "by-reference argument"),
]


@pytest.mark.parametrize("text,words", BLOCK_ERRORS)
def test_block_and_statement_errors(text, words):
    with pytest.raises(AsSyntaxError) as info:
        body(text)
    assert words in str(info.value) and str(info.value).startswith("t.as:") and "\n" not in str(info.value)
