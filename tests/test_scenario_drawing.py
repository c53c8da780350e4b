"""Scenario keys for drawn parts: curve.file as a drawing with layer and join tolerance,
motion.contour_order, and the checks that keep them with drawings; the drawing is scaled and
rotated before it is fitted."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from coatsim.core.errors import InputError
from coatsim.robot.cell import load_cell
from coatsim.run.scenario import load_scenario
from coatsim.run.scenario_inputs import segment_input

BASE = """\
name: drawn
curve: {curve}
workpiece: {{kind: plate, size_mm: [300.0, 300.0]}}
motion: {{contour_order: {order}}}
"""


def _write(tmp_path: Path, curve: str, order: str = "as-drawn") -> Path:
    path = tmp_path / "s.yaml"
    path.write_text(BASE.format(curve=curve, order=order), encoding="utf-8")
    return path


def _dxf(tmp_path: Path) -> None:
    import ezdxf

    doc = ezdxf.new("R2010")
    doc.header["$INSUNITS"] = 4
    doc.layers.add("CUT")
    doc.modelspace().add_circle((10, 0), 5, dxfattribs={"layer": "CUT"})
    doc.modelspace().add_line((0, 0), (100, 0))
    doc.saveas(tmp_path / "part.dxf")


def test_drawing_keys_load_and_the_part_is_scaled_and_rotated(tmp_path):
    _dxf(tmp_path)
    loaded = load_scenario(_write(tmp_path, "{file: part.dxf, layer: [CUT], join_tolerance_mm: 0.0005, scale: 2.0, "
                                            "rotate_deg: 90}", "nearest"))
    assert loaded.spec.curve.layer == ["CUT"] and loaded.spec.motion.contour_order == "nearest"
    contours, part = segment_input(loaded, load_cell())
    assert part is not None and len(contours) == 1
    arc = contours[0].polysegment.segments[0]
    assert arc.radius == pytest.approx(10.0) and math.dist(arc.center, (0.0, 20.0)) < 1e-9
    assert part.join_tolerance_mm == 0.0005


@pytest.mark.parametrize(("curve", "fragment"), [
    ("{file: points.csv, layer: CUT}", "'layer' and 'join_tolerance_mm' apply to drawings"),
    ("{builtin: ellipse, join_tolerance_mm: 0.01}", "apply to drawings"),
    ("{file: part.dxf, closed: true}", "'closed' applies to point curves"),
])
def test_drawing_keys_only_with_drawings(tmp_path, curve, fragment):
    with pytest.raises(InputError, match=fragment):
        load_scenario(_write(tmp_path, curve))


def test_bad_order_and_missing_layer(tmp_path):
    _dxf(tmp_path)
    with pytest.raises(InputError, match="contour_order"):
        load_scenario(_write(tmp_path, "{file: part.dxf}", "random"))
    loaded = load_scenario(_write(tmp_path, "{file: part.dxf, layer: WOOD}"))
    with pytest.raises(InputError, match=r"s\.yaml:2: curve: .*layer 'WOOD' \(--layer\): no such layer"):
        segment_input(loaded, load_cell())
