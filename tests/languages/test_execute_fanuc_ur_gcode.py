"""``coatsim execute`` reads a Fanuc TP, URScript or G-code program by its suffix and runs it;
a program the twin cannot run exits 3, one that is not valid exits 2, each with one line."""

from __future__ import annotations

import json

import pytest

from coatsim.languages.registry import language

from cli_helpers import cli
from language_plans import planned


@pytest.mark.parametrize("name, suffix", [("fanuc-tp", ".LS"), ("urscript", ".script"), ("gcode", ".nc")])
def test_execute_runs_a_written_program(name, suffix, tmp_path):
    program = tmp_path / f"shapes{suffix}"
    program.write_text(planned(name).text)
    code, out, err = cli("execute", program, "-o", tmp_path / "out")
    assert code == 0, err
    motion = json.loads((tmp_path / "out" / "motion.json").read_text())["motion"]
    assert motion["curve_length_mm"] == pytest.approx(442.8318531, abs=5e-3) and motion["stops"] == 0
    assert "cycle" in out


@pytest.mark.parametrize("name, text, code, words", [
    ("fanuc-tp", "/PROG  BAD\n/MN\n   1:J P[1] 50% FINE ;\n   2:A P[1] 100mm/sec CNT100 ;\n/POS\n"
                 "P[1]{GP1: UF : 0, UT : 0, X = 700 mm, Y = 0 mm, Z = 300 mm, W = 180 deg, P = 0 deg, R = 0 deg};\n/END\n",
     3, "A motion"),
    ("urscript", "def bad():\n  movel(p[0.7, 0, 0.3])\nend\n", 2, "a pose p[...] has 6 values"),
    ("gcode", "G21 G90\nG0 X700 Y0 Z300\nG1 X710 A10 F600\n", 3, "axis A"),
])
def test_execute_reports_a_bad_program_in_one_line(name, text, code, words, tmp_path):
    program = tmp_path / f"bad{language(name).suffixes[0]}"
    program.write_text(text)
    got, _, err = cli("execute", program, "-o", tmp_path / "out")
    assert got == code and words in err and err.count("\n") == 1, err
