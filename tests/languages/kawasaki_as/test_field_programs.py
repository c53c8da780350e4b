"""Programs written for real cells in field styles (data/field/ beside this file, written for these
tests): each is read (exit 0), the values NAME=VALUE gives complete the partly read ones, the one
with a FOR never closed is refused; a program that never opens the gun is read and reported, and
only what needs a sprayed path (convert, a scenario variant) refuses it, naming the outputs it
switches. A property test mixes the constructs at random: exit 0 or a one-line error, never a
traceback.

b_sealer_memory      backup: direction, $cnt[0], bead.speed from the controller's memory
b_unclosed_for       backup: a FOR never closed (rightly refused)
b_weld_joint_ref     backup: POINT .#j = .pose, #ref and POINT #j = pose, #ref
k_draw_tcp           K-IDE: CALL tcp.send.pc(.$data[], 2), local string arrays, AVE_TRANS, POINT .#j
k_functions          K-IDE: functions of the index (TRADD, WHICHTASK, MSPEED2, EXISTINTEGER, $ERRORS ...)
k_keyword_vars       K-IDE: variables named step, len, value, to
k_spray_memory_poses K-IDE: a home pose taught on the pendant, kept in the controller
k_tending_abbrev     K-IDE: ty, spe, accu, jm, lm, bre, tw, ldep; value[i] = VAL($temp); grippers only
m_laser_polish       mixed case: laser on output 12, never output 1
m_long_expr          mixed case: a 600-term checksum expression
n_handling_steps     step numbers: CASE on a PLC variable, GOTO loop, TWA abbreviated, output 9
u_instructions       upper case: WEIGHT, ULIMIT, L3ACCURACY, ON ... CALL, HSENSESET, MVWAIT, XMOVE ...
u_pallet_arrays      upper case: layers from the HMI, CALL calc.layer(.l, .&pos[,]), vacuum on output 5
u_string_arrays      upper case: local string arrays, SCASE, CALL trace.part(.&p[], 3)
u_trace_rel          upper case: CALL trace.part(.&p.rel[,]) of a 2-D pose array
"""

from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from coatsim.core.errors import CoatsimError, InputError
from program_helpers import check_as as check_program
from coatsim.path.convert import ConvertOptions
from program_helpers import convert_as as convert_program

from styles import STYLES, styled

DATA = Path(__file__).resolve().parent / "data" / "field"


@pytest.fixture(scope="module")
def cell():
    from coatsim.robot.cell import load_cell
    from coatsim.robot.kinematics import CellKinematics

    c = load_cell()
    return CellKinematics(c), (c.gun_rotation, c.gun_offset_mm)


# file, options, (moves, unknowns, skipped, sprayed mm), outputs switched
READ = [
    ("b_sealer_memory.as", {}, (8, 3, 1, 580.0), (1,)),
    ("b_sealer_memory.as", {"variables": {"bead.speed": 60, "direction": 8, "$cnt[0]": "x"}}, (8, 0, 0, 580.0), (1,)),
    ("b_weld_joint_ref.as", {}, (6, 0, 0, 188.680), (1,)),
    ("k_draw_tcp.pg", {}, (9, 0, 0, 300.0), (1,)),
    ("k_functions.pg", {}, (5, 0, 1, 150.0), (1,)),
    ("k_keyword_vars.pg", {}, (3, 0, 0, 90.0), (1,)),
    ("k_spray_memory_poses.pg", {}, (4, 1, 2, 500.0), (1,)),
    ("k_spray_memory_poses.pg", {"variables": {"p.home": "TRANS(650, 0, 400, 0, 180, 0)"}}, (6, 0, 0, 500.0), (1,)),
    ("k_tending_abbrev.pg", {}, (20, 0, 0, 0.0), (9, 10)),
    ("m_laser_polish.as", {}, (5, 1, 0, 0.0), (12,)),
    ("m_laser_polish.as", {"gun_signal": 12}, (5, 1, 0, 251.327), (12,)),
    ("m_long_expr.as", {}, (3, 1, 0, 80.0), (1,)),
    ("n_handling_steps.as", {}, (14, 2, 0, 0.0), (9,)),
    ("u_instructions.as", {}, (5, 0, 0, 310.840), (1, 9)),
    ("u_pallet_arrays.as", {}, (2, 1, 0, 0.0), ()),
    ("u_pallet_arrays.as", {"variables": {"layers": 2}, "gun_signal": 5}, (34, 0, 0, 3371.629), (5,)),  # joint moves as chords
    ("u_string_arrays.as", {}, (4, 0, 0, 170.711), (1,)),
    ("u_trace_rel.as", {}, (6, 0, 0, 240.0), (1,)),
]


@pytest.mark.parametrize("name,options,figures,outputs", READ, ids=[f"{r[0]}-{i}" for i, r in enumerate(READ)])
def test_each_field_program_is_read(name, options, figures, outputs, cell):
    kinematics, gun_tcp = cell
    done = check_program(DATA / name, kinematics=kinematics, gun_tcp=gun_tcp, **options)
    assert (len(done.toolpath.moves), len(done.unknowns), len(done.skipped)) == figures[:3]
    assert done.spray_length_mm == pytest.approx(figures[3], abs=0.01) and done.outputs == outputs
    never = [n for n in done.notes if "is never on during a motion" in n]
    assert bool(never) == (figures[3] == 0.0)
    if never:
        switched = ", ".join(map(str, outputs))
        assert never[0].endswith(f"switches output{'s' if len(outputs) > 1 else ''} {switched}" if outputs
                                 else "switches no output")


def test_the_for_never_closed_is_refused(cell):
    with pytest.raises(InputError, match=r"b_unclosed_for\.as:6:1: the FOR block of line 3 in program 'count\.parts' "
                                         r"is not closed; expected END before \.END"):
        check_program(DATA / "b_unclosed_for.as", kinematics=cell[0])


def test_the_command_reads_a_field_program_that_never_opens_the_gun(run_cli):
    code, out, err = run_cli(["check-program", str(DATA / "k_tending_abbrev.pg")])
    assert code == 0 and err == ""
    assert "the gun (output 1) is never on during a motion; it switches outputs 9, 10" in out


def test_convert_refuses_a_program_that_never_opens_the_gun_naming_its_outputs(cell):
    with pytest.raises(InputError) as info:
        convert_program(DATA / "m_laser_polish.as", ConvertOptions(0.1), kinematics=cell[0])
    assert "never on over two or more consecutive LMOVE/C1MOVE/C2MOVE moves (it switches output 12: is the process " \
        "signal one of them?)" in str(info.value)
    done = convert_program(DATA / "m_laser_polish.as", ConvertOptions(0.1, gun_signal=12), kinematics=cell[0])
    assert done.paths[0].deviation_mm <= 0.1


def test_convert_refuses_what_it_cannot_read_whole(cell):
    with pytest.raises(InputError, match=r"k_spray_memory_poses\.pg:4: JMOVE skipped: pose p\.home has no value "
                                         r"\(and 1 more\)"):
        convert_program(DATA / "k_spray_memory_poses.pg", ConvertOptions(0.1), kinematics=cell[0])
    done = convert_program(DATA / "k_spray_memory_poses.pg", ConvertOptions(0.1), kinematics=cell[0],
                           variables={"p.home": "TRANS(650, 0, 400, 0, 180, 0)"})
    assert done.paths[0].moves_before == 3


# --- random mixes of the constructs ----------------------------------------------------------
SNIPPETS = [
    'TY "pass"', "SPE 50 ALWAYS", "ACCU 5 ALWAYS", "TWA 0.1", "BRE", "LM b", "JM a",
    "IF direction == 8 THEN\nLMOVE b\nELSE\nLMOVE c\nEND", '$cnt[0] = $cnt[0] + "x"', "LMOVE pick.mem",
    "SPEED bead.speed MM/S", "FOR .i = 1 TO layers\nLMOVE c\nEND", "WAIT ready",
    "CASE part OF\nVALUE 1:\nLMOVE a\nANY :\nLMOVE b\nEND", "POINT .m = AVE_TRANS(a, b)\nLMOVE .m",
    "x = TIMER(1) + TRQNM(2)", "POINT .t = TRADD(a, b)", "LMOVE zz.f(1)", 'x = EXISTINTEGER("cnt")',
    "CALL fill(.&arr[,])\nLMOVE .arr[1,1]", '.$d[1] = "a"\nCALL send(.$d[], 1)', 'value[1] = VAL("3")',
    "step = 2\nlen = 1 + step", "POINT .#j = a, #h\nJMOVE .#j", "BREAK\nSIGNAL 1\nLMOVE c\nBREAK\nSIGNAL -1",
    "SIGNAL 9", "x = " + "+".join(["1"] * 300), "ALIGN", "DRIVE 1, 5", "CALL nowhere", "WEIGHT 5, 0, 0, 50",
    "MVWAIT 5 MM", "ON 1010 CALL fill", "DECOMPOSE d[1] = a", "LDEPART 20", "HERE .h\nLMOVE .h",
]
BROKEN = ["FOR .k = 1 TO 2", "ACC 1", "x = " + "(" * 80 + "1" + ")" * 80, "IF x THEN", "LMOVE a,"]
EXTRA = (".PROGRAM fill(.&p[,])\n  POINT .p[1,1] = SHIFT(a BY 10, 0, 0)\n.END\n"
         ".PROGRAM send(.$m[], .n)\n  $last = .$m[.n]\n.END\n")
SLOW = [HealthCheck.too_slow, HealthCheck.function_scoped_fixture]
POSES = ".TRANS\na 620 -60 300 0 180 0\nb 720 -60 300 0 180 0\nc 720 60 300 0 180 0\n.END\n" \
        ".JOINTS\n#h 0 10 40 0 50 0\n.END\n"


@settings(max_examples=150, deadline=None, suppress_health_check=SLOW)
@given(snippets=st.lists(st.sampled_from(SNIPPETS), min_size=1, max_size=12), style=st.sampled_from(STYLES),
       broken=st.booleans(), defect=st.sampled_from(BROKEN), gun=st.integers(1, 12), data=st.data())
def test_random_mixes_read_or_fail_in_one_line(snippets, style, broken, defect, gun, data, cell, tmp_path):
    body = "\n".join(["JMOVE a", *snippets] + ([defect] if broken else []))
    path = tmp_path / f"mix.{data.draw(st.sampled_from(['as', 'pg']))}"
    path.write_bytes(styled(body, style, POSES, extra=EXTRA).encode("latin-1"))
    try:
        done = check_program(path, gun_signal=gun, kinematics=cell[0], gun_tcp=cell[1])
    except CoatsimError as exc:
        message = str(exc)
        assert message.startswith(str(path)) and "\n" not in message, message
        assert broken, message  # only a defect refuses to read
        return
    assert not broken, "a defect was read"
    assert all(u.count("\n") == 0 for u in (*done.unknowns, *done.skipped, *done.warnings))


@settings(max_examples=25, deadline=None, suppress_health_check=SLOW)
@given(snippets=st.lists(st.sampled_from(SNIPPETS), min_size=1, max_size=8), style=st.sampled_from(STYLES),
       broken=st.booleans(), defect=st.sampled_from(BROKEN))
def test_the_command_exits_0_or_prints_one_line(snippets, style, broken, defect, run_cli, tmp_path):
    path = tmp_path / "mix.as"
    body = "\n".join(["JMOVE a", *snippets] + ([defect] if broken else []))
    path.write_bytes(styled(body, style, POSES, extra=EXTRA).encode("latin-1"))
    code, out, err = run_cli(["check-program", str(path), "--set", "direction=8"])
    if broken:
        assert code == 2 and err.startswith(f"coatsim: error: {path}:") and err.count("\n") == 1, err
    else:
        assert code in (0, 3) and (err == "" if code == 0 else err.count("\n") == 1), err
        assert code == 0 or "coatsim: error:" in err
