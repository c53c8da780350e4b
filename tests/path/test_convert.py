"""coatsim convert: a program written by hand in a user's style becomes an arc program of the
same path, within the tolerance, with far fewer moves, everything around it untouched."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

from coatsim.core.errors import InputError
from coatsim.languages.kawasaki_as.files import read_toolpath
from coatsim.languages.kawasaki_as.source import split_lines
from coatsim.path.convert import ConvertOptions
from program_helpers import convert_as as convert_program

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parents[1] / "languages" / "kawasaki_as"))
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
    assert after.process == before.process and after.dwells[0].seconds == pytest.approx(0.1)


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
    np.testing.assert_allclose(tp.tool.offset_mm, [0, 0, 250])
    assert tp.process.variant == "convert"
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


@pytest.mark.parametrize("inside,words", [
    ("  TWAIT 0.5\n", "TWAIT"), ("  SIGNAL 5\n", "SIGNAL"), ("  SPEED 50 MM/S ALWAYS\n", "SPEED"),
    ("  CALL noop\n", "a CALL statement"), ("  ACCURACY 2\n", "an ACCURACY statement"), ("  CP OFF\n", "a CP OFF statement"),
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
    # lines taking in moves the gun sprays and moves it does not: a standalone would spray them all
    body = body.replace("  LMOVE c[10]\n", "  LMOVE c[10]\n  BREAK\n  SIGNAL 1\n")
    src = write(tmp_path, (".PROGRAM x()\n  JMOVE c[0]\n" + body + f"\n.END\n.TRANS\n{trans}\n.END\n").encode())
    with pytest.raises(InputError, match=r"lines 3-40: the gun sprays some of these moves and not others \(line 3\)"):
        convert_program(src, ConvertOptions(TOL, lines=(3, 40), standalone=True))


def test_cli(tmp_path, run_cli):
    src = write(tmp_path, user_contour(rounded_rectangle_points(), crlf=False))
    out = tmp_path / "arcs.as"
    code, text, err = run_cli(["convert", str(src), "--tol", "0.1", "-o", str(out)])
    assert code == 0, err
    m = re.search(r"(\d+) moves -> (\d+) \((\d+) lines \+ (\d+) arcs\).*deviation ([0-9.]+) mm", text)
    assert m and int(m.group(2)) < int(m.group(1)) / 10 and float(m.group(5)) <= 0.1
    assert f"wrote {out}" in text and out.read_bytes().startswith(b".PROGRAM trace()")
    # the file written keeps the original's bytes (a Windows code page comment), not re-encoded
    assert out.read_bytes().split(b"\n")[:5] == src.read_bytes().split(b"\n")[:5]
    assert "\xe9paisseur".encode("latin-1") in out.read_bytes()
    before = src.read_bytes()
    code, _, err = run_cli(["convert", str(src), "--tol", "0.1", "-o", str(tmp_path / "." / src.name)])
    assert code == 2 and "is the same file as the program" in err and src.read_bytes() == before
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


def _goto_loop_program(points, *, jump_in: bool = False) -> bytes:
    """A contour traced by a label and an IF ... GOTO back to it over a pose array, step
    numbers, the gun switched in CALLed routines (``jump_in``: a GOTO from before the loop into it)."""
    lines = [".PROGRAM loop_trace()", "1 TOOL TRANS(0, 0, 250)", "2 SPEED 150 MM/S ALWAYS", "3 JMOVE c[0] + TRANS(, , -40)",
             "4 LMOVE c[0]", "5 CALL gun_on", *(["  IF last < 0 GOTO again"] if jump_in else []), "6 .i = 1",
             "again:", "7 LMOVE c[.i]", "8 .i = .i + 1", "9 IF .i <= last GOTO again", "10 CALL gun_off",
             "11 LDEPART 40", ".END", ".PROGRAM gun_on()", "  BREAK", "  SIGNAL 1", ".END", ".PROGRAM gun_off()",
             "  BREAK", "  SIGNAL -1", ".END", ".REALS", f"last = {len(points) - 1}", ".END", ".TRANS"]
    lines += [f"c[{i}] {700 + x:.4f} {y:.4f} 300 0 180 0" for i, (x, y) in enumerate(points)] + [".END"]
    return ("\n".join(lines) + "\n").encode()


def test_a_goto_loop_is_replaced_whole(tmp_path, kin):
    points = rounded_rectangle_points()
    src = write(tmp_path, _goto_loop_program(points))
    result = convert_program(src, ConvertOptions(TOL), kinematics=kin)
    (report,) = result.paths
    assert (report.first_line, report.last_line) == (8, 11) and report.deviation_mm <= TOL
    assert report.moves_before == len(points) - 1 and report.moves_after <= 12
    lines = split_lines(result.text)
    assert lines[6] == "6 .i = 1" and lines[7].startswith("; coatsim convert: lines 8-11")
    assert not any("GOTO again" in line or line == "again:" for line in lines)
    with pytest.raises(InputError, match=r"user.as:9: label again inside the process path is a GOTO target"):
        convert_program(write(tmp_path, _goto_loop_program(points, jump_in=True)), ConvertOptions(TOL), kinematics=kin)


def test_a_drawing_robot_s_draw_steps_become_arcs(tmp_path, kin):
    """A pen plotter tracing a circle by relative DRAW steps (and TDRAW) in a FOR loop."""
    n, r = 180, 40.0
    steps = [(r * (math.cos(2 * math.pi * (i + 1) / n) - math.cos(2 * math.pi * i / n)),
              r * (math.sin(2 * math.pi * (i + 1) / n) - math.sin(2 * math.pi * i / n))) for i in range(n)]
    text = "\n".join([".PROGRAM plot()", "  TOOL TRANS(0, 0, 250)", "  SPEED 120 MM/S ALWAYS", "  JMOVE start + TRANS(, , -30)",
                      "  LMOVE start", "  BREAK", "  SIGNAL 1", "  FOR .i = 0 TO 179", "    DRAW stx[.i], sty[.i]", "  END",
                      "  TDRAW 0, 20", "  BREAK", "  SIGNAL -1", "  LDEPART 30", ".END", ".TRANS", "start 740 0 300 0 180 0",
                      ".END", ".REALS", *[f"stx[{i}] = {x:.6f}\nsty[{i}] = {y:.6f}" for i, (x, y) in enumerate(steps)],
                      ".END"]) + "\n"
    result = convert_program(write(tmp_path, text.encode()), ConvertOptions(TOL), kinematics=kin)
    (report,) = result.paths
    assert (report.first_line, report.last_line) == (8, 11) and report.moves_before == n + 1
    assert report.moves_after <= 6 and report.n_arcs >= 1 and report.deviation_mm <= TOL


def test_a_program_already_in_arcs_is_kept_as_it_is(tmp_path, kin):
    text = (".PROGRAM ring()\n  TOOL TRANS(0, 0, 250)\n  SPEED 100 MM/S ALWAYS\n  JMOVE a + TRANS(, , -30)\n  LMOVE a\n"
            "  BREAK\n  SIGNAL 1\n  C1MOVE b\n  C2MOVE c\n  C1MOVE d\n  C2MOVE a\n  BREAK\n  SIGNAL -1\n.END\n.TRANS\n"
            "a 700 -40 300 0 180 0\nb 740 0 300 0 180 0\nc 700 40 300 0 180 0\nd 660 0 300 0 180 0\n.END\n")
    result = convert_program(write(tmp_path, text.encode()), ConvertOptions(TOL), kinematics=kin)
    (report,) = result.paths
    assert not result.written and result.data == b"" and report.kept
    assert report.moves_before == report.moves_after == 2 and report.deviation_mm == 0.0
    assert any("no fewer moves (2 against 2" in n and "kept as it was" in n for n in result.notes)


def test_standalone_sprays_every_pass_of_a_loop(tmp_path, kin):
    """Two passes of one FOR loop (the same lines make both): the standalone program sprays each
    in turn; in place the loop cannot be kept."""
    pts = rounded_rectangle_points()
    lines = [".PROGRAM passes()", "  TOOL TRANS(0, 0, 250)", "  SPEED 150 MM/S ALWAYS", "  JMOVE c[0] + TRANS(, , -40)",
             "  FOR .pass = 0 TO 1", "    LMOVE c[0] + TRANS(, , -10 * .pass)", "    BREAK", "    SIGNAL 1",
             f"    FOR .i = 1 TO {len(pts) - 1}", "      LMOVE c[.i] + TRANS(, , -10 * .pass)", "    END", "    BREAK",
             "    SIGNAL -1", "  END", ".END", ".TRANS", *[f"c[{i}] {700 + x:.4f} {y:.4f} 300 0 180 0"
                                                       for i, (x, y) in enumerate(pts)], ".END"]
    src = write(tmp_path, ("\n".join(lines) + "\n").encode())
    with pytest.raises(InputError, match="run more than once"):
        convert_program(src, ConvertOptions(TOL), kinematics=kin)
    result = convert_program(src, ConvertOptions(TOL, standalone=True), kinematics=kin)
    assert [(r.first_line, r.last_line) for r in result.paths] == [(10, 10), (10, 10)]
    assert all(r.deviation_mm <= TOL and r.moves_after <= 12 for r in result.paths)
    out = tmp_path / "arcs.as"
    out.write_bytes(result.data)
    tp = read_toolpath(out)
    runs = [m.end.translation_mm[2] for m in tp.spray_moves]
    assert sorted({round(z) for z in runs}) == [300, 310] and result.text.count("SIGNAL 1 ") == 2


def test_poses_with_an_external_axis_keep_it(tmp_path, kin):
    """A cell with a rail (a 7th axis in every pose): the new poses carry the rail's value; poses
    along the path with different rail values are refused."""
    pts = rounded_rectangle_points()
    def program(rail):
        lines = [".PROGRAM rail()", "  TOOL TRANS(0, 0, 250)", "  SPEED 150 MM/S ALWAYS", "  JMOVE c[0]", "  BREAK",
                 "  SIGNAL 1", f"  FOR .i = 1 TO {len(pts) - 1}", "    LMOVE c[.i]", "  END", "  BREAK", "  SIGNAL -1",
                 ".END", ".TRANS", *[f"c[{i}] {700 + x:.4f} {y:.4f} 300 0 180 0 {rail(i):.3f}" for i, (x, y) in
                                     enumerate(pts)], ".END"]
        return write(tmp_path, ("\n".join(lines) + "\n").encode())
    result = convert_program(program(lambda i: 1250.0), ConvertOptions(TOL), kinematics=kin)
    new = [line for line in split_lines(result.text) if line.startswith("cv1_")]
    assert new and all(line.endswith(" 180.000000 0.000000 1250.000") for line in new)
    with pytest.raises(InputError, match="different external axis values"):
        convert_program(program(lambda i: 1250.0 + i), ConvertOptions(TOL), kinematics=kin)


@pytest.mark.parametrize("wait,seconds", [("TWAIT 0.5", 0.5), ("DELAY 0.25", 0.25), ("TWAIT(1.5)", 1.5)])
def test_standalone_names_the_waits_on_the_path_it_does_not_keep(tmp_path, wait, seconds):
    """A wait between two sprayed moves (a thick spot in the original) is not in the standalone
    program: the note says where, and how long the original stood."""
    pts = rounded_rectangle_points(80, 40, 10, step=2.0)
    trans = "\n".join(f"c[{i}] {700 + x:.4f} {y:.4f} 300 0 180 0" for i, (x, y) in enumerate(pts))
    moves = [f"  LMOVE c[{i}]" for i in range(1, len(pts))]
    moves.insert(30, f"  BREAK\n  {wait}")
    text = (".PROGRAM x()\n  JMOVE c[0]\n  BREAK\n  SIGNAL 1\n  TWAIT 0.2\n" + "\n".join(moves)
            + "\n  BREAK\n  SIGNAL -1\n  TWAIT 3\n.END\n" f".TRANS\n{trans}\n.END\n")
    result = convert_program(write(tmp_path, text.encode()), ConvertOptions(TOL, standalone=True))
    (note,) = [n for n in result.notes if "waits on the path" in n]
    assert f"line 37 ({seconds:g} s)" in note and "line 5 " not in note and note.count("line ") == 1
    plain = text.replace(f"  BREAK\n  {wait}\n", "")
    assert not any("waits" in n for n in convert_program(write(tmp_path, plain.encode(), "b.as"),
                                                         ConvertOptions(TOL, standalone=True)).notes)
