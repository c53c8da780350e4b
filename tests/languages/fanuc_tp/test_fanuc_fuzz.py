"""The .LS reader never fails with anything but a one-line InputError (or an ExecutionError for
what the twin cannot run), whatever the bytes."""

from __future__ import annotations

from coatsim.languages.fanuc_tp.language import FANUC_TP
from coatsim.path.language import ReadOptions

from fuzzing import fuzz_tests, read_fuzzed
from language_plans import planned

GOLDEN = planned("fanuc-tp").text.encode()
WORDS = ["/PROG", "/ATTR", "/MN", "/POS", "/END", "/APPL", "MAIN", "1:", ":", ";", "J", "L", "C", "A", "P[1]", "P[2]",
         "PR[1]", "PR[1,2]", "P[", "]", "[", "100%", "500mm/sec", "2sec", "FINE", "CNT100", "CNT", "CR5", "R[1]",
         "R[R[1]]", "AR[1]", "=", "+", "-", "*", "/", "MOD", "DIV", "(", ")", ",", "!", "//", "LBL[1]", "JMP",
         "IF", "THEN", "ELSE", "ENDIF", "FOR", "TO", "DOWNTO", "ENDFOR", "SELECT", "CALL", "WAIT", "DI[1]=ON",
         "DO[1]=ON", "DO[1]=OFF", "PULSE", "UFRAME_NUM=1", "UTOOL_NUM=1", "UFRAME[1]=PR[1]", "LPOS", "JPOS",
         "Offset,PR[1]", "INC", "ACC50", "TIMEOUT", "END", "ABORT", "OVERRIDE=50%", "GP1:", "UF : 1", "UT : 1",
         "X = 1 mm", "W = 1 deg", "J1= 1 deg", "{", "};", "'N U T, 0, 0, 0'", "\n", "\r\n", "\t", " ", "\x00",
         "\xe9", "1e999", "-0", ".5", "$X"]


def read(data: bytes, folder) -> None:
    read_fuzzed(FANUC_TP, data, folder, ".ls", ReadOptions(), also_starts=("program ",))


test_random_bytes, test_word_soup_inside_a_program, test_a_written_program_with_words_spliced_in = fuzz_tests(
    read, WORDS, GOLDEN, lambda body: f"/PROG  MAIN\n/MN\n   1:  {body} ;\n   2:{body}\n/POS\n{body}\n/END\n", 60)
