"""`coatsim segment --speed/--tool-accel/--min-segment` and the polysegment JSON's
``speed_limited`` (writer, reader, validation)."""

from __future__ import annotations

import copy
import json
import math

import pytest

from coatsim.core.errors import InputError
from coatsim.geometry import load_curve, read_polysegment_json, segment_curve, write_polysegment_json
from coatsim.geometry.polysegment_json import polysegment_from_document


def one_line_error(code, err, fragment):
    assert code == 2, err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("coatsim: error:") and fragment in lines[0], err


def test_speed_limited_stretches_are_written_and_read_back(tmp_path, run_cli):
    """builtin:ellipse (tightest radius 25 mm) at 400 mm/s needs 6.4 m/s² at its tips: with
    the cell's 5 m/s² the tips are speed-limited."""
    from coatsim.robot.cell import load_cell

    out = tmp_path / "e.json"
    code, stdout, err = run_cli(["segment", "builtin:ellipse", "--tol", "0.05", "--speed", "400", "-o", str(out)])
    assert code == 0, err
    doc = json.loads(out.read_text())
    assert doc["stats"]["speed_mm_s"] == 400.0
    assert doc["stats"]["tool_accel_mm_s2"] == load_cell().tool_accel_mm_s2 == 5000.0
    limited = doc["speed_limited"]
    assert len(limited) >= 2 and all(0 <= a < b and v < 400 for a, b, v in limited)
    assert all(v >= math.sqrt(5000.0 * 25.0 * 0.8) for _, _, v in limited)  # no arc tighter than 0.8 x 25 mm
    assert "speed-limited stretch" in stdout
    poly = read_polysegment_json(out)
    assert [list(x) for x in poly.speed_limited] == limited


def test_a_larger_tool_acceleration_removes_the_limits(tmp_path, run_cli):
    out = tmp_path / "e.json"
    code, stdout, err = run_cli(["segment", "builtin:ellipse", "--tol", "0.05", "--speed", "400", "--tool-accel", "10",
                                 "-o", str(out)])
    assert code == 0, err
    doc = json.loads(out.read_text())
    assert doc["stats"]["tool_accel_mm_s2"] == 10000.0 and doc["speed_limited"] == []
    assert all(s["radius"] >= 400.0**2 / 10000.0 for s in doc["segments"] if s["kind"] == "arc")
    assert "no speed-limited stretch" in stdout


def test_without_speed_nothing_is_speed_limited(tmp_path, run_cli):
    out = tmp_path / "e.json"
    code, _, err = run_cli(["segment", "builtin:d-shape", "--tol", "0.1", "-o", str(out)])
    assert code == 0, err
    doc = json.loads(out.read_text())
    assert doc["speed_limited"] == [] and doc["stats"]["speed_mm_s"] is None


@pytest.mark.parametrize("args,fragment", [
    (["--tool-accel", "5"], "--tool-accel: needs --speed"),
    (["--speed", "-1"], "--speed"),
    (["--speed", "nan"], "--speed"),
    (["--speed", "300", "--tool-accel", "0"], "--tool-accel"),
    (["--speed", "300", "--tool-accel", "inf"], "--tool-accel"),
    (["--min-segment", "0"], "--min-segment"),
])
def test_bad_speed_flags_are_one_line_errors(run_cli, args, fragment):
    code, _, err = run_cli(["segment", "builtin:sine:points=300", "--tol", "0.1", *args])
    one_line_error(code, err, fragment)


def test_a_min_segment_that_cannot_be_kept_names_the_flag(run_cli):
    code, _, err = run_cli(["segment", "builtin:sine", "--tol", "0.05", "--min-segment", "10"])
    one_line_error(code, err, "--min-segment 10 mm")


# ---------------------------------------------------------------- the reader


@pytest.fixture(scope="module")
def limited_doc(tmp_path_factory):
    seg = segment_curve(load_curve("builtin:ellipse:points=1500"), 0.1, speed_mm_s=400.0, tool_accel_mm_s2=5000.0)
    path = tmp_path_factory.mktemp("doc") / "e.json"
    write_polysegment_json(path, seg)
    return json.loads(path.read_text())


@pytest.mark.parametrize("value,fragment", [
    ({}, "speed_limited: expected a list"),
    ([[0.0, 1.0]], "speed_limited[0]"),
    ([[5.0, 1.0, 100.0]], "speed_limited[0]"),
    ([[0.0, 1e9, 100.0]], "the path length"),
    ([[0.0, 1.0, -1.0]], "v_max >= 0"),
    ([[0.0, 1.0, "fast"]], "speed_limited[0]"),
    ([[0.0, 1.0, float("nan")]], "speed_limited[0]"),
])
def test_bad_speed_limited_entries_are_rejected(limited_doc, value, fragment):
    doc = copy.deepcopy(limited_doc)
    doc["speed_limited"] = value
    with pytest.raises(InputError, match=fragment.replace("[", r"\[").replace("]", r"\]")):
        polysegment_from_document(doc, "e.json")


def test_a_file_without_speed_limited_reads(limited_doc):
    doc = copy.deepcopy(limited_doc)
    del doc["speed_limited"]
    assert polysegment_from_document(doc, "old.json").speed_limited == ()
