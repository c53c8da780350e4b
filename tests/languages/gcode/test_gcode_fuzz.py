"""The G-code reader never fails with anything but a one-line InputError (or an ExecutionError
for what the twin cannot run), whatever the bytes."""

from __future__ import annotations

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from coatsim.core.errors import ExecutionError, InputError
from coatsim.languages.gcode.language import GCODE
from coatsim.path.language import ReadOptions

from language_plans import planned

GOLDEN = planned("gcode").text.encode()
WORDS = ["G0", "G1", "G2", "G3", "G4", "G10", "L2", "L20", "P1", "G17", "G18", "G19", "G20", "G21", "G28", "G53",
         "G54", "G55", "G59.3", "G61", "G61.1", "G64", "G90", "G91", "G90.1", "G91.1", "G92", "G92.1", "G9", "G41",
         "M3", "M5", "M7", "M9", "M2", "M30", "M62", "M98", "X", "Y", "Z", "I", "J", "K", "R", "F", "P", "A", "E", "N",
         "O", "o100 sub", "10", "-5", ".5", "1e3", "0", "[", "]", "#1", "#<a>", "=", "+", "*", "/", "**", "MOD",
         "SIN[", "ATAN[1]/[", "(", ")", ";", "%", "\n", "\r\n", "\t", " ", "\x00", "\xe9", "X1", "Y1", "Z1", "F100",
         "I5", "J5", "R5", "R-5", "P0.5", "X1e999", "#5221", "#5999", "#6000"]
SETTINGS = settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.too_slow])


def read(data: bytes, tmp_path) -> None:
    path = tmp_path / "fuzz.ngc"
    path.write_bytes(data)
    try:
        GCODE.read([path], ReadOptions(needs_spray=False))
    except (InputError, ExecutionError) as exc:
        assert str(exc).startswith(str(path)) and "\n" not in str(exc), str(exc)


@SETTINGS
@given(data=st.binary(max_size=400))
def test_random_bytes(data, tmp_path_factory):
    read(data, tmp_path_factory.mktemp("f"))


@SETTINGS
@given(words=st.lists(st.sampled_from(WORDS), max_size=80))
def test_word_soup(words, tmp_path_factory):
    read(" ".join(words).encode("utf-8", "replace"), tmp_path_factory.mktemp("f"))


@SETTINGS
@given(cut=st.integers(0, len(GOLDEN)), words=st.lists(st.sampled_from(WORDS), max_size=12))
def test_a_written_program_with_words_spliced_in(cut, words, tmp_path_factory):
    read(GOLDEN[:cut] + " ".join(words).encode() + GOLDEN[cut:], tmp_path_factory.mktemp("f"))
