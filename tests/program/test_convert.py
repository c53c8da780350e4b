"""coatsim convert: a program written by hand in a user's style becomes an arc program of the
same path, within the tolerance, with far fewer moves, everything around it untouched."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

from coatsim.errors import InputError
from coatsim.program import read_toolpath
from coatsim.program.as_lang.source import split_lines
from coatsim.program.convert import ConvertOptions, convert_program

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent / "as_lang"))
from as_samples import rounded_rectangle_points, user_contour  # noqa: E402

TOL = 0.1


@pytest.fixture(scope="module")
def kin():
    from coatsim.robot.kinematics import LazyKinematics

    return LazyKinematics()


def write(tmp_path, data: bytes, name="user.as") -> Path:
    path = tmp_path / name
    path.write_bytes(data)
    return path


def test_user_style_contour_in_place(tmp_path, kin):
    points = rounded_rectangle_points()
    src = write(tmp_path, user_contour(points))
    result = convert_program(src, ConvertOptions(TOL), kinematics=kin)
    (report,) = result.paths
    assert report.moves_before == len(points) - 1 and report.moves_after <= 12
    assert report.deviation_mm <= TOL and report.n_arcs >= 4
    original, edited = src.read_bytes(), result.text.encode("latin-1")
    assert b"\xe9paisseur" in edited and edited.count(b"\r\n") == edited.count(b"\n")   # code page and CRLF kept
    old_lines, new_lines = split_lines(original.decode("latin-1")), split_lines(result.text)
    first, last = report.first_line, report.last_line
    statements = report.moves_after + report.n_arcs   # an arc is a C1MOVE and a C2MOVE
    block = new_lines[first - 1:first + statements]
    assert block[0].lstrip().startswith("; coatsim convert:") and len(block) == 1 + statements
    assert new_lines[:first - 1] == old_lines[:first - 1]                  # untouched before
    assert new_lines[first + statements:-(statements + 2)] == old_lines[last:]  # and after, up to the new poses
    assert new_lines[-(statements + 2)] == ".TRANS" and new_lines[-1] == ".END"
    out = tmp_path / "arcs.as"
    out.write_text(result.text, encoding="latin-1", newline="")
    before, after = read_toolpath(src, kinematics=kin), read_toolpath(out, kinematics=kin)
    assert len(after.moves) == len(before.moves) - report.moves_before + report.moves_after
    assert sum(m.spray for m in after.moves) == report.moves_after
    assert after.metadata == before.metadata and after.dwells[0].seconds == pytest.approx(0.1)


def test_contour_in_a_tilted_plane(tmp_path, kin):
    src = write(tmp_path, user_contour(rounded_rectangle_points(), tilt_deg=30.0))
    (report,) = convert_program(src, ConvertOptions(TOL), kinematics=kin).paths
    assert report.deviation_mm <= TOL and report.moves_after <= 12 and report.plane_deviation_mm < 1e-3


def test_standalone(tmp_path, kin):
    src = write(tmp_path, user_contour(rounded_rectangle_points()))
    result = convert_program(src, ConvertOptions(TOL, standalone=True, name="arcs"), kinematics=kin)
    assert result.replaces is None and result.text.startswith(".PROGRAM arcs()")
    out = tmp_path / "arcs.as"
    out.write_text(result.text)
    tp = read_toolpath(out)
    assert tp.metadata["tool"] == "0,0,250,0,0,0" and tp.metadata["variant"] == "convert"
    assert result.paths[0].deviation_mm <= TOL
    assert all(m.settings.speed_mm_s == 150.0 for m in tp.spray_moves)


def test_points_fed_by_a_loop(tmp_path):
    pts = rounded_rectangle_points(80, 40, 10, step=2.0)
    trans = "\n".join(f"c[{i}] {700 + x:.4f} {y:.4f} 300 0 180 0" for i, (x, y) in enumerate(pts))
    text = (".PROGRAM loop()\n  SPEED 100 MM/S ALWAYS\n  JMOVE c[0]\n  BREAK\n  SIGNAL 1\n  FOR .i = 1 TO "
            f"{len(pts) - 1}\n    LMOVE c[.i]\n  END\n  BREAK\n  SIGNAL -1\n.END\n.TRANS\n{trans}\n.END\n")
    src = write(tmp_path, text.encode())
    result = convert_program(src, ConvertOptions(TOL))
    (report,) = result.paths
    assert (report.first_line, report.last_line) == (6, 8) and report.moves_after < 12
    assert "FOR .i" not in result.text and "SIGNAL -1" in result.text


def test_a_sprayed_descent_is_kept_and_the_gun_switch_moves_with_it(tmp_path):
    pts = rounded_rectangle_points(80, 40, 10, step=2.0)
    trans = "\n".join(f"c[{i}] {700 + x:.4f} {y:.4f} 300 0 180 0" for i, (x, y) in enumerate(pts))
    body = "\n".join(f"  LMOVE c[{i}]" for i in range(1, len(pts)))
    text = (".PROGRAM fwd()\n  JMOVE above\n  LMOVE c[0]\n  SIGNAL 1\n" + body + "\n  SIGNAL -1\n  LMOVE above\n.END\n"
            f".TRANS\nabove 740 -20 400 0 180 0\n{trans}\n.END\n")
    src = write(tmp_path, text.encode())
    result = convert_program(src, ConvertOptions(TOL))
    assert any("first sprayed move" in n for n in result.notes)
    assert result.paths[0].deviation_mm <= TOL and result.paths[0].moves_before == len(pts) - 2


def test_switch_inside_the_path_is_written_again(tmp_path):
    pts = rounded_rectangle_points(80, 40, 10, step=2.0)
    trans = "\n".join(f"c[{i}] {700 + x:.4f} {y:.4f} 300 0 180 0" for i, (x, y) in enumerate(pts))
    body = "\n".join(f"  LMOVE c[{i}]" for i in range(2, len(pts)))
    text = (".PROGRAM fwd()\n  JMOVE c[0]\n  LMOVE c[1]\n  SIGNAL 1\n" + body + "\n  BREAK\n  SIGNAL -1\n.END\n"
            f".TRANS\n{trans}\n.END\n")
    src = write(tmp_path, text.encode())
    result = convert_program(src, ConvertOptions(TOL))
    assert result.paths[0].moves_before == len(pts) - 1 and "gun on (as in the original)" in result.text


def test_not_planar_is_one_line(tmp_path):
    lines = ["  LMOVE h[%d]" % i for i in range(1, 200)]
    trans = "\n".join(f"h[{i}] {700 + 50 * math.cos(i / 10):.4f} {50 * math.sin(i / 10):.4f} {300 + i / 5:.4f} 0 180 0"
                      for i in range(200))
    text = ".PROGRAM helix()\n  JMOVE h[0]\n  BREAK\n  SIGNAL 1\n" + "\n".join(lines) + f"\n  BREAK\n  SIGNAL -1\n.END\n.TRANS\n{trans}\n.END\n"
    with pytest.raises(InputError) as info:
        convert_program(write(tmp_path, text.encode()), ConvertOptions(TOL))
    assert "is not planar" in str(info.value) and "\n" not in str(info.value)


@pytest.mark.parametrize("inside,words", [
    ("  TWAIT 0.5\n", "TWAIT"), ("  SIGNAL 5\n", "SIGNAL"), ("  SPEED 50 MM/S ALWAYS\n", "SPEED"),
    ("  CALL noop\n", "CALLPROGRAM"),
])
def test_statements_that_cannot_stay_are_refused(tmp_path, inside, words):
    pts = rounded_rectangle_points(80, 40, 10, step=2.0)
    trans = "\n".join(f"c[{i}] {700 + x:.4f} {y:.4f} 300 0 180 0" for i, (x, y) in enumerate(pts))
    moves = [f"  LMOVE c[{i}]" for i in range(1, len(pts))]
    moves.insert(20, inside.rstrip("\n"))
    text = (".PROGRAM x()\n  JMOVE c[0]\n  BREAK\n  SIGNAL 1\n" + "\n".join(moves) + "\n  BREAK\n  SIGNAL -1\n.END\n"
            ".PROGRAM noop()\n.END\n" f".TRANS\n{trans}\n.END\n")
    src = write(tmp_path, text.encode())
    with pytest.raises(InputError) as info:
        convert_program(src, ConvertOptions(TOL))
    assert "--standalone" in str(info.value) and (words in str(info.value) or "speed" in str(info.value))
    assert convert_program(src, ConvertOptions(TOL, standalone=True)).paths[0].deviation_mm <= TOL or words != "SPEED"


def test_named_lines_and_errors(tmp_path):
    pts = rounded_rectangle_points(80, 40, 10, step=2.0)
    trans = "\n".join(f"c[{i}] {700 + x:.4f} {y:.4f} 300 0 180 0" for i, (x, y) in enumerate(pts))
    body = "\n".join(f"  LMOVE c[{i}]" for i in range(1, len(pts)))
    text = ".PROGRAM x()\n  JMOVE c[0]\n" + body + f"\n.END\n.TRANS\n{trans}\n.END\n"
    src = write(tmp_path, text.encode())
    with pytest.raises(InputError, match="no process path"):
        convert_program(src, ConvertOptions(TOL))
    result = convert_program(src, ConvertOptions(TOL, lines=(3, 40)))
    assert result.paths[0].moves_before == 38 and result.paths[0].deviation_mm <= TOL
    with pytest.raises(InputError, match="no motion comes from these lines"):
        convert_program(src, ConvertOptions(TOL, lines=(5000, 5001)))
    with pytest.raises(InputError, match="joint move"):
        convert_program(src, ConvertOptions(TOL, lines=(1, 10)))


def test_cli(tmp_path, run_cli):
    src = write(tmp_path, user_contour(rounded_rectangle_points(), crlf=False))
    out = tmp_path / "arcs.as"
    code, text, err = run_cli(["convert", str(src), "--tol", "0.1", "-o", str(out)])
    assert code == 0, err
    m = re.search(r"(\d+) moves -> (\d+) \((\d+) lines \+ (\d+) arcs\).*deviation ([0-9.]+) mm", text)
    assert m and int(m.group(2)) < int(m.group(1)) / 10 and float(m.group(5)) <= 0.1
    assert f"wrote {out}" in text and out.read_text().startswith(".PROGRAM trace()")
    code, text, err = run_cli(["convert", str(src), "--tol", "0.1", "--standalone"])
    assert code == 0 and text.startswith(".PROGRAM trace()") and "standalone program" in err
    for args, words in ((["--tol", "0"], "--tol"), (["--tol", "0.1", "--lines", "9-x"], "--lines"),
                        (["--tol", "0.1", "--name", "bad name"], "not a valid AS name")):
        code, _, err = run_cli(["convert", str(src), *args])
        assert code == 2 and words in err and err.count("\n") == 1


@pytest.mark.slow
def test_the_twin_runs_both(tmp_path):
    """End to end on the real stack: the user's polyline program and its arc version."""
    from coatsim.robot.cell import load_cell
    from coatsim.robot.execute import execute
    from coatsim.robot.kinematics import CellKinematics

    cell = load_cell()
    kin = CellKinematics(cell)
    src = write(tmp_path, user_contour(rounded_rectangle_points()))
    result = convert_program(src, ConvertOptions(TOL), kinematics=kin)
    out = tmp_path / "arcs.as"
    out.write_text(result.text, encoding="latin-1", newline="")
    runs = {name: execute(read_toolpath(path, kinematics=kin), cell) for name, path in (("user", src), ("arcs", out))}
    for ex in runs.values():
        assert ex.metrics.max_path_error_mm < 0.5 and ex.log.spray.any()
    sprayed = {k: float(np.linalg.norm(np.diff(ex.log.position[ex.log.spray], axis=0), axis=1).sum())
               for k, ex in runs.items()}
    assert sprayed["arcs"] == pytest.approx(sprayed["user"], rel=0.01)
