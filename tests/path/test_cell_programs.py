"""Programs written the way cells write them (tests/path/data/cells/, written for these tests,
each in its own style): every one parses and runs, check-program reports what it does, and the
spraying ones convert to arcs in place.

pallet_sjis      palletising, Shift-JIS comments, CRLF, step numbers, labels, GOTO, SHIFT with an
                 empty component, a CALLed gripper routine with a value argument
features_tabs    tab indentation, strings, arrays, WHILE/DO/UNTIL/CASE/SCASE, by-reference CALL,
                 compound and SHIFTed poses, DECOMPOSE, SPEED 200MM/S, ACCURACY 1 FINE, TWAIT(1)
laser_polish     laser polishing with C1MOVE/C2MOVE half circles, the output in .REALS, ACCEL/DECEL
backup_cp1252    a controller backup: .* header, .NETCONF/.ROBOTDATA*/.AUXDATA/.SYSDATA/
                 .INTER_PANEL_*/.SIG_COMMENT/.STORAGE/.BRKLOG, autostart.pc, cp1252 text, 7-axis poses
draw_frame       a pen plotter: FRAME from taught points, DRAW / TDRAW with empty components
tasks_switches   PCEXECUTE/MC/WAIT SWITCH, system switches by name, IFPWPRINT, SCALL, HERE, #[...]
oddities_lower   lower case, `10` alone, IF without THEN, SWITCH(), TASK(), a label named end,
                 signal arrays, programs named lib.init_ / addpoint.pc, $DECODE of a plain string
spray_sjis_goto  a plasma contour traced by a label + IF ... GOTO loop, Shift-JIS, the gun on output 3
expressions      arithmetic, string and array functions (checked value by value)
"""

from __future__ import annotations

from pathlib import Path

import pytest

from coatsim.languages.kawasaki_as.files import parse_files
from coatsim.languages.kawasaki_as.interpreter import Interpreter
from program_helpers import check_as as check_program
from coatsim.path.convert import ConvertOptions
from program_helpers import convert_as as convert_program

DATA = Path(__file__).parent / "data" / "cells"


@pytest.fixture(scope="module")
def cell():
    from coatsim.robot.cell import load_cell
    from coatsim.robot.kinematics import CellKinematics

    c = load_cell()
    return CellKinematics(c), (c.gun_rotation, c.gun_offset_mm)


# file, options, (joint, linear, arc moves), sprayed mm, words every listed one must appear in the report
CHECKS = [
    ("pallet_sjis.as", {}, (14, 24, 0), 0.0, ["SPEED in %", "never on during a motion"]),
    ("features_tabs.as", {}, (3, 3, 0), 100.0, []),
    ("laser_polish.as", {}, (3, 3, 4), 396.991, ["ACCEL: the cell's acceleration limits apply"]),
    ("backup_cp1252.as", {"program": "peinture", "inputs": {1001: True}}, (2, 16, 0), 240.0,
     ["sections not read", ".SIG_COMMENT", "external axes"]),
    ("draw_frame.as", {}, (1, 6, 0), 230.0, []),
    ("tasks_switches.as", {"program": "h_main"}, (3, 4, 0), 0.0,
     ["switch DISP.EXESTEP is not simulated", "DLYSIG -2", "UTIMER", "never on during a motion"]),
    ("oddities_lower.as", {}, (1, 4, 0), 97.082, ["TASK is not simulated"]),
    ("spray_sjis_goto.as", {"gun_signal": 3}, (2, 363, 0), 359.784, []),
]


@pytest.mark.parametrize("name,options,counts,sprayed,words", CHECKS, ids=[c[0] for c in CHECKS])
def test_check_program_reads_and_runs_each(name, options, counts, sprayed, words, cell):
    kinematics, gun_tcp = cell
    done = check_program(DATA / name, kinematics=kinematics, gun_tcp=gun_tcp, **options)
    assert (done.n_joint_moves, done.n_linear_moves, done.n_arc_moves) == counts
    assert done.spray_length_mm == pytest.approx(sprayed, abs=0.01)
    report = "\n".join((*done.warnings, *done.problems, *done.notes))
    for word in words:
        assert word in report, word
    assert bool(done.notes) == (sprayed == 0.0)  # reading is not spraying: a note, no error
    assert done.skipped == ()


@pytest.mark.parametrize("name,options,lines,gains", [
    ("laser_polish.as", {}, (16, 25), False), ("draw_frame.as", {}, (10, 13), False),
    ("spray_sjis_goto.as", {"gun_signal": 3}, (11, 14), True),
])
def test_the_spraying_ones_convert_in_place(name, options, lines, gains, cell):
    """A path the arcs shorten is rewritten in place, the bytes before it kept; one they cannot
    shorten (a square of 4 LMOVEs, a circle already in C1MOVE/C2MOVE) is kept as it was, and
    with no path gaining, nothing is written."""
    result = convert_program(DATA / name, ConvertOptions(0.1, **options), kinematics=cell[0])
    (report,) = result.paths
    assert (report.first_line, report.last_line) == lines and report.deviation_mm <= 0.1
    assert result.written == gains and report.kept == (not gains)
    if gains:
        original = (DATA / name).read_bytes()
        assert result.data.split(b"\n")[:lines[0] - 1] == original.split(b"\n")[:lines[0] - 1]  # bytes kept before
        assert report.moves_after < report.moves_before
    else:
        assert result.data == b"" and report.moves_after == report.moves_before


def test_expressions_evaluate_as_written():
    files = parse_files(DATA / "expressions.as")
    run = Interpreter(files, 1, {}, None, 1000.0, 100_000)
    run.run(files[0].programs[0])
    real, text = (lambda k: run.globals.get("real", k)), (lambda k: run.globals.get("string", k))
    assert [real(f"r{i}") for i in (1, 2, 3, 4, 5, 6, 8, 9, 10, 11, 12, 13, 15, 16, 19, 21, 22, 23)] == \
        [1, -1, 1024, -2, 7, 45, 7, 1, 7, 0, -1, 5, 2.5, 260, -6, 0, 150, 1.5]
    assert real("r7") == pytest.approx(1.0) and real("r40") == 42 and real("r50") == 5 and real("glob_out") == 60
    assert (real("sq[1]"), real("sq[2]"), real("which"), real("cnt"), real("r60"), real("r62")) == (4, 1, 4, 4, None, 1)
    assert (text("$c"), text("$d"), text("$e2"), text("$e3"), text("$g"), text("$h"), text("$i"), text("$f")) == \
        ("world", "Helld", "  3.14", "x=1.5 y=-2", "12.5", ";", "7", "")
    assert (real("r30"), real("r34"), text("$names[1]"), text("$k")) == (12, 8, "ab", "   |")


def test_a_backup_s_main_program_is_not_its_autostart_pc(cell):
    done = check_program(DATA / "backup_cp1252.as", kinematics=cell[0], inputs={1001: True})
    assert done.program == "peinture" and done.spray_length_mm == pytest.approx(240.0)
