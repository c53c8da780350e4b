"""coatsim program / check-program end to end, through the console entry point."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from coatsim.program import read_toolpath

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
    code, out, err = run_cli(["check-program", str(broken)])
    assert code == 2 and err.strip() == f"coatsim: error: {broken}:3: pose 'p9' is not defined; add it to .TRANS or assign it with POINT"
    broken.write_text(".PROGRAM x()\n  JMOVE p1,\n.END\n")
    code, _, err = run_cli(["check-program", str(broken)])
    assert code == 2 and f"{broken}:2:12: expected a clamp number" in err
    code, _, err = run_cli(["check-program", str(tmp_path / "none.as")])
    assert code == 2 and "cannot read program" in err


def test_program_from_polysegment_json(tmp_path, run_cli):
    src = polysegment_json(tmp_path / "rr.json")
    out_file = tmp_path / "rr.as"
    code, out, err = run_cli(["program", str(src), "-o", str(out_file), "--speed", "300", "--standoff", "80",
                              "--frame", "600,100,250,0,0,0", "--lead-in", "20", "--name", "rr"])
    assert code == 0, err
    assert "program rr: polysegment, 4 lines + 4 arcs" in out and f"wrote {out_file}" in out
    tp = read_toolpath(out_file)
    assert tp.metadata["tolerance_mm"] == "0.1" and tp.metadata["lead_in_mm"] == "20"
    assert tp.spray_moves[0].start.position[2] == pytest.approx(330.0)
    assert tp.metadata["sprayed"] == "curve"
    assert all(m.settings.speed_mm_s == 300.0 for m in tp.moves)
    code, text, err = run_cli(["program", str(src), "--variant", "polyline-stop", "--tol", "0.5"])
    assert code == 0 and text.startswith(".PROGRAM rr()") and "CP OFF" in text and "program rr" in err


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
