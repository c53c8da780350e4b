"""Programs of parts: contours sprayed one after the other with the gun off between them,
read back by the interpreter; spray order; a one-contour part is the single-contour program;
the program command on drawings and part JSON."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from coatsim.languages.kawasaki_as.language import KAWASAKI_AS
from coatsim.core.errors import InputError
from coatsim.geometry import Arc, Line, Polysegment
from coatsim.languages.kawasaki_as.parser import parse_as
from coatsim.path.build import ProgramOptions, build_program
from coatsim.languages.kawasaki_as.interpreter import interpret
from coatsim.path.part_program import build_part_program, contour_order, part_centering_offset
from coatsim.geometry.space.xyzoat import pose_from_xyzoat
from coatsim.path.placement import Placement

from program_helpers import roundrect


def circle(cx: float, cy: float, r: float) -> Polysegment:
    start = (cx + r, cy)
    return Polysegment((Arc(start, start, (cx, cy), r, 2 * math.pi),), closed=True)


PART = [roundrect(), circle(-40.0, 0.0, 12.0), circle(40.0, 0.0, 15.0)]
PLACEMENT = Placement(frame=pose_from_xyzoat((700, 0, 200, 0, 0, 0)), standoff_mm=100.0, lead_in_mm=10.0, lead_out_mm=10.0)


def toolpath_of(text: str):
    return interpret(parse_as(text, "part.as"))


def spray_runs(toolpath) -> list[list]:
    runs, current = [], []
    for move in toolpath.moves:
        if move.spray:
            current.append(move)
        elif current:
            runs.append(current)
            current = []
    return runs + ([current] if current else [])


def test_part_program_sprays_each_contour_with_the_gun_off_between():
    options = ProgramOptions(approach_mm=40.0)
    built = build_part_program(PART, PLACEMENT, options, language=KAWASAKI_AS, tolerance_mm=0.1, source="part")
    tp = toolpath_of(built.text)
    runs = spray_runs(tp)
    assert len(runs) == 3
    for run, poly in zip(runs, PART):
        start = run[0].start.translation_mm
        expected = np.array([700.0 + poly.start[0], poly.start[1], 300.0])
        # a closed contour is sprayed once around: the gun opens at its seam, after the lead-in
        assert np.linalg.norm(start - expected) < 1e-6
        assert all(abs(m.end.translation_mm[2] - 300.0) < 1e-6 for m in run)
    travel = [m for m in tp.moves if not m.spray and m.kind == "line" and m.start is not None
              and abs(m.start.translation_mm[2] - 340.0) < 1e-6 and abs(m.end.translation_mm[2] - 340.0) < 1e-6]
    assert len(travel) == 2  # one straight gun-off travel at the clearance between each pair of contours
    process = tp.process
    assert len(process.contours) == 3 and process.contour_order == (1, 2, 3)
    assert process.curve_length_mm == pytest.approx(sum(p.length for p in PART), abs=1e-6)
    assert process.n_segments == sum(p.n_segments for p in PART)


def test_one_contour_part_is_the_single_contour_program():
    options = ProgramOptions()
    single = build_program(PART[0], PLACEMENT, options, language=KAWASAKI_AS, tolerance_mm=0.1, source="part")
    part = build_part_program(PART[:1], PLACEMENT, options, language=KAWASAKI_AS, tolerance_mm=0.1, source="part")
    assert part.text == single.text and part.curves == (single.curve,)


@pytest.mark.parametrize("variant", ["polyline-stop", "polyline-blend"])
def test_polyline_variants_of_a_part(variant):
    built = build_part_program(PART, PLACEMENT, ProgramOptions(variant=variant), language=KAWASAKI_AS, tolerance_mm=0.1, source="part")
    assert len(built.curves) == 3 and all(c.n_arcs == 0 for c in built.curves)
    assert len(spray_runs(toolpath_of(built.text))) == 3


def test_nearest_order_goes_to_the_closest_start():
    far, near = circle(300.0, 0.0, 5.0), circle(20.0, 0.0, 5.0)
    line = Polysegment((Line((0.0, 0.0), (10.0, 0.0)),))
    assert contour_order([line, far, near], "nearest") == (0, 2, 1)
    assert contour_order([line, far, near], "as-drawn") == (0, 1, 2)
    built = build_part_program([line, far, near], PLACEMENT, ProgramOptions(), language=KAWASAKI_AS, tolerance_mm=0.1, source="p",
                               order="nearest")
    assert built.order == (0, 2, 1) and built.curves[1] is near
    with pytest.raises(InputError, match=r"--order 'random'"):
        contour_order([line, far, near], "random")


def test_a_part_needs_a_travel_clearance():
    with pytest.raises(InputError, match=r"--approach 0: a part of 3 contours"):
        build_part_program(PART, PLACEMENT, ProgramOptions(approach_mm=0.0), language=KAWASAKI_AS, tolerance_mm=0.1, source="part")


def test_centering_takes_every_contour():
    off = part_centering_offset([circle(0.0, 0.0, 10.0), circle(100.0, 50.0, 10.0)])
    assert off == pytest.approx((-50.0, -25.0))


def _part_dxf(tmp_path):
    import ezdxf

    doc = ezdxf.new("R2010")
    doc.header["$INSUNITS"] = 4
    msp = doc.modelspace()
    msp.add_lwpolyline([(0, 0), (120, 0), (120, 80), (0, 80)], close=True)
    msp.add_circle((30, 40), 10)
    msp.add_circle((90, 40), 12)
    path = tmp_path / "plate.dxf"
    doc.saveas(path)
    return path


def test_program_command_on_a_drawing_and_on_its_part_json(tmp_path, run_cli):
    dxf = _part_dxf(tmp_path)
    code, out, err = run_cli(["program", str(dxf), "--tol", "0.1", "--order", "nearest", "-o", str(tmp_path / "a.as")])
    assert code == 0, err
    assert "3 contours" in err + out
    code, out, err = run_cli(["segment", str(dxf), "-o", str(tmp_path / "part.json")])
    assert code == 0, err
    doc = json.loads((tmp_path / "part.json").read_text(encoding="utf-8"))
    assert doc["format"] == "coatsim.part/1" and len(doc["contours"]) == 3
    code, out, err = run_cli(["program", str(tmp_path / "part.json"), "-o", str(tmp_path / "b.as")])
    assert code == 0, err
    a = toolpath_of((tmp_path / "a.as").read_text(encoding="utf-8"))
    b = toolpath_of((tmp_path / "b.as").read_text(encoding="utf-8"))
    assert len(spray_runs(a)) == len(spray_runs(b)) == 3


def test_program_command_errors_on_drawings(tmp_path, run_cli):
    dxf = _part_dxf(tmp_path)
    code, _, err = run_cli(["program", str(dxf)])
    assert code == 2 and "--tol MM is required" in err and err.count("\n") == 1
    code, _, err = run_cli(["program", "builtin:ellipse", "--tol", "0.1", "--layer", "X"])
    assert code == 2 and "apply to drawings" in err
    code, _, err = run_cli(["program", str(dxf), "--tol", "0.1", "--layer", "NOPE"])
    assert code == 2 and "no such layer" in err


def test_per_contour_header_fields_of_a_mixed_part():
    """A closed contour is sprayed once around, an open one with its leads; the header says so
    per contour, in spray order."""
    stroke = Polysegment((Line((-60.0, 30.0), (60.0, 30.0)),))
    built = build_part_program([PART[1], stroke], PLACEMENT, ProgramOptions(), language=KAWASAKI_AS, tolerance_mm=0.1, source="part")
    text = built.text
    assert "; coatsim: closed=yes | no\n" in text and "; coatsim: sprayed=curve | lead-in,curve,lead-out\n" in text
    contours = toolpath_of(text).process.contours
    assert [(c.closed, c.leads_sprayed) for c in contours] == [(True, False), (False, True)]
    runs = spray_runs(toolpath_of(built.text))
    assert [len(r) for r in runs][1] == 3  # lead-in, line, lead-out
