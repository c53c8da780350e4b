"""Interpreter: control flow, programs CALLed with arguments, the step budget, several files,
inputs and what is not simulated (warnings), and the sample programs of every style."""

from __future__ import annotations

import numpy as np
import pytest

from coatsim.core.errors import ExecutionError, InputError
from coatsim.languages.kawasaki_as import interpret, interpret_run, parse_as, parse_as_bytes
from coatsim.languages.kawasaki_as.interpreter import Interpreter
from coatsim.path.toolpath import CircularMove, JointMove

from as_samples import ARC_POLISHING, BACKUP, DRAWING, MACHINE_TENDING, PALLETISING

DATA = ".TRANS\na 0 0 0 0 180 0\n.END\n"


def globals_after(body: str, extra: str = "", **options):
    f = parse_as(".PROGRAM t()\n" + body + "\n.END\n" + extra + DATA, "t.as")
    run = Interpreter((f,), 1, options.get("inputs", {}), None, 1000.0, options.get("max_steps", 100_000))
    tp = run.run(f.programs[0])
    return (lambda kind, name: run.globals.get(kind, name)), tp


@pytest.mark.parametrize("body,expected", [
    ("x = 0\n10 x = x + 1\nIF x < 5 GOTO 10", 5.0),
    ("x = 1\nGOTO skip\nx = 2\nskip:", 1.0),
    ("x = 0\nagain:\nx = x + 1\nIF x < 4 GOTO again", 4.0),  # the one-line IF of AS, to a named label
    ("x = 0\n10 x = x + 1\nIF SIG(2001) GOTO 20\nIF x >= 2 GOTO 20\nGOTO 10\n20 y = 1", 2.0),
    ("x = 0\nIF 1 > 2 THEN\n x = 1\nELSEIF 2 > 1 THEN\n x = 2\nELSE\n x = 3\nEND", 2.0),
    ("x = 0\nIF 0 THEN\n x = 1\nELSE\n x = 3\nEND", 3.0),
    ("x = 0\nWHILE x < 7 DO\n x = x + 2\nEND", 8.0),
    ("x = 10\nDO\n x = x - 3\nUNTIL x < 0", -2.0),
    ("x = 0\nFOR .i = 1 TO 4\n x = x + .i\nEND", 10.0),
    ("x = 0\nFOR .i = 10 TO 1 STEP -3\n x = x * 10 + .i\nEND", 10741.0),
    ("x = 0\nFOR .i = 1 TO 0\n x = 99\nEND", 0.0),
    ("x = 0\nWHILE TRUE DO\n x = x + 1\n IF x == 3 THEN\n  EXIT\n END\nEND", 3.0),
    ("x = 0\nFOR .i = 1 TO 3\n FOR .j = 1 TO 3\n  IF .j == 2 THEN\n   EXIT\n  END\n  x = x + 1\n END\nEND", 3.0),
    ("y = 2\nCASE y OF\n VALUE 1:\n  x = 10\n VALUE 2, 3:\n  x = 20\n ANY :\n  x = 30\nEND", 20.0),
    ("y = 9\nCASE y OF\n VALUE 1:\n  x = 10\n ANY :\n  x = 30\nEND", 30.0),
    ("y = 9\nx = 5\nCASE y OF\n VALUE 1:\n  x = 10\nEND", 5.0),
    ("$s = \"b\"\nSCASE $s OF\n SVALUE \"a\":\n  x = 1\n SVALUE \"b\", \"c\":\n  x = 2\nEND", 2.0),
    ("x = 1\nSTOP\nx = 2", 1.0),
    ("x = 1\nHALT\nx = 2", 1.0),
    ("x = 1\nPAUSE\nx = 2", 2.0),
    ("x = 0\nGOTO 5\nWHILE x < 3 DO\n5 x = x + 1\nEND", 3.0),
])
def test_control_flow(body, expected):
    get, _ = globals_after(body)
    assert get("real", "x") == expected


def test_call_by_value_and_by_reference():
    subs = (".PROGRAM add(.a, .&b, .$s, .p)\n  .a = .a + 1\n  .b = .a * 10\n  .$s = \"changed\"\n"
            "  POINT .p = SHIFT(.p BY 1, 0, 0)\n  RETURN\n  .b = -1\n.END\n"
            ".PROGRAM twice(.&k)\n  CALL add(.k, .&k, \"x\", a)\n  CALL add(.k, .&k, \"x\", a)\n.END\n")
    get, _ = globals_after("v = 1\nCALL add(v, &w, \"s\", a)\nk = 1\nCALL twice(&k)", subs)
    assert get("real", "v") == 1.0 and get("real", "w") == 20.0
    assert get("real", "k") == 210.0  # .a = 1 + 1 -> .b = 20, then .a = 20 + 1 -> .b = 210


def test_pose_passed_by_reference():
    subs = ".PROGRAM lift(.&p)\n  POINT .p = SHIFT(.p BY 0, 0, 5)\n.END\n"
    get, _ = globals_after("POINT q = a\nCALL lift(&q)", subs)
    assert np.allclose(get("pose", "q").translation_mm, [0, 0, 5])


def test_local_variables_are_local():
    subs = ".PROGRAM sub()\n  .x = 5\n  x = .x\n.END\n"
    get, _ = globals_after(".x = 1\nCALL sub\ny = .x", subs)
    assert get("real", "x") == 5.0 and get("real", "y") == 1.0


def test_step_budget_names_the_loop():
    with pytest.raises(ExecutionError) as info:
        globals_after("x = 0\nWHILE x >= 0 DO\n  x = x + 1\nEND", max_steps=5000)
    assert str(info.value).startswith("t.as:3: ") and "WHILE loop of line 3" in str(info.value)
    with pytest.raises(ExecutionError) as info:
        globals_after("x = 0\n10 x = x + 1\nIF x > 0 GOTO 10", max_steps=5000)
    assert "GOTO 10 loop of line 3" in str(info.value)


CYCLE_DATA = ".TRANS\np1 600 -100 300 0 180 0\np2 700 -100 300 0 180 0\np3 700 100 300 0 180 0\n.END\n"
PAINT = ".PROGRAM paint()\n  JMOVE p1\n  BREAK\n  SIGNAL 1\n  LMOVE p2\n  LMOVE p3\n  BREAK\n  SIGNAL -1\n.END\n"


def _cycle(body: str, extra: str = PAINT, inputs: dict | None = None):
    f = parse_as(".PROGRAM main()\n" + body + "\n.END\n" + extra + CYCLE_DATA, "m.as")
    run = Interpreter((f,), 1, inputs or {}, None, 1000.0, 100_000)
    tp = run.run(f.programs[0])
    return run, tp


@pytest.mark.parametrize("body", [
    "1 SWAIT 1001\nSIGNAL -2001\nCALL paint\nSIGNAL 2001\nSWAIT -1001\nGOTO 1",
    "cnt = 0\n10\nCALL paint\ncnt = cnt + 1\nIF cnt > 5 THEN\n  cnt = 0\nEND\nGOTO 10",
    "WHILE TRUE DO\n  SWAIT 1001\n  CALL paint\nEND",
    "DO\n  CALL paint\n  TWAIT 1\nUNTIL FALSE",
])
def test_a_production_cycle_with_no_way_out_is_read_once(body):
    """A main program that repeats its cycle for ever (a label and GOTO back, WHILE TRUE, DO ...
    UNTIL FALSE, with no jump out, RETURN, STOP or HALT in it) is read once, with a note: the
    cell's cycle, not a refusal after 200 000 motions."""
    run, tp = _cycle(body)
    assert len(tp.moves) == 3 and sum(m.spray for m in tp.moves) == 2
    assert any("has no way out: a cycle the cell repeats; the twin runs it once" in w for w in tp.warnings), tp.warnings


def test_a_loop_with_a_way_out_runs_to_its_end():
    """A GOTO loop left by a counter is no cycle: all its passes run."""
    _, tp = _cycle("n = 0\n10 CALL paint\nn = n + 1\nIF n >= 3 GOTO 20\nGOTO 10\n20 x = 1", extra=PAINT)
    assert len(tp.moves) == 9 and not any("no way out" in w for w in tp.warnings)


@pytest.mark.parametrize("body,reads", [
    ("WHILE NOT stop.req DO\n  CALL paint\nEND\nx = 1", "NOT stop.req (line 2, it reads stop.req)"),
    ("WHILE NOT SIG(1020) DO\n  CALL paint\nEND\nx = 1", "NOT SIG(1020) (line 2, it reads an input not given)"),
    ("10 CALL paint\nIF SIG(1020) GOTO 99\nGOTO 10\nx = 2\n99 x = 1", "SIG(1020) (line 3, it reads an input not given)"),
    ("DO\n  CALL paint\nUNTIL done.flag\nx = 1", "done.flag (line 4, it reads done.flag)"),
])
def test_a_loop_ended_only_by_the_cell_runs_once(body, reads):
    """A loop that works but is left only on a variable no file gives or an input not given
    (the operator's stop request) runs once and is left where its exit goes, with a note naming
    what it waits on; not run to the motion cap."""
    run, tp = _cycle(body)
    assert len(tp.moves) == 3 and run.globals.get("real", "x") == 1.0
    assert any(f"ends only on what the twin does not know: {reads}; the twin runs it once" in w
               for w in tp.warnings), tp.warnings


@pytest.mark.parametrize("body,inputs", [
    ("n = 0\nWHILE NOT SIG(1020) AND n < 3 DO\n  CALL paint\n  n = n + 1\nEND", {}),
    ("n = 0\n10 CALL paint\nn = n + 1\nIF SIG(1020) OR n >= 3 GOTO 99\nGOTO 10\n99 x = 1", {}),
    ("n = 0\nWHILE NOT SIG(2020) DO\n  CALL paint\n  n = n + 1\n  IF n >= 3 THEN\n    SIGNAL 2020\n  END\nEND", {}),
    ("n = 0\nWHILE NOT done DO\n  CALL paint\n  n = n + 1\n  done = n >= 3\nEND", {}),
])
def test_a_loop_with_a_known_way_out_runs_as_written(body, inputs):
    """A loop whose exit also turns on a value the run has (a counter), or on a variable or a
    signal the loop itself sets, runs all its passes."""
    _, tp = _cycle(body, inputs=inputs)
    assert len(tp.moves) == 9 and not any("ends only on" in w for w in tp.warnings), tp.warnings


CONSTANTS = ".REALS\ndi.stop = 1020\ndo.gun = 1\nint.done = 2020\n.END\n"


@pytest.mark.parametrize("body", [
    "WHILE NOT SIG(di.stop) DO\n  CALL paint\nEND\nx = 1",
    "WHILE NOT SIG(di.stop) DO\n  SIGNAL -do.gun\n  CALL paint\nEND\nx = 1",
    "10 CALL paint\nIF SIG(di.stop) GOTO 99\nGOTO 10\nx = 2\n99 x = 1",
])
def test_a_loop_on_an_input_named_by_a_constant_runs_once(body):
    """An input named by a .REALS constant (``di.stop = 1020``, ``WHILE NOT SIG(di.stop) DO``) is
    what the loop waits on, not the constant, which has its value: the loop runs once with a note,
    not to the motion cap; signals the loop switches through constants are told apart from it."""
    run, tp = _cycle(body, extra=PAINT + CONSTANTS)
    assert len(tp.moves) == 3 and run.globals.get("real", "x") == 1.0
    assert any("ends only on what the twin does not know" in w and "SIG(di.stop)" in w
               and "it reads an input not given" in w for w in tp.warnings), tp.warnings


def test_a_loop_that_sets_the_signal_a_constant_names_runs_as_written():
    """A loop that itself switches the signal its exit reads, both named by one constant, runs all
    its passes."""
    body = "n = 0\nWHILE NOT SIG(int.done) DO\n  CALL paint\n  n = n + 1\n  IF n >= 3 THEN\n" \
           "    SIGNAL int.done\n  END\nEND"
    _, tp = _cycle(body, extra=PAINT + CONSTANTS)
    assert len(tp.moves) == 9 and not any("ends only on" in w for w in tp.warnings), tp.warnings


def test_a_value_given_for_the_exit_of_a_loop_is_honoured():
    """Given the input or the variable, the loop runs as written: not entered, or to its end."""
    _, tp = _cycle("WHILE NOT SIG(1020) DO\n  CALL paint\nEND\nCALL paint", inputs={1020: True})
    assert len(tp.moves) == 3 and not any("ends only on" in w for w in tp.warnings)
    f = parse_as(".PROGRAM main()\nWHILE NOT stop.req DO\n  CALL paint\nEND\nCALL paint\n.END\n" + PAINT + CYCLE_DATA)
    tp = interpret_run((f,), variables={"stop.req": 1}).toolpath
    assert len(tp.moves) == 3 and not any("ends only on" in w for w in tp.warnings)


@pytest.mark.parametrize("body,reads", [
    ("TIMER 1 = 0\nWHILE TIMER(1) < 3 DO\n  TWAIT 0.5\nEND", "TIMER"),
    ("10 IF SIG(1002) GOTO 20\nTWAIT 0.1\nGOTO 10\n20 x = 1", "an input not given"),
    ("10 TCP_RECV .ret, 1, .$buf[1], .num, 30, 255\nIF .num <= 0 GOTO 10\nx = 1", "a message"),
    ("DO\n  TWAIT 0.2\nUNTIL SIG(1003)", "an input not given"),
])
def test_a_loop_that_waits_for_what_the_twin_does_not_know_is_taken_as_ended(body, reads):
    """A loop whose pass changes nothing but reads a timer, an input nobody gives or a message
    waits for the cell: it is taken as ended with a note, and the program goes on."""
    run, tp = _cycle(body + "\nCALL paint", extra=PAINT)
    assert len(tp.moves) == 3
    assert any(f"waits for what the twin does not know (it reads {reads}" in w for w in tp.warnings), tp.warnings


def test_a_loop_serving_the_cell_is_read_for_one_pass():
    """A server loop: wait for a message (or an input), work, go back and wait again, with a way
    out only on an error status. The first wait is taken as ended; the second ends the run."""
    body = ("n = 0\n10 TCP_RECV .ret, 1, .$buf[1], .num, 30, 255\nIF .ret < 0 GOTO 900\nIF .num <= 0 GOTO 10\n"
            "CALL paint\nn = n + 1\nGOTO 10\n900 TCP_CLOSE .ret, 1")
    run, tp = _cycle(body)
    assert len(tp.moves) == 3 and run.globals.get("real", "n") == 1.0
    assert any("waits again for a message: the twin read one pass of the loop that serves the cell" in w
               for w in tp.warnings), tp.warnings


def test_a_loop_waiting_for_a_timer_in_a_finite_loop_is_taken_as_ended_each_pass():
    """A flash-off wait on a timer between coats does not end the run: all three coats are read."""
    body = "FOR .c = 1 TO 3\n  CALL paint\n  TIMER 1 = 0\n  WHILE TIMER(1) < 30 DO\n    TWAIT 1\n  END\nEND"
    _, tp = _cycle(body)
    assert len(tp.moves) == 9


def test_a_loop_that_changes_nothing_and_reads_nothing_unknown_never_ends():
    """Waiting on an input the cell gives as OFF: nothing can end it; said at once, naming it."""
    with pytest.raises(ExecutionError) as info:
        _cycle("10 TWAIT 0.1\nIF SIG(-1001) GOTO 10\nCALL paint", inputs={1001: False})
    assert "the GOTO 10 loop of line 2 repeats with nothing changing: it never ends" in str(info.value)


@pytest.mark.parametrize("body,expected", [
    ("x = 3 =< 3", -1.0), ("x = 2 => 3", 0.0), ("y = 4\nx = 0\nIF y => 4 THEN\n  x = 1\nEND", 1.0),
    ("y = 5\nDO\n  y = y - 1\nUNTIL y =< 2\nx = y", 2.0),
])
def test_relational_operators_are_read_either_way_round(body, expected):
    get, _ = globals_after(body)
    assert get("real", "x") == expected


def test_reset_turns_every_output_off_the_gun_with_them():
    """RESET switches the external outputs off: the moves after it are not sprayed."""
    _, tp = _cycle("JMOVE p1\nBREAK\nSIGNAL 1, 5\nLMOVE p2\nBREAK\nRESET\nLMOVE p3\nLMOVE p1", extra="")
    assert [m.spray for m in tp.moves] == [False, True, False, False]


@pytest.mark.parametrize("body,extra,kind,words", [
    ("GOTO 99", "", InputError, "GOTO 99: no such label"),
    ("EXIT", "", InputError, "EXIT outside a loop"),
    ("10 x = 1\n10 x = 2", "", InputError, "label 10 is defined twice"),
    ("CALL sub(1, 2)", ".PROGRAM sub(.a)\n.END\n", InputError, "takes 1 argument(s), 2 given"),
    ("CALL sub(1 + 2)", ".PROGRAM sub(.&a)\n.END\n", InputError, "passed by reference"),
    ("CALL me", ".PROGRAM me()\n  CALL me\n.END\n", ExecutionError, "the CALL cycle me -> me never ends"),
    ("GOTO 5\nFOR .i = 1 TO 3\n5 x = 1\nEND", "", ExecutionError, "reached without its FOR"),
    ("x = 0\nWAIT x == 1", "", ExecutionError, "WAIT condition is false"),
])
def test_flow_errors(body, extra, kind, words):
    with pytest.raises(kind) as info:
        globals_after(body, extra)
    assert words in str(info.value) and "\n" not in str(info.value)


# --- inputs and outputs --------------------------------------------------------------------
def test_inputs_given_and_unknown():
    get, tp = globals_after("x = SIG(1001)\ny = SIG(1002)\nSWAIT 1003\nz = SIG(1001, -1002)", inputs={1001: True})
    assert (get("real", "x"), get("real", "y"), get("real", "z")) == (-1.0, 0.0, -1.0)
    assert any("input 1002 is not given" in w for w in tp.warnings)
    assert any("SWAIT 1003" in w and "taken as satisfied" in w for w in tp.warnings)
    with pytest.raises(ExecutionError, match="SWAIT -1001 is never satisfied"):
        globals_after("SWAIT -1001", inputs={1001: True})
    get, tp = globals_after("WAIT SIG(1005)")
    assert any("taken as satisfied" in w for w in tp.warnings)


def test_outputs_internal_signals_and_bits():
    get, _ = globals_after("SIGNAL 3, 2001\nBITS 10, 3 = 5\nx = SIG(3, 2001, 10, -11, 12)\ny = BITS(10, 3)")
    assert get("real", "x") == -1.0 and get("real", "y") == 5.0


def test_network_tasks_and_operator_defaults():
    get, tp = globals_after("TCP_CONNECT sock, 49152, ip[1], 5\nTCP_RECV ret, sock, $b[1], n, 5, 255\n"
                            "PCEXECUTE 2: logger\nPROMPT \"n?\", m\nMC EXECUTE other\nOPENI\nRIGHTY\nTIMER 1 = 0\n"
                            "IFPWPRINT 1, 1, 1 = \"hi\"\nTYPE \"done\"")
    assert (get("real", "sock"), get("real", "ret"), get("real", "n"), get("real", "m")) == (1.0, 0.0, 0.0, 0.0)
    joined = " | ".join(tp.warnings)
    for words in ("network and serial I/O are not simulated", "PCEXECUTE 2: logger", "PROMPT", "MC EXECUTE other",
                  "grippers", "RIGHTY", "TIMER"):
        assert words in joined
    assert not any("IFPWPRINT" in w or "TYPE" in w for w in tp.warnings)
    assert all(w.startswith("t.as:") and "\n" not in w for w in tp.warnings)


# --- several files -------------------------------------------------------------------------
def test_programs_and_data_in_separate_files():
    prog = parse_as(".PROGRAM main()\n  JMOVE home1\n  CALL other\n.END\n", "a.as")
    data = parse_as(".TRANS\nhome1 600 0 400 0 180 0\n.END\n", "b.as")
    other = parse_as(".PROGRAM other()\n  LMOVE SHIFT(home1 BY 0, 0, -50)\n.END\n.TRANS\nhome1 600 0 500 0 180 0\n.END\n",
                     "c.as")
    tp = interpret([prog, data, other])
    assert len(tp.moves) == 2 and np.allclose(tp.moves[1].end.translation_mm, [600, 0, 450])
    assert any("c.as:5: home1 is also defined at b.as:2" in w for w in tp.warnings)
    with pytest.raises(InputError, match="is also defined in a.as:1"):
        interpret([prog, parse_as(".PROGRAM main()\n.END\n", "d.as")])
    with pytest.raises(InputError, match="no .PROGRAM section"):
        interpret([data])


# --- the sample programs -------------------------------------------------------------------
@pytest.fixture(scope="module")
def kin():
    from coatsim.robot.cell import load_cell
    from coatsim.robot.kinematics import CellKinematics

    return CellKinematics(load_cell())


def test_machine_tending(kin):
    tp = interpret(parse_as(MACHINE_TENDING, "tend.as"), inputs={1001: True, 1002: False}, kinematics=kin)
    kinds = [m.kind for m in tp.moves]
    assert kinds.count("joint") == 2 + 3 * 3 and kinds.count("line") == 3 * 4
    drops = [m for m in tp.moves if m.kind == "line" and m.line == 24]
    assert [float(d.end.translation_mm[0]) for d in drops] == pytest.approx([550, 610, 670])
    assert any("grippers" in w for w in tp.warnings) and not any("SWAIT" in w for w in tp.warnings)


def test_palletising():
    run = interpret_run(parse_as(PALLETISING, "pallet.as"))
    tp = run.toolpath
    places = [m for m in tp.moves if m.kind == "line" and m.line == 9]
    assert len(places) == 6 and all(m.settings.speed_mm_s == pytest.approx(25.0) for m in places)
    # corner's tool x points along base -x (A = 180); BASE lifts everything by 100
    assert np.allclose(places[-1].end.translation_mm, [500 - 160, -100 + 60, 300])
    assert any("PULSE 7" in w for w in tp.warnings)


def test_arc_polishing():
    tp = interpret(parse_as(ARC_POLISHING, "polish.as"), gun_signal=3)
    assert [m.kind for m in tp.moves] == ["joint", "line", "arc", "line", "arc", "line"]
    assert [m.spray for m in tp.moves] == [False, True, True, True, True, True]
    assert tp.moves[-1].settings.stop_at_end and tp.moves[-1].settings.accuracy_mm == 1.0
    assert isinstance(tp.moves[2], CircularMove) and tp.moves[2].settings.speed_mm_s == pytest.approx(50.0)
    assert [(d.seconds, d.spray) for d in tp.dwells] == [(1.0, False)]


def test_drawing_robot():
    tp = interpret(parse_as(DRAWING, "draw.as"))
    ends = np.array([m.end.translation_mm if m.kind != "joint" else m.target.translation_mm for m in tp.moves])
    assert np.allclose(ends[-5:-1], [[740, 0, 300], [740, 40, 300], [780, 40, 300], [780, 0, 300]])
    assert any("TCP_RECV" in w for w in tp.warnings)


HELPERS = (".PROGRAM a.home()\n  JMOVE p1\n.END\n.PROGRAM gun.off()\n  SIGNAL -1\n.END\n"
           ".PROGRAM pg1()\n  CALL a.home\n  LMOVE p1\n  SIGNAL 1\n  LMOVE p2\n  CALL gun.off\n.END\n")


@pytest.mark.parametrize("text,main,note", [
    (HELPERS, "pg1", "program pg1 is taken as the main program: no other loaded program CALLs it (the first, a.home, "
                     "is CALLed by another)"),
    (".PROGRAM a.log()\n  x = 1\n.END\n" + HELPERS + ".PROGRAM spare()\n  JMOVE p2\n.END\n", "pg1",
     "program pg1 is taken as the main program: no other loaded program CALLs it (the first, a.log, is without "
     "motion); other programs no one CALLs that move: spare; name one to run it instead"),
    (".PROGRAM main()\n  JMOVE p1\n.END\n.PROGRAM spare()\n  JMOVE p2\n.END\n", "main",
     "program main is taken as the main program: no other loaded program CALLs it; other programs no one CALLs "
     "that move: spare; name one to run it instead"),
    (".PROGRAM main()\n  JMOVE p1\n.END\n.PROGRAM comment()\n  ; notes\n.END\n", "main", ""),
])
def test_the_main_program_of_a_backup_is_one_no_program_calls(text, main, note):
    """A backup saves programs alphabetically: the main program is the first that no other
    program CALLs and that moves, not the helper saved first; the note says which and the
    other candidates."""
    run = interpret_run(parse_as(text + CYCLE_DATA, "backup.as"))
    assert run.toolpath.name == main and run.notes == ((note,) if note else ())
    assert interpret_run(parse_as(text + CYCLE_DATA), program=main).notes == ()


def test_backup_file():
    f = parse_as_bytes(BACKUP, "backup.as")
    tp = interpret(f, program="main")
    # forward processing: each SIGNAL switches as the motion before it starts
    assert [m.kind for m in tp.moves] == ["joint", "line"] and [m.spray for m in tp.moves] == [True, False]
    assert interpret(f, program="autostart.pc").moves == ()
    assert interpret(f).name == "main"  # the background PC program is not the default main
    assert isinstance(tp.moves[0], JointMove)


def test_pose_statements_evaluate():
    extra = ".TRANS\nb 10 20 30 90 180 0\n.END\n"
    get, _ = globals_after("JMOVE b\nHERE h\nDECOMPOSE d[1] = h\nPOINT/X q = TRANS(5, 6, 7)\nPOINT/Z q2 = b\n"
                           "POINT/OAT r = b\nPOINT s = -b + b\nx = DISTANCE(h, b)", extra)
    assert [get("real", f"d[{i}]") for i in range(1, 7)] == pytest.approx([10, 20, 30, 90, 180, 0])
    assert np.allclose(get("pose", "q").translation_mm, [5, 0, 0]) and np.allclose(get("pose", "q2").translation_mm, [0, 0, 30])
    assert np.allclose(get("pose", "r").translation_mm, [0, 0, 0]) and np.allclose(get("pose", "r").rotation, get("pose", "b").rotation)
    assert np.allclose(get("pose", "s").translation_mm, 0) and np.allclose(get("pose", "s").rotation, np.eye(3))
    assert get("real", "x") == 0.0


def test_a_guard_on_an_input_not_given_names_it_where_nothing_moves(tmp_path):
    """A part-present guard (IF NOT SIG(1001) THEN RETURN) with the input not given leaves the
    program before any motion: the error names the input, taken as off, besides the end."""
    from coatsim.languages.registry import language
    from coatsim.path.check import check_program

    path = tmp_path / "guard.as"
    path.write_text(".PROGRAM g()\n  IF NOT SIG(1001) THEN\n    RETURN\n  END\n  LMOVE a\n.END\n"
                    ".TRANS\na 600 0 300 0 180 0\n.END\n")
    with pytest.raises(ExecutionError, match="has no motion .*input 1001 is not given; taken as OFF"):
        check_program(path, language("kawasaki-as"))
