"""Programs put together from the statements cells write, with values both sane and hostile:
check-program and convert (in place and standalone) either work or stop with one line of a
CoatsimError; when convert writes a program, coatsim reads it again and it sprays within the
tolerance of the original."""

from __future__ import annotations

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from coatsim.core.errors import CoatsimError
from program_helpers import check_as as check_program
from coatsim.path.convert import ConvertOptions
from program_helpers import convert_as as convert_program

SANE = ["0", "1", ".5", "1.E+1", "5E-3", "-0", "3", "20", "-15", "12.345", "2^2", "-(3)", "INT(2.7)", "ABS(-4)"]
HOSTILE = ["1e300", "-1e300", "1/0", "SQRT(-2)", "1e15", "0.0", "-1"]
POSES = ["p1", "p2", "p1 + TRANS(10)", "SHIFT(p1 BY 5,,)", "p[1]", ".lp", "TRANS(600, 10, 300, 0, 180, 0)",
         "FRAME(p1, p2, p3, p1) + TRANS(20, 20, 0, 0, 180, 0)", "HERE", "-p1", "NULL", "#[0,0,35,0,55,0]"]


def number() -> st.SearchStrategy[str]:
    return st.one_of(st.sampled_from(SANE), st.sampled_from(HOSTILE),
                     st.floats(-60, 60, allow_nan=False).map(lambda x: f"{x:.3f}"))


def statement() -> st.SearchStrategy[str]:
    n, p = number(), st.sampled_from(POSES)
    return st.one_of(
        p.map(lambda q: f"LMOVE {q}"), p.map(lambda q: f"JMOVE {q}"), st.tuples(p, n).map(lambda t: f"LAPPRO {t[0]}, {t[1]}"),
        n.map(lambda x: f"LDEPART {x}"), st.tuples(p, p).map(lambda t: f"C1MOVE {t[0]}\n  C2MOVE {t[1]}"),
        st.tuples(n, n).map(lambda t: f"DRAW {t[0]}, {t[1]}"), n.map(lambda x: f"TDRAW , {x}"),
        st.tuples(n, st.sampled_from(["", "MM/S", "MM/MIN", "S", "%", "MM/S ALWAYS", "ALWAYS"])).map(
            lambda t: f"SPEED {t[0]} {t[1]}"),
        st.tuples(n, st.sampled_from(["", "FINE", "ALWAYS"])).map(lambda t: f"ACCURACY {t[0]} {t[1]}"),
        st.sampled_from(["BREAK", "SIGNAL 1", "SIGNAL -1", "SIGNAL 1, -2", "SIGNAL o.g", "SIGNAL -o.g", "CP OFF", "CP ON",
                         "HOME", "CALL gun", "HERE .lp", "DECOMPOSE .v[0] = p1", "MC SPEED 50", "ONI 1001 CALL gun",
                         "SWAIT 1001", "GOTO 10", "TOOL tl", "BASE NULL", "XMOVE p2 TILL 1001"]),
        n.map(lambda x: f"TWAIT {x}"), n.map(lambda x: f".x = {x}"), p.map(lambda q: f"POINT .lp = {q}"),
        st.tuples(n, p).map(lambda t: f"IF .x > {t[0]} THEN\n    LMOVE {t[1]}\n  ELSE\n    SIGNAL -1\n  END"),
        st.tuples(st.integers(0, 3), p).map(lambda t: f"FOR .i = 1 TO {t[0]}\n    LMOVE SHIFT({t[1]} BY .i * 5)\n  END"),
        n.map(lambda x: f"CALL setv({x}, .&x)"),
    )


DATA = (".PROGRAM gun()\n  SIGNAL 1\n.END\n.PROGRAM setv(.a, .&b)\n  .b = .a\n.END\n"
        ".TRANS\np1 560 -40 300 0 180 0\np2 640 -40 300 0 180 0\np3 560 40 300 0 180 0\np[1] 600 0 300 0 180 0\n"
        "tl 0 0 250 0 0 0\n.END\n.REALS\no.g = 1\n.END\n")


@pytest.fixture(scope="module")
def kin():
    from coatsim.robot.kinematics import LazyKinematics

    return LazyKinematics()


@given(st.lists(statement(), max_size=5), st.lists(statement(), max_size=6), st.lists(statement(), max_size=5))
@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow,
                                                                   HealthCheck.function_scoped_fixture])
def test_generated_programs_work_or_stop_with_one_line(tmp_path_factory, kin, before, inside, after):
    """Random statements before, inside and after a sprayed stretch."""
    lines = (["  .x = 0", "  TOOL TRANS(0,0,250)", "  JMOVE #[0,0,35,0,55,0]"] + before
             + ["LMOVE p1", "BREAK", "SIGNAL 1", "LMOVE TRANS(600, -40, 300, 0, 180, 0)"] + inside
             + ["LMOVE p2", "LMOVE TRANS(640, 0, 300, 0, 180, 0)", "BREAK", "SIGNAL -1"] + after + ["10 BREAK"])
    body = "\n".join(line if line.startswith(" ") or line.startswith("10") else "  " + line for line in lines)
    path = tmp_path_factory.mktemp("gen") / "gen.as"
    path.write_text(".PROGRAM gen()\n" + body + "\n.END\n" + DATA)
    for standalone in (None, False, True):
        try:
            if standalone is None:
                check_program(path, kinematics=kin)
                continue
            result = convert_program(path, ConvertOptions(0.1, standalone=standalone), kinematics=kin)
        except CoatsimError as exc:
            assert "\n" not in str(exc) and str(exc).strip(), str(exc)
            continue
        assert all(r.deviation_mm <= 0.1 + 1e-9 for r in result.paths)
        if not result.written:  # no path gains a move: nothing to write, every path kept as it was
            assert all(r.kept for r in result.paths) and result.data == b""
            continue
        out = path.with_name(f"out_{standalone}.as")
        out.write_bytes(result.data)
        check_program(out, kinematics=kin)
