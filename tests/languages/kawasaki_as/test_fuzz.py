"""The reader and the interpreter never fail with anything but a one-line InputError (or an
ExecutionError for what the twin cannot run), whatever the input."""

from __future__ import annotations

from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from coatsim.core.errors import ExecutionError, InputError
from coatsim.languages.kawasaki_as import interpret, parse_as_bytes

from as_samples import BACKUP, MACHINE_TENDING, PALLETISING

GOLDEN = (Path(__file__).resolve().parents[2] / "path" / "data" / "roundrect_polysegment.as").read_bytes()
SAMPLES = [GOLDEN, BACKUP, MACHINE_TENDING.encode(), PALLETISING.encode()]
WORDS = [
    ".PROGRAM", ".END", ".TRANS", ".JOINTS", ".REALS", ".STRINGS", ".AUXDATA", ".*", "JMOVE", "LMOVE", "C1MOVE",
    "C2MOVE", "JAPPRO", "LAPPRO", "LDEPART", "JDEPART", "DRAW", "TDRAW", "HOME", "DELAY", "SPEED", "ACCURACY",
    "ACCEL", "CP", "ON", "OFF", "BREAK", "SIGNAL", "TWAIT", "TOOL", "BASE", "POINT", "TRANS", "SHIFT", "BY", "NULL",
    "ALWAYS", "FINE", "MM", "S", "MIN", "%", "/", "(", ")", "[", "]", ",", "=", "+", "-", "#", "$", ";", ":", '"',
    "p1", "p2", "#home", "x()", "0", "1", "-1", "1.5", "1e3", "1e999", "180", ".5", "125.", "\n", "\r\n", "\r",
    "\t", " ", "\x00", "\xe9", "\ufeff", "IF", "THEN", "ELSE", "END", "WHILE", "DO", "UNTIL", "FOR", "TO", "STEP",
    "CASE", "OF", "VALUE", "ANY", "GOTO", "CALL", "RETURN", "x", ".x", "$s", "&x", ".&x", "^HFF", "AND", "NOT", "==",
    "SIN(", "TRANS(", "SHIFT(", "#[", "SWAIT", "WAIT", "SIG(", "TCP_RECV", "HERE", "POINT/X", "DECOMPOSE", "10",
    ".STRINGS", ".SYSDATA", ".NETCONF", "EXIT", "STOP", "BITS", "PULSE",
]
SETTINGS = settings(max_examples=250, deadline=None, suppress_health_check=[HealthCheck.too_slow])


def read(data: bytes) -> None:
    """Parse and interpret; anything but an InputError fails the test."""
    try:
        interpret(parse_as_bytes(data, "fuzz.as"), max_steps=20_000)
    except (InputError, ExecutionError) as exc:
        message = str(exc)
        assert message.startswith("fuzz.as") or message.startswith("gun"), message
        assert "\n" not in message


@SETTINGS
@given(st.binary(max_size=400))
def test_random_bytes(data):
    read(data)


@SETTINGS
@given(st.lists(st.sampled_from(WORDS), max_size=80))
def test_token_soup(words):
    read(" ".join(words).encode("utf-8"))


@SETTINGS
@given(st.lists(st.sampled_from(WORDS), max_size=30))
def test_token_soup_inside_a_program(words):
    body = " ".join(words).replace(" \n ", "\n")
    read(b".PROGRAM f()\n  JMOVE p1\n" + body.encode("utf-8") + b"\n.END\n.TRANS\np1 0 0 0 0 180 0\np2 1 2 3 4 5 6\n.END\n")


@st.composite
def mutations(draw):
    data = bytearray(draw(st.sampled_from(SAMPLES)))
    for _ in range(draw(st.integers(1, 6))):
        kind = draw(st.sampled_from(["delete", "insert", "replace", "drop_line", "swap_lines"]))
        pos = draw(st.integers(0, len(data) - 1))
        if kind == "delete":
            del data[pos:pos + draw(st.integers(1, 20))]
        elif kind == "insert":
            data[pos:pos] = draw(st.sampled_from(WORDS)).encode("utf-8")
        elif kind == "replace":
            data[pos] = draw(st.integers(0, 255))
        else:
            lines = bytes(data).split(b"\n")
            i, j = draw(st.integers(0, len(lines) - 1)), draw(st.integers(0, len(lines) - 1))
            if kind == "drop_line":
                del lines[i]
            else:
                lines[i], lines[j] = lines[j], lines[i]
            data = bytearray(b"\n".join(lines))
        if not data:
            break
    return bytes(data)


@SETTINGS
@given(mutations())
def test_mutated_valid_programs(data):
    read(data)


def test_golden_reads():
    assert len(interpret(parse_as_bytes(GOLDEN, "fuzz.as")).spray_moves) == 8
