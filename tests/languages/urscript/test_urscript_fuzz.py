"""The URScript reader never fails with anything but a one-line InputError (or an ExecutionError
for what the twin cannot run), whatever the bytes."""

from __future__ import annotations

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from coatsim.core.errors import ExecutionError, InputError
from coatsim.languages.urscript.language import URSCRIPT
from coatsim.path.language import ReadOptions

from language_plans import planned

GOLDEN = planned("urscript").text.encode()
WORDS = ["def", "end", "f():", "if", "elif", "else:", "while", "for", "i", "in", "range(0, 3)", "return", "break",
         "continue", "halt", "global", "local", "x", "=", "==", "!=", "<", "+", "-", "*", "/", "%", "and", "or",
         "not", "xor", "True", "False", "(", ")", "[", "]", ",", ":", "p[", "0.1", "-1", "1e3", "1e999", ".5",
         "movel(p[0.5,0,0.3,3.14,0,0])", "movec(", "movej(", "movep(", "a=1.2", "v=0.25", "r=0.001", "t=1",
         "mode=1", "set_tcp(", "set_digital_out(1, True)", "sleep(1)", "sync()", "pose_trans(", "pose_add(",
         "get_actual_tcp_pose()", "get_inverse_kin(", "\"s\"", "'s'", "#", "$ 1 \"x\"", "\n", "\r\n", "\t", " ",
         "\x00", "\xe9", "thread", "run", "speedl("]
SETTINGS = settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.too_slow])


def read(data: bytes, folder) -> None:
    path = folder / "fuzz.script"
    path.write_bytes(data)
    try:
        URSCRIPT.read([path], ReadOptions())
    except (InputError, ExecutionError) as exc:
        assert str(exc).startswith(str(path)) and "\n" not in str(exc), str(exc)


@SETTINGS
@given(data=st.binary(max_size=400))
def test_random_bytes(data, tmp_path_factory):
    read(data, tmp_path_factory.mktemp("f"))


@SETTINGS
@given(words=st.lists(st.sampled_from(WORDS), max_size=60))
def test_word_soup_inside_a_program(words, tmp_path_factory):
    body = " ".join(words)
    read(f"def prog():\n  movej(p[0.5, 0, 0.3, 3.14, 0, 0])\n  {body}\nend\n".encode("utf-8", "replace"),
         tmp_path_factory.mktemp("f"))


@SETTINGS
@given(cut=st.integers(0, len(GOLDEN)), words=st.lists(st.sampled_from(WORDS), max_size=12))
def test_a_written_program_with_words_spliced_in(cut, words, tmp_path_factory):
    read(GOLDEN[:cut] + " ".join(words).encode() + GOLDEN[cut:], tmp_path_factory.mktemp("f"))
