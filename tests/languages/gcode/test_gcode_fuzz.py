"""The G-code reader never fails with anything but a one-line InputError (or an ExecutionError
for what the twin cannot run), whatever the bytes."""

from __future__ import annotations

from coatsim.languages.gcode.language import GCODE
from coatsim.path.language import ReadOptions

from fuzzing import fuzz_tests, read_fuzzed
from language_plans import planned

GOLDEN = planned("gcode").text.encode()
WORDS = ["G0", "G1", "G2", "G3", "G4", "G10", "L2", "L20", "P1", "G17", "G18", "G19", "G20", "G21", "G28", "G53",
         "G54", "G55", "G59.3", "G61", "G61.1", "G64", "G90", "G91", "G90.1", "G91.1", "G92", "G92.1", "G9", "G41",
         "M3", "M5", "M7", "M9", "M2", "M30", "M62", "M98", "X", "Y", "Z", "I", "J", "K", "R", "F", "P", "A", "E", "N",
         "O", "o100 sub", "10", "-5", ".5", "1e3", "0", "[", "]", "#1", "#<a>", "=", "+", "*", "/", "**", "MOD",
         "SIN[", "ATAN[1]/[", "(", ")", ";", "%", "\n", "\r\n", "\t", " ", "\x00", "\xe9", "X1", "Y1", "Z1", "F100",
         "I5", "J5", "R5", "R-5", "P0.5", "X1e999", "#5221", "#5999", "#6000"]


def read(data: bytes, folder) -> None:
    read_fuzzed(GCODE, data, folder, ".ngc", ReadOptions(needs_spray=False))


test_random_bytes, test_word_soup_inside_a_program, test_a_written_program_with_words_spliced_in = fuzz_tests(
    read, WORDS, GOLDEN, lambda body: body, 80)
