"""Polysegment JSON (write/read, the DESIGN.md format, malformed files) and the `coatsim
segment` command end to end (outputs, exit codes, one-line errors)."""

from __future__ import annotations

import copy
import json
import math
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from coatsim.core.errors import InputError
from coatsim.geometry import Polysegment, Segmentation, chain, make_curve, read_polysegment_json, write_polysegment_json
from coatsim.geometry.theta import theta_of_polyline

from geometry_helpers import bench_spec, segmented

# The example of the design notes' "Polysegment JSON" section, verbatim (it predates the removal
# of stats.seconds and the addition of speed_limited and the curvature stats; readers accept it).
DESIGN_EXAMPLE = Path(__file__).resolve().parents[1] / "data" / "design_polysegment_example.json"
TOP_KEYS = {"format", "units", "closed", "tolerance_mm", "segments", "corners", "speed_limited", "stats"}
STATS_KEYS = {"n_segments", "n_arcs", "n_lines", "max_deviation_mm", "max_tangent_break_deg", "min_radius_mm",
              "input_min_radius_mm", "min_segment_mm", "max_curvature_jump_per_mm", "limits_kept", "speed_mm_s",
              "tool_accel_mm_s2", "input_points"}
LINE_KEYS = {"kind", "start", "end"}
ARC_KEYS = {"kind", "start", "end", "center", "radius", "sweep"}


def roundtrip(tmp_path: Path, seg, name: str = "poly.json") -> tuple[Polysegment, dict]:
    path = tmp_path / name
    write_polysegment_json(path, seg)
    return read_polysegment_json(path), json.loads(path.read_text(encoding="utf-8"))


# ---------------------------------------------------------------- round trip and format

ROUNDTRIP_SPECS = [
    pytest.param("builtin:rounded-rectangle", 0.5, "optimal", id="rounded-rectangle"),
    pytest.param("builtin:polygon:sides=6", 0.5, "optimal", id="polygon"),
    pytest.param("builtin:naca:points=2000", 0.1, "optimal", id="naca-corner"),
    pytest.param("builtin:paper-spiral:points=1500", 0.5, "optimal", id="spiral"),
    pytest.param("builtin:sine:points=1000", 0.5, "paper", id="sine-paper"),
    pytest.param(bench_spec("ellipse"), 0.5, "optimal", id="bench-ellipse"),
    # Regression: the d-shape once had a 3e-14 mm gap at a corner, which the reader rejects.
    pytest.param("builtin:d-shape", 0.5, "optimal", id="d-shape"),
    pytest.param("builtin:ellipse:points=1000", 0.5, "paper", id="closed-paper"),
]


@pytest.mark.parametrize("spec,tol,method", ROUNDTRIP_SPECS)
def test_write_read_roundtrip_is_exact(tmp_path, spec, tol, method):
    seg = segmented(spec, tol, method)
    back, doc = roundtrip(tmp_path, seg)
    assert back == seg.polysegment  # frozen dataclasses: every float compared exactly
    assert back.segments == seg.polysegment.segments
    assert [type(s) for s in back.segments] == [type(s) for s in seg.polysegment.segments]
    assert back.corners == seg.polysegment.corners and back.closed == seg.polysegment.closed


@pytest.mark.parametrize("spec,tol,method", ROUNDTRIP_SPECS[:6])
def test_document_matches_the_design_format(tmp_path, spec, tol, method):
    seg = segmented(spec, tol, method)
    path = tmp_path / "doc.json"
    write_polysegment_json(path, seg)
    text = path.read_text(encoding="utf-8")
    assert text.endswith("\n") and "NaN" not in text and "Infinity" not in text
    doc = json.loads(text)
    assert set(doc) == TOP_KEYS
    assert doc["format"] == "coatsim.polysegment/1" and doc["units"] == "mm"
    assert doc["closed"] is seg.curve.closed and doc["tolerance_mm"] == tol
    assert isinstance(doc["corners"], list) and all(isinstance(k, int) for k in doc["corners"])
    poly = seg.polysegment
    assert len(doc["segments"]) == poly.n_segments
    for item, s in zip(doc["segments"], poly.segments):
        assert set(item) == (ARC_KEYS if s.kind == "arc" else LINE_KEYS)
        assert item["kind"] == s.kind
        assert item["start"] == list(s.start) and item["end"] == list(s.end)
        for p in ("start", "end") + (("center",) if s.kind == "arc" else ()):
            assert len(item[p]) == 2 and all(isinstance(v, float) for v in item[p])
        if s.kind == "arc":
            assert item["radius"] == s.radius > 0 and item["sweep"] == s.sweep != 0
    stats = doc["stats"]
    assert set(stats) == STATS_KEYS
    assert stats["n_segments"] == poly.n_segments == stats["n_arcs"] + stats["n_lines"]
    assert stats["n_arcs"] == sum(s["kind"] == "arc" for s in doc["segments"])
    assert stats["input_points"] == len(seg.curve.points)
    assert stats["max_deviation_mm"] == seg.max_deviation_mm <= tol
    assert stats["max_tangent_break_deg"] == pytest.approx(math.degrees(poly.max_tangent_break()))
    assert "seconds" not in stats  # the file is the same for the same input, whatever the wall time
    for key in ("n_segments", "n_arcs", "n_lines", "input_points"):
        assert type(stats[key]) is int


def test_counter_clockwise_sweeps_are_positive(tmp_path):
    _, doc = roundtrip(tmp_path, segmented("builtin:rounded-rectangle", 0.5))
    assert all(s["sweep"] > 0 for s in doc["segments"] if s["kind"] == "arc")
    cw = segmented("builtin:raster", 0.5)  # turn-arounds alternate
    _, doc = roundtrip(tmp_path, cw, "raster.json")
    assert [s["sweep"] > 0 for s in doc["segments"] if s["kind"] == "arc"] == [True, False, True, False, True]


def _segmentation_of(poly: Polysegment, tol: float = 0.1) -> Segmentation:
    pts = poly.sample(max(poly.length / 200, 1e-3))[0]
    c = make_curve(pts, "chain")
    return Segmentation(c, poly, "optimal", tol, 0.0, 0.0, theta_of_polyline(c.points))


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(
    start=st.tuples(st.floats(-1e4, 1e4), st.floats(-1e4, 1e4)),
    heading=st.floats(-math.pi, math.pi),
    pieces=st.lists(st.tuples(st.sampled_from([0.0, 1.0, -1.0]), st.floats(1e-3, 2.0), st.floats(0.01, 500.0)),
                    min_size=1, max_size=8),
)
def test_roundtrip_of_random_chains(tmp_path, start, heading, pieces):
    kappas = [kind * k for kind, k, _ in pieces]
    lengths = [min(l, 6.0 / abs(k)) if k else l for k, (_, _, l) in zip(kappas, pieces)]
    poly = Polysegment(chain(start, heading, kappas, lengths))
    back, _ = roundtrip(tmp_path, _segmentation_of(poly), "random.json")
    assert back == poly


def test_the_design_example_is_a_valid_file(tmp_path):
    """The design's example (which predates speed_limited and the curvature stats, and still
    carries stats.seconds: such a file still reads) is a valid file."""
    block = DESIGN_EXAMPLE.read_text(encoding="utf-8")
    doc = json.loads(block)
    assert set(doc) <= TOP_KEYS and set(doc["stats"]) <= STATS_KEYS | {"seconds"}
    path = tmp_path / "design.json"
    path.write_text(block)
    poly = read_polysegment_json(path)
    assert [s.kind for s in poly.segments] == ["line", "arc"]
    assert poly.segments[1].sweep == pytest.approx(math.pi / 2, abs=1e-7)


# ---------------------------------------------------------------- malformed files

VALID = {
    "format": "coatsim.polysegment/1", "units": "mm", "closed": False, "tolerance_mm": 0.1,
    "segments": [
        {"kind": "line", "start": [0.0, 0.0], "end": [50.0, 0.0]},
        {"kind": "arc", "start": [50.0, 0.0], "end": [90.0, 40.0], "center": [50.0, 40.0], "radius": 40.0,
         "sweep": math.pi / 2},
        {"kind": "line", "start": [90.0, 40.0], "end": [90.0, 100.0]},
    ],
    "corners": [],
    "stats": {"n_segments": 3, "n_arcs": 1, "n_lines": 2, "max_deviation_mm": 0.0, "max_tangent_break_deg": 0.0,
              "input_points": 3},
}


def mutate(fn):
    """A deep copy of VALID changed in place by ``fn`` (or replaced by what ``fn`` returns
    wrapped as ("replace", value))."""
    doc = copy.deepcopy(VALID)
    out = fn(doc)
    return out[1] if isinstance(out, tuple) and out[:1] == ("replace",) else doc


MALFORMED = {
    "bad format tag": (lambda d: d.update(format="coatsim.polysegment/2"), "format"),
    "no format": (lambda d: d.pop("format"), "format"),
    "not an object": (lambda d: ("replace", [d]), "format"),
    "missing segments": (lambda d: d.pop("segments"), "segments"),
    "empty segments": (lambda d: d.update(segments=[]), "segments"),
    "segments not a list": (lambda d: d.update(segments="line"), "segments"),
    "segment not an object": (lambda d: d["segments"].__setitem__(0, 7), "segments[0].kind"),
    "unknown kind": (lambda d: d["segments"][2].update(kind="spline"), "segments[2].kind"),
    "broken chain": (lambda d: d["segments"][2].update(start=[90.0, 40.000001]), "segments[2].start"),
    "tiny chain gap": (lambda d: d["segments"][1].update(start=[50.0 + 1e-12, 0.0]), "segments[1].start"),
    "arc end off its circle": (lambda d: (d["segments"][1].update(end=[90.01, 40.0]),
                                          d["segments"][2].update(start=[90.01, 40.0])), "segments[1].end"),
    "arc start off its circle": (lambda d: (d["segments"][0].update(end=[50.0, 0.5]),
                                            d["segments"][1].update(start=[50.0, 0.5])), "segments[1].start"),
    "radius not a number": (lambda d: d["segments"][1].update(radius="40"), "segments[1].radius"),
    "radius boolean": (lambda d: d["segments"][1].update(radius=True), "segments[1].radius"),
    "radius missing": (lambda d: d["segments"][1].pop("radius"), "segments[1].radius"),
    "negative radius": (lambda d: d["segments"][1].update(radius=-40.0), "segments[1]"),
    "zero sweep": (lambda d: d["segments"][1].update(sweep=0.0), "segments[1]"),
    "sweep not a number": (lambda d: d["segments"][1].update(sweep=None), "segments[1].sweep"),
    "centre missing": (lambda d: d["segments"][1].pop("center"), "segments[1].center"),
    "point with text": (lambda d: d["segments"][0].update(start=["0", 0.0]), "segments[0].start"),
    "point with three values": (lambda d: d["segments"][0].update(start=[0.0, 0.0, 0.0]), "segments[0].start"),
    "point not a list": (lambda d: d["segments"][0].update(end="50,0"), "segments[0].end"),
    "nan coordinate": (lambda d: d["segments"][2].update(end=[float("nan"), 100.0]), "segments[2].end"),
    "closed not a boolean": (lambda d: d.update(closed="yes"), "closed"),
    "corner out of range": (lambda d: d.update(corners=[3]), "corners"),
    "corner not an integer": (lambda d: d.update(corners=["1"]), "corners"),
    "corners not a list": (lambda d: d.update(corners=1), "corners"),
}


@pytest.mark.parametrize("fn,field", MALFORMED.values(), ids=list(MALFORMED))
def test_malformed_files_name_the_field(tmp_path, fn, field):
    path = tmp_path / "bad.json"
    path.write_text(json.dumps(mutate(fn)))
    with pytest.raises(InputError) as info:
        read_polysegment_json(path)
    msg = str(info.value)
    assert str(path) in msg and field in msg, msg
    assert "\n" not in msg


def test_the_valid_base_document_reads():
    import tempfile

    with tempfile.TemporaryDirectory() as d:
        path = Path(d) / "ok.json"
        path.write_text(json.dumps(VALID))
        poly = read_polysegment_json(path)
    assert [s.kind for s in poly.segments] == ["line", "arc", "line"]


@pytest.mark.parametrize("text,where", [("{", ":1:"), ("", ":1:"),
                                        ('{"format": "coatsim.polysegment/1",\n "segments": [,]}', ":2:")],
                         ids=["truncated", "empty", "syntax on line 2"])
def test_invalid_json_names_the_line(tmp_path, text, where):
    path = tmp_path / "broken.json"
    path.write_text(text)
    with pytest.raises(InputError, match=re.escape(f"{path}{where}")):
        read_polysegment_json(path)


def test_unreadable_json_paths(tmp_path):
    with pytest.raises(InputError, match=re.escape(str(tmp_path / "none.json"))):
        read_polysegment_json(tmp_path / "none.json")
    with pytest.raises(InputError, match=re.escape(str(tmp_path))):
        read_polysegment_json(tmp_path)
    binary = tmp_path / "bin.json"
    binary.write_bytes(b"\xff\xfe\x00garbage")
    with pytest.raises(InputError, match=re.escape(str(binary))):
        read_polysegment_json(binary)


@pytest.mark.parametrize("sweep", [1.0, -math.pi / 2, 3 * math.pi / 2, -0.5])
def test_arc_sweep_must_match_its_end_points(tmp_path, sweep):
    """Regression: a quarter arc written with a sweep that does not lead from its start to its
    end (1.0, -pi/2, ...) was once accepted."""
    path = tmp_path / "sweep.json"
    path.write_text(json.dumps(mutate(lambda d: d["segments"][1].update(sweep=sweep))))
    with pytest.raises(InputError, match=r"segments\[1\]"):
        read_polysegment_json(path)


# ---------------------------------------------------------------- the CLI


def run_module(args: list[str], cwd: Path, timeout: float = 300) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "coatsim.cli", *args], cwd=cwd, capture_output=True, text=True,
                          timeout=timeout, env={**os.environ, "PYTHONWARNINGS": "ignore"})


def assert_one_line_error(code, err, fragment=""):
    assert code == 2, err
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert lines[0].startswith("coatsim: error:"), err
    assert "Traceback" not in err
    assert fragment in lines[0], err


def test_cli_segment_writes_json_and_png(tmp_path):
    proc = run_module(["segment", "builtin:rounded-rectangle", "--tol", "0.1", "-o", "rr.json", "--plot", "rr.png"],
                      tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert "segments 8 (4 arcs, 4 lines)" in proc.stdout
    assert "wrote rr.json" in proc.stdout and "wrote rr.png" in proc.stdout
    poly = read_polysegment_json(tmp_path / "rr.json")
    assert poly.n_segments == 8 and poly.closed
    doc = json.loads((tmp_path / "rr.json").read_text())
    assert doc["tolerance_mm"] == 0.1 and doc["stats"]["n_arcs"] == 4
    png = (tmp_path / "rr.png").read_bytes()
    assert png.startswith(b"\x89PNG\r\n\x1a\n") and len(png) > 10_000
    assert sorted(p.name for p in tmp_path.iterdir()) == ["rr.json", "rr.png"]  # no temporary leftovers


def test_console_script(tmp_path):
    script = shutil.which("coatsim", path=str(Path(sys.executable).parent)) or shutil.which("coatsim")
    assert script is not None, "the coatsim console script is not installed (pip install -e .)"
    proc = subprocess.run([script, "segment", "builtin:polygon:sides=4", "--tol", "0.5", "-o", "sq.json"],
                          cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    poly = read_polysegment_json(tmp_path / "sq.json")
    assert poly.n_lines == 4 and poly.corners == (0, 1, 2, 3)
    proc = subprocess.run([script, "segment", "missing.csv"], cwd=tmp_path, capture_output=True, text=True,
                          timeout=300)
    assert_one_line_error(proc.returncode, proc.stderr, "missing.csv")


def test_cli_paper_method(tmp_path, run_cli):
    code, out, err = run_cli(["segment", "builtin:sine:points=800", "--method", "paper", "--tol", "0.5",
                                    "-o", str(tmp_path / "p.json")])
    assert code == 0, err
    assert "method paper" in out and "θ tolerance" in out
    assert read_polysegment_json(tmp_path / "p.json").n_segments >= 2


@pytest.mark.parametrize("args,fragment", [
    (["segment", "missing.csv"], "missing.csv"),
    (["segment", "empty.csv"], "empty.csv"),
    (["segment", "builtin:nope"], "builtin:nope"),
    (["segment", "builtin:ellipse", "--tol", "-1"], "--tol"),
], ids=["missing file", "empty file", "unknown builtin", "negative tol"])
def test_cli_bad_inputs_subprocess(tmp_path, args, fragment):
    (tmp_path / "empty.csv").write_text("")
    proc = run_module(args, tmp_path)
    assert_one_line_error(proc.returncode, proc.stderr, fragment)
    assert proc.stdout == ""


def _bad_inprocess_cases(tmp: Path):
    (tmp / "text.csv").write_text("0,0\n1,1\n2,two\n")
    (tmp / "nan.csv").write_text("0,0\nnan,1\n2,2\n")
    (tmp / "one.csv").write_text("1,1\n")
    (tmp / "afile").write_text("x")
    return {
        "tol zero": (["builtin:ellipse", "--tol", "0"], "--tol"),
        "tol nan": (["builtin:ellipse", "--tol", "nan"], "--tol"),
        "unknown method": (["builtin:ellipse", "--method", "fast"], "--method"),
        "bad closed": (["builtin:ellipse", "--closed", "maybe"], "--closed"),
        "corner 0": (["builtin:ellipse", "--corner-deg", "0"], "--corner-deg"),
        "corner 180": (["builtin:ellipse", "--corner-deg", "180"], "--corner-deg"),
        "theta tol 0": (["builtin:ellipse", "--method", "paper", "--theta-tol", "0"], "--theta-tol"),
        "folder input": ([str(tmp)], str(tmp)),
        "text in column": ([str(tmp / "text.csv")], f"{tmp / 'text.csv'}:3"),
        "nan in file": ([str(tmp / "nan.csv")], f"{tmp / 'nan.csv'}:2"),
        "one point": ([str(tmp / "one.csv")], str(tmp / "one.csv")),
        "bad builtin parameter": (["builtin:ellipse:foo=1"], "builtin:ellipse"),
        "output under a file": (["builtin:polygon", "-o", str(tmp / "afile" / "out.json")], str(tmp / "afile")),
    }


BAD_INPROCESS = ["tol zero", "tol nan", "unknown method", "bad closed", "corner 0", "corner 180", "theta tol 0",
                 "folder input", "text in column", "nan in file", "one point", "bad builtin parameter",
                 "output under a file"]


@pytest.mark.parametrize("case", BAD_INPROCESS)
def test_cli_bad_inputs(tmp_path, run_cli, case):
    args, fragment = _bad_inprocess_cases(tmp_path)[case]
    code, out, err = run_cli(["segment", *args])
    assert_one_line_error(code, err, fragment)
    assert not list(tmp_path.glob("**/*.json")) and not list(tmp_path.glob("**/.*.tmp"))


def test_cli_crashing_builtin_parameter(tmp_path):
    """Regression: int('abc') once escaped as a ValueError: traceback, exit 1."""
    proc = run_module(["segment", "builtin:polygon:sides=abc"], tmp_path)
    assert_one_line_error(proc.returncode, proc.stderr, "builtin:polygon")


def test_cli_sparse_kinked_csv(tmp_path):
    """Regression: band_fit once raised AssertionError on this input: traceback, exit 1."""
    (tmp_path / "kink.csv").write_text("0,0\n50,0\n60,5\n100,5\n")
    proc = run_module(["segment", "kink.csv", "--tol", "0.5"], tmp_path)
    assert proc.returncode == 0 or (proc.returncode == 2 and "Traceback" not in proc.stderr), proc.stderr


def test_cli_output_onto_a_folder(tmp_path):
    """Regression: os.replace onto a folder once escaped as IsADirectoryError: traceback, exit 1."""
    (tmp_path / "out").mkdir()
    proc = run_module(["segment", "builtin:polygon", "-o", "out"], tmp_path)
    assert_one_line_error(proc.returncode, proc.stderr, "out")


@pytest.mark.parametrize("args", [["segment", "builtin:ellipse", "--tol", "abc"], ["segment", "builtin:ellipse", "--bogus"],
                                  ["segment"]], ids=["tol text", "unknown option", "missing input"])
def test_cli_usage_errors_are_one_line(run_cli, args):
    """Regression: click usage errors once printed a three-line 'Usage: ... Error: ...' block."""
    code, _, err = run_cli(args)
    assert_one_line_error(code, err)


@pytest.mark.parametrize("umask,mode", [(0o022, 0o644), (0o077, 0o600)])
def test_outputs_get_the_usual_permissions(tmp_path, run_cli, umask, mode):
    old = os.umask(umask)
    try:
        code, _, err = run_cli(["segment", "builtin:polygon", "-o", str(tmp_path / "p.json"),
                                      "--plot", str(tmp_path / "p.png")])
    finally:
        os.umask(old)
    assert code == 0, err
    assert (tmp_path / "p.json").stat().st_mode & 0o777 == mode
    assert (tmp_path / "p.png").stat().st_mode & 0o777 == mode
