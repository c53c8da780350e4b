"""coatsim program / check-program end to end, through the console entry point."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from coatsim.languages.kawasaki_as.files import read_toolpath

from program_helpers import roundrect

GOLDEN = Path(__file__).parent / "data" / "roundrect_polysegment.as"


def polysegment_json(path: Path) -> Path:
    """The rounded rectangle in the polysegment JSON format of DESIGN.md."""
    segments = []
    for s in roundrect().segments:
        if s.kind == "line":
            segments.append({"kind": "line", "start": list(s.start), "end": list(s.end)})
        else:
            segments.append({"kind": "arc", "start": list(s.start), "end": list(s.end), "center": list(s.center),
                             "radius": s.radius, "sweep": s.sweep})
    doc = {"format": "coatsim.polysegment/1", "units": "mm", "closed": True, "tolerance_mm": 0.1,
           "segments": segments, "corners": [],
           "stats": {"n_segments": 8, "n_arcs": 4, "n_lines": 4, "max_deviation_mm": 0.0,
                     "max_tangent_break_deg": 0.0, "input_points": 0, "seconds": 0.0}}
    path.write_text(json.dumps(doc))
    return path


def test_check_program_reports_the_golden_program(run_cli):
    code, out, err = run_cli(["check-program", str(GOLDEN)])
    assert code == 0, err
    assert "program roundrect: 26 steps, 15 poses; moves: 1 joint, 8 linear, 4 arc" in out
    length = 2 * 130 + 2 * 60 + 2 * math.pi * 10  # one lap: the lead-in and lead-out run with the gun closed
    assert f"sprayed {length:.3f} mm" in out and "no problems found" in out


def test_check_program_problems_and_errors(tmp_path, run_cli):
    odd = tmp_path / "odd.as"
    odd.write_text(".PROGRAM a_very_long_program_name()\n  SPEED 50\n  JMOVE p1\n  SIGNAL 1\n  LMOVE p2\n.END\n"
                   ".TRANS\np1 0 0 0 0 180 0\np2 10 0 0 0 180 0\nunused 0 0 0 0 0 0\n.END\n")
    code, out, _ = run_cli(["check-program", str(odd)])
    assert code == 0
    assert "odd.as:10: pose 'unused' is defined but never used" in out
    assert "longer than 15 characters" in out and "still on at the end" in out and "SPEED in %" in out
    broken = tmp_path / "broken.as"
    broken.write_text(".PROGRAM x()\n  JMOVE p1\n  LMOVE p9\n.END\n.TRANS\np1 0 0 0 0 180 0\n.END\n")
    code, out, err = run_cli(["check-program", str(broken)])  # a pose no file gives: read, the move skipped
    assert code == 0 and f"warning: {broken}:3: p9 (pose) is read but no file gives it a value" in out
    assert f"warning: {broken}:3: LMOVE skipped: pose p9 has no value" in out
    code, out, err = run_cli(["check-program", str(broken), "--set", "p9=TRANS(10, 0, 0, 0, 180, 0)"])
    assert code == 0 and "moves: 1 joint, 1 linear" in out and "skipped" not in out
    broken.write_text(".PROGRAM x()\n  JMOVE p1,\n.END\n")
    code, _, err = run_cli(["check-program", str(broken)])
    assert code == 2 and f"{broken}:2:12: expected a clamp number" in err
    code, _, err = run_cli(["check-program", str(tmp_path / "none.as")])
    assert code == 2 and f"{tmp_path / 'none.as'}: no such file" in err


def test_program_from_polysegment_json(tmp_path, run_cli):
    src = polysegment_json(tmp_path / "rr.json")
    out_file = tmp_path / "rr.as"
    code, out, err = run_cli(["program", str(src), "-o", str(out_file), "--speed", "300", "--standoff", "80",
                              "--frame", "600,100,250,0,0,0", "--lead-in", "20", "--name", "rr"])
    assert code == 0, err
    assert "program rr: polysegment, 4 lines + 4 arcs" in out and f"wrote {out_file}" in out
    tp = read_toolpath(out_file)
    assert tp.process.tolerance_mm == 0.1 and tp.process.lead_in_mm == 20.0
    assert tp.spray_moves[0].start.translation_mm[2] == pytest.approx(330.0)
    assert not tp.process.contours[0].leads_sprayed
    assert all(m.settings.speed_mm_s == 300.0 for m in tp.moves)
    code, text, err = run_cli(["program", str(src), "--variant", "polyline-stop", "--tol", "0.5"])
    assert code == 0 and text.startswith(".PROGRAM rr()") and "CP OFF" in text and "program rr" in err


def test_program_refuses_a_3d_polysegment_and_says_what_to_program(tmp_path, run_cli):
    """A polysegment/2 (a fitted space curve) has no spray axis: one line pointing at the surface paths."""
    import numpy as np

    t = np.linspace(0.0, 4 * np.pi, 400)
    curve = tmp_path / "helix.csv"
    np.savetxt(curve, np.c_[40 * np.cos(t), 40 * np.sin(t), 5 * t], delimiter=",")
    fitted = tmp_path / "helix.json"
    code, _, err = run_cli(["segment", str(curve), "--tol", "0.5", "-o", str(fitted)])
    assert code == 0 and '"coatsim.polysegment/2"' in fitted.read_text(), err
    code, _, err = run_cli(["program", str(fitted), "-o", str(tmp_path / "h.as")])
    assert code == 2 and err.count("\n") == 1 and "no spray axis" in err and "coatsim.surfacepaths/1" in err
    assert not (tmp_path / "h.as").exists()


@pytest.mark.parametrize("args,words", [
    (["--variant", "zigzag"], "--variant 'zigzag'"),
    (["--frame", "1,2,3"], "--frame"),
    (["--speed", "0"], "--speed"),
    (["--standoff", "-5"], "standoff_mm"),
])
def test_program_rejects_bad_options(tmp_path, run_cli, args, words):
    src = polysegment_json(tmp_path / "rr.json")
    code, _, err = run_cli(["program", str(src), *args])
    assert code == 2 and words in err and err.count("\n") == 1


def test_check_program_lists_signals_and_sprayed_stretches(run_cli):
    code, out, err = run_cli(["check-program", str(GOLDEN)])
    assert code == 0, err
    # a closed contour: the gun opens on the fly at the seam and closes after exactly one lap
    assert f"signal: {GOLDEN}:30: SIGNAL 1 (gun on)" in out and f"signal: {GOLDEN}:43: SIGNAL -1 (gun off)" in out
    length = 2 * 130 + 2 * 60 + 2 * math.pi * 10
    assert f"sprayed: lines 29-41 of {GOLDEN}, 8 moves, {length:.3f} mm" in out


def test_check_program_accepts_a_bom_and_several_files(tmp_path, run_cli):
    prog, data = tmp_path / "prog.as", tmp_path / "poses.as"
    prog.write_bytes(b"\xef\xbb\xbf.PROGRAM main()\r\n  JMOVE p1\r\n  SIGNAL 2\r\n  LMOVE p2\r\n  BREAK\r\n  SIGNAL -2\r\n.END\r\n")
    data.write_bytes(b".TRANS\r\np1 600 0 300 0 180 0\r\np2 700 0 300 0 180 0\r\n.END\r\n")
    code, out, err = run_cli(["check-program", str(prog), str(data), "--gun", "2"])
    assert code == 0, err
    assert "program main" in out and "(sprayed 100.000 mm)" in out and "SIGNAL 2 (gun on)" in out


def test_check_program_rejects_what_execute_rejects(tmp_path, run_cli):
    empty = tmp_path / "empty.as"
    empty.write_text(".PROGRAM nothing()\n  SPEED 100 MM/S\n.END\n")
    code, _, err = run_cli(["check-program", str(empty)])
    assert code == 3 and "has no motion" in err and err.count("\n") == 1
    still = tmp_path / "still.as"
    still.write_text(".PROGRAM still()\n  LMOVE HERE\n  LMOVE HERE\n.END\n")
    code, _, err = run_cli(["check-program", str(still)])
    assert code == 3 and "moves the tool nowhere" in err


@pytest.mark.parametrize("offset", [0.0, 1e-12, 1e-9, 1e-8, 1e-7, 1e-5])
def test_nearly_collinear_arcs_check_and_execute_agree(tmp_path, run_cli, offset):
    from coatsim.core.errors import CoatsimError
    from coatsim.robot.sampling import plan_pieces

    prog = tmp_path / "arc.as"
    prog.write_text(".PROGRAM arc()\n  JMOVE a\n  SIGNAL 1\n  C1MOVE v\n  C2MOVE b\n.END\n.TRANS\na 600 0 300 0 180 0\n"
                    f"v 650 {offset!r} 300 0 180 0\nb 700 0 300 0 180 0\n.END\n")
    code, _, err = run_cli(["check-program", str(prog)])
    try:
        plan_pieces(read_toolpath(prog))
        executes = True
    except CoatsimError:
        executes = False
    assert (code == 0) == executes, err


def test_check_program_options(tmp_path, run_cli):
    prog = tmp_path / "two.as"
    prog.write_text(".PROGRAM first()\n  JMOVE a\n.END\n.PROGRAM second()\n  JMOVE a\n  SWAIT 1001\n  SIGNAL 1\n"
                    "  LMOVE b\n  IF SIG(1002) THEN\n    LMOVE a\n  END\n.END\n"
                    ".TRANS\na 600 0 300 0 180 0\nb 700 0 300 0 180 0\n.END\n")
    code, out, _ = run_cli(["check-program", str(prog), "--program", "second", "--inputs", "1001,1002"])
    assert code == 0 and "program second" in out and "moves: 1 joint, 2 linear" in out and "warning" not in out
    code, out, _ = run_cli(["check-program", str(prog), "--program", "second"])
    assert code == 0 and "warning:" in out and "moves: 1 joint, 1 linear" in out
    code, _, err = run_cli(["check-program", str(prog), "--inputs", "10x1"])
    assert code == 2 and "--inputs" in err
    code, _, err = run_cli(["check-program", str(prog), "--program", "third"])
    assert code == 2 and "no program named 'third'" in err


def test_program_segments_a_curve_for_its_speed(tmp_path, run_cli):
    """--speed and the tool acceleration (the cell's, or --tool-accel) reach the fitter: the NACA
    leading edge (radius ~3 mm) is listed as speed-limited at 300 mm/s, and with a laxer tool
    limit it is not; the trailing edge is a true corner either way."""
    out_file = tmp_path / "naca.as"
    code, _, err = run_cli(["program", "builtin:naca", "--tol", "0.1", "--speed", "300", "-o", str(out_file)])
    assert code == 0, err
    (contour,) = read_toolpath(out_file).process.contours
    limits = contour.speed_limits
    assert len(limits) == 2 and limits[-1].v_max_mm_s == 0.0 and 0.0 < limits[0].v_max_mm_s < 300.0
    code, _, err = run_cli(["program", "builtin:naca", "--tol", "0.1", "--speed", "300", "--tool-accel", "50",
                            "-o", str(out_file)])
    assert code == 0, err
    assert len(read_toolpath(out_file).process.contours[0].speed_limits) == 1
    code, _, err = run_cli(["program", "builtin:naca", "--tol", "0.1", "--tool-accel", "0"])
    assert code == 2 and "--tool-accel" in err
    # a polysegment JSON gets its stretches listed again for the program's speed
    src = polysegment_json(tmp_path / "rr.json")
    code, _, err = run_cli(["program", str(src), "--speed", "300", "-o", str(out_file)])
    assert code == 0, err
    assert len(read_toolpath(out_file).process.contours[0].speed_limits) == 4  # the 10 mm corner arcs
    code, _, err = run_cli(["program", str(src), "--speed", "200", "-o", str(out_file)])
    assert read_toolpath(out_file).process.contours[0].speed_limits == ()
