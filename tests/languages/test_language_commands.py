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


def test_files_are_told_apart_by_their_opening(tmp_path):
    (tmp_path / "a.txt").write_text("MODULE x\nENDMODULE\n")
    (tmp_path / "b.txt").write_text("&ACCESS RVP\nDEF b( )\nEND\n")
    (tmp_path / "c.txt").write_text(".PROGRAM c()\n.END\n")
    assert language_of([tmp_path / "a.txt"]).name == "abb-rapid"
    assert language_of([tmp_path / "b.txt"]).name == "kuka-krl"
    assert language_of([tmp_path / "c.txt"]).name == "kawasaki-as"
    assert language("krl").name == "kuka-krl" and language("RAPID").name == "abb-rapid"


@pytest.mark.parametrize("target, suffix, words", [("rapid", ".mod", "MoveC"), ("krl", ".src", "CIRC"),
                                                   ("as", ".as", "C1MOVE")])
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
