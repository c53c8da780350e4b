"""The URScript reader never fails with anything but a one-line InputError (or an ExecutionError
for what the twin cannot run), whatever the bytes."""

from __future__ import annotations

from coatsim.languages.urscript.language import URSCRIPT
from coatsim.path.language import ReadOptions

from fuzzing import fuzz_tests, read_fuzzed
from language_plans import planned

GOLDEN = planned("urscript").text.encode()
WORDS = ["def", "end", "f():", "if", "elif", "else:", "while", "for", "i", "in", "range(0, 3)", "return", "break",
         "continue", "halt", "global", "local", "x", "=", "==", "!=", "<", "+", "-", "*", "/", "%", "and", "or",
         "not", "xor", "True", "False", "(", ")", "[", "]", ",", ":", "p[", "0.1", "-1", "1e3", "1e999", ".5",
         "movel(p[0.5,0,0.3,3.14,0,0])", "movec(", "movej(", "movep(", "a=1.2", "v=0.25", "r=0.001", "t=1",
         "mode=1", "set_tcp(", "set_digital_out(1, True)", "sleep(1)", "sync()", "pose_trans(", "pose_add(",
         "get_actual_tcp_pose()", "get_inverse_kin(", "\"s\"", "'s'", "#", "$ 1 \"x\"", "\n", "\r\n", "\t", " ",
         "\x00", "\xe9", "thread", "run", "speedl("]


def read(data: bytes, folder) -> None:
    read_fuzzed(URSCRIPT, data, folder, ".script", ReadOptions())


test_random_bytes, test_word_soup_inside_a_program, test_a_written_program_with_words_spliced_in = fuzz_tests(
    read, WORDS, GOLDEN, lambda body: f"def prog():\n  movej(p[0.5, 0, 0.3, 3.14, 0, 0])\n  {body}\nend\n", 60)
