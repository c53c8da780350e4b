"""The commands in any registered language: program --language, check-program and convert by
suffix, by content and by --language, convert --to another language, a scenario variant in a
language."""

from __future__ import annotations

import re

import pytest

from coatsim.languages.registry import language, language_of


def test_program_writes_each_language_with_its_suffix(tmp_path, run_cli):
    out = tmp_path / "rr.mod"
    code, text, err = run_cli(["program", "builtin:ellipse", "--tol", "0.1", "--language", "rapid", "-o", str(out)])
    assert code == 0, err
    assert out.read_text().startswith("MODULE ellipse") and "MoveC" in out.read_text()
    src = tmp_path / "coat_ring.src"
    code, _, err = run_cli(["program", "builtin:ellipse", "--tol", "0.1", "--language", "kuka-krl", "-o", str(src)])
    assert code == 0, err
    assert "DEF coat_ring( )" in src.read_text() and "DEFDAT coat_ring" in src.with_suffix(".dat").read_text()
    code, text, err = run_cli(["check-program", str(src)])
    assert code == 0 and "moves:" in text and "arc" in text, err


@pytest.mark.parametrize("name", ["coat", "coat.txt", "coat.dat"])
def test_a_program_of_two_files_must_be_saved_under_its_main_suffix(tmp_path, run_cli, name):
    """A KRL program is its .src and .dat, paired by name: saved as ``coat`` and ``coat.dat`` it
    is neither loaded by a controller nor read back (the .dat is not found); nothing is written."""
    code, _, err = run_cli(["program", "builtin:ellipse", "--tol", "0.1", "--language", "kuka-krl",
                            "-o", str(tmp_path / name)])
    assert code == 2 and "a KUKA KRL program is saved as NAME.src and NAME.dat; name the output coat.src" in err
    assert list(tmp_path.iterdir()) == []


def test_files_are_told_apart_by_their_opening(tmp_path):
    (tmp_path / "a.txt").write_text("MODULE x\nENDMODULE\n")
    (tmp_path / "b.txt").write_text("&ACCESS RVP\nDEF b( )\nEND\n")
    (tmp_path / "c.txt").write_text(".PROGRAM c()\n.END\n")
    assert language_of([tmp_path / "a.txt"]).name == "abb-rapid"
    assert language_of([tmp_path / "b.txt"]).name == "kuka-krl"
    assert language_of([tmp_path / "c.txt"]).name == "kawasaki-as"
    assert language("krl").name == "kuka-krl" and language("RAPID").name == "abb-rapid"
    (tmp_path / "d.txt").write_text("/PROG  D\n/ATTR\n/MN\n   1:  DO[1]=ON ;\n/POS\n/END\n")
    (tmp_path / "e.txt").write_text("def e():\n  movel(p[0.5, 0, 0.3, 0, 3.1416, 0], v=0.2)\nend\n")
    (tmp_path / "f.txt").write_text("%\n(a CAM post)\nN10 G21 G90\nN20 G1X10Y5F600\n%\n")
    assert language_of([tmp_path / "d.txt"]).name == "fanuc-tp"
    assert language_of([tmp_path / "e.txt"]).name == "urscript"  # a def with a colon is not KRL's DEF
    assert language_of([tmp_path / "f.txt"]).name == "gcode"
    assert language("fanuc").name == "fanuc-tp" and language("TP").name == "fanuc-tp"


@pytest.mark.parametrize("target, suffix, words", [("rapid", ".mod", "MoveC"), ("krl", ".src", "CIRC"),
                                                   ("as", ".as", "C1MOVE"), ("fanuc", ".ls", "C P["),
                                                   ("urscript", ".script", "movec("), ("gcode", ".ngc", "G3")])
def test_convert_a_polyline_program_to_arcs_in_another_language(tmp_path, run_cli, target, suffix, words):
    poly = tmp_path / "poly.mod"
    code, _, err = run_cli(["program", "builtin:ellipse", "--tol", "0.05", "--variant", "polyline-blend", "--language",
                            "abb-rapid", "-o", str(poly)])
    assert code == 0, err
    out = tmp_path / f"arcs{suffix}"
    code, text, err = run_cli(["convert", str(poly), "--tol", "0.1", "--to", target, "-o", str(out)])
    assert code == 0, err
    m = re.search(r"(\d+) moves -> (\d+) .*deviation ([0-9.]+) mm", text)
    assert m and int(m.group(2)) < int(m.group(1)) and float(m.group(3)) <= 0.1
    assert words in out.read_text() and "standalone program" in text


def test_rapid_is_not_edited_in_place(tmp_path, run_cli):
    poly = tmp_path / "poly.mod"
    run_cli(["program", "builtin:ellipse", "--tol", "0.05", "--variant", "polyline-blend", "--language", "rapid",
             "-o", str(poly)])
    code, _, err = run_cli(["convert", str(poly), "--tol", "0.1"])
    assert code == 2 and "not edited in place" in err and err.count("\n") == 1


@pytest.mark.parametrize("source, suffix", [("fanuc-tp", ".ls"), ("urscript", ".script"), ("gcode", ".ngc")])
def test_a_polyline_program_in_each_language_converts_to_arcs_in_as(tmp_path, run_cli, source, suffix):
    """check-program reports a Fanuc, URScript or G-code program as it does any (its switches and
    sprayed lines), and convert --to rewrites its sprayed path with arcs."""
    poly = tmp_path / f"poly{suffix}"
    code, _, err = run_cli(["program", "builtin:ellipse", "--tol", "0.05", "--variant", "polyline-blend", "--language",
                            source, "-o", str(poly)])
    assert code == 0, err
    code, text, err = run_cli(["check-program", str(poly)])
    assert code == 0, err
    assert "(gun on)" in text and "(gun off)" in text and re.search(r"sprayed: lines \d+-\d+ of ", text)
    out = tmp_path / "arcs.as"
    code, text, err = run_cli(["convert", str(poly), "--tol", "0.1", "--to", "as", "-o", str(out)])
    assert code == 0, err
    m = re.search(r"(\d+) moves -> (\d+) .*deviation ([0-9.]+) mm", text)
    assert m and int(m.group(2)) < int(m.group(1)) and float(m.group(3)) <= 0.1
    assert "C1MOVE" in out.read_text()
