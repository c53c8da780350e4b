"""`coatsim segment` on drawings: the part JSON (coatsim.part/1) with a complete
polysegment/1 document per contour, one contour as polysegment/1, plots, flags, one-line
errors with exit code 2."""

from __future__ import annotations

import json

import pytest

from coatsim.geometry.part_json import read_part_json
from coatsim.geometry.polysegment_json import polysegment_from_document

from cad_helpers import write_dxf, write_svg

POLY_KEYS = {"format", "units", "closed", "tolerance_mm", "segments", "corners", "speed_limited", "stats"}


def plate(msp, doc) -> None:
    msp.add_lwpolyline([(0, 0), (120, 0), (120, 80), (0, 80)], close=True)
    msp.add_circle((30, 40), 10)
    msp.add_circle((90, 40), 12)
    msp.add_text("PLATE")


def test_part_json_holds_a_complete_polysegment_document_per_contour(tmp_path, run_cli):
    dxf = write_dxf(tmp_path, plate)
    out = tmp_path / "part.json"
    code, stdout, err = run_cli(["segment", str(dxf), "--tol", "0.05", "-o", str(out), "--plot", str(tmp_path / "p.png")])
    assert code == 0, err
    assert "3 contours (3 closed)" in stdout and "note: ignored 1 TEXT" in stdout
    doc = json.loads(out.read_text(encoding="utf-8"))
    assert doc["format"] == "coatsim.part/1" and doc["units"] == "mm" and doc["source"] == str(dxf)
    assert len(doc["contours"]) == 3
    for k, contour in enumerate(doc["contours"]):
        assert set(contour) == POLY_KEYS and contour["format"] == "coatsim.polysegment/1"
        assert contour["tolerance_mm"] == 0.05 and contour["closed"] is True
        polysegment_from_document(contour, f"contours[{k}]")
    assert doc["stats"]["n_contours"] == 3 and doc["stats"]["n_segments"] == 6
    assert doc["stats"]["max_deviation_mm"] == 0.0
    part = read_part_json(out)
    assert len(part.contours) == 3 and part.tolerance_mm == 0.05
    assert (tmp_path / "p.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_single_contour_drawing_keeps_polysegment_json(tmp_path, run_cli):
    svg = write_svg(tmp_path, '<rect x="10" y="10" width="80" height="40" rx="5"/>')
    out = tmp_path / "poly.json"
    code, _, err = run_cli(["segment", str(svg), "-o", str(out), "--plot", str(tmp_path / "p.png")])
    assert code == 0, err
    doc = json.loads(out.read_text(encoding="utf-8"))
    assert set(doc) == POLY_KEYS and doc["format"] == "coatsim.polysegment/1"
    assert doc["stats"]["n_segments"] == 8 and doc["stats"]["input_primitives"] == 8
    assert doc["corners"] == [] and doc["stats"]["max_deviation_mm"] == 0.0


def test_layer_and_join_tolerance_flags(tmp_path, run_cli):
    def draw(msp, doc):
        doc.layers.add("CUT")
        msp.add_line((0, 0), (10, 0), dxfattribs={"layer": "CUT"})
        msp.add_line((10.004, 0), (10, 10), dxfattribs={"layer": "CUT"})
        msp.add_circle((50, 50), 5)

    dxf = write_dxf(tmp_path, draw)
    code, out, err = run_cli(["segment", str(dxf), "--layer", "CUT", "--join-tol", "0.005"])
    assert code == 0, err
    assert "1 contour (1 closed)" not in out and "1 contour (0 closed)" in out
    code, out, err = run_cli(["segment", str(dxf), "--layer", "CUT", "--layer", "0", "--join-tol", "0.005"])
    assert code == 0 and "2 contours" in out
    code, out, err = run_cli(["segment", str(dxf), "--layer", "CUT"])  # the 0.004 mm gap is closed, and noted
    assert code == 0 and "1 contour (0 closed)" in out and "largest gap closed is 0.004 mm" in out


@pytest.mark.parametrize(("args", "match"), [
    (["--method", "paper"], "apply to point curves"),
    (["--closed", "yes"], "--closed applies to point curves"),
    (["--join-tol", "0.5"], "--join-tol 0.5: must be > 0 and below the tolerance"),
    (["--join-tol", "-1"], "--join-tol"),
    (["--layer", "NOPE"], "no such layer"),
])
def test_bad_flags_on_drawings(tmp_path, run_cli, args, match):
    code, _, err = run_cli(["segment", str(write_dxf(tmp_path, plate)), *args])
    assert code == 2 and match in err and err.startswith("coatsim: error: ") and err.count("\n") == 1


def test_drawing_flags_on_point_curves(run_cli):
    code, _, err = run_cli(["segment", "builtin:ellipse", "--layer", "A"])
    assert code == 2 and "apply to drawings" in err


@pytest.mark.parametrize(("name", "content", "match"), [
    ("empty.dxf", None, "modelspace is empty"),
    ("garbage.dxf", b"\x00\xff binary", "not a readable DXF file"),
    ("broken.svg", b"<svg xmlns='http://www.w3.org/2000/svg'><path d='M 0 0 L 1 1'>", "not well-formed SVG"),
    ("bad.svg", b"<svg xmlns='http://www.w3.org/2000/svg'><path id='p9' d='M 0 0 L 5'/></svg>", "<path id='p9'>"),
])
def test_bad_drawings_exit_2_with_one_line(tmp_path, run_cli, name, content, match):
    if content is None:
        path = write_dxf(tmp_path, lambda msp, doc: None, name=name)
    else:
        path = tmp_path / name
        path.write_bytes(content)
    code, out, err = run_cli(["segment", str(path)])
    assert code == 2 and match in err and str(path) in err and err.count("\n") == 1 and "Traceback" not in err
