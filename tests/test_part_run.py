"""`coatsim run` end to end on a drawn part (an outline and two holes, a DXF written here)
with the real stack in fast mode: part.json, one program spraying every contour, the
per-contour metrics summing to the part's, the report drawing every contour."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from coatsim.geometry.part_json import read_part_json
from coatsim.languages.kawasaki_as.files import read_toolpath
from coatsim.robot.trajectory_log import read_trajectory_csv

SCENARIO = """\
name: drawn_part
curve: {{file: plate.dxf, layer: CUT}}
segmentation: {{tolerance_mm: 0.05}}
workpiece: {{kind: plate, size_mm: [200.0, 150.0]}}
gun: {{footprint: "gaussian:sigma=5", target_thickness_um: 16.0}}
motion: {{speed_mm_s: 200.0, accuracy_mm: 0.5, lead_in_mm: 10.0, lead_out_mm: 10.0, contour_order: {order}}}
coating: {{spacing_mm: 2.5, band_halfwidth_mm: 2.5}}
fast: {{coating_spacing_mm: 3.0, sample_step_mm: 2.0}}
variants: [polysegment, polyline-blend]
gates:
  - {{metric: segmentation.max_deviation_mm, op: "==", threshold: 0.0}}
  - {{metric: motion.stops, op: "==", threshold: 0}}
"""


def _plate(path) -> None:
    import ezdxf

    doc = ezdxf.new("R2010")
    doc.header["$INSUNITS"] = 4
    doc.layers.add("CUT")
    msp = doc.modelspace()
    b = math.tan(math.pi / 8)
    msp.add_lwpolyline([(10, 0, 0, 0, 0), (110, 0, 0, 0, b), (120, 10), (120, 70, 0, 0, b), (110, 80),
                        (10, 80, 0, 0, b), (0, 70), (0, 10, 0, 0, b)], format="xyseb", close=True,
                       dxfattribs={"layer": "CUT"})
    msp.add_circle((90, 40), 12, dxfattribs={"layer": "CUT"})  # drawn before the nearer hole
    msp.add_circle((30, 40), 10, dxfattribs={"layer": "CUT"})
    msp.add_text("PLATE", dxfattribs={"layer": "CUT"})
    msp.add_circle((300, 300), 50)  # layer 0: not sprayed
    doc.saveas(path)


@pytest.mark.slow
@pytest.mark.parametrize("order", ["nearest"])
def test_run_on_a_drawn_part(tmp_path, run_cli, order):
    _plate(tmp_path / "plate.dxf")
    scenario = tmp_path / "part.yaml"
    scenario.write_text(SCENARIO.format(order=order), encoding="utf-8")
    out = tmp_path / "run"
    code, stdout, err = run_cli(["run", str(scenario), "--fast", "-o", str(out)])
    assert code == 0, err
    part = read_part_json(out / "part.json")
    assert len(part.contours) == 3 and all(c.closed for c in part.contours)
    assert [c.n_segments for c in part.contours] == [8, 1, 1]

    doc = json.loads((out / "metrics.json").read_text(encoding="utf-8"))
    rows = doc["contours"]
    assert [r["contour"] for r in rows] == [1, 2, 3]
    assert [r["spray_order"] for r in rows] == [1, 3, 2]  # nearest: the left hole before the right one
    for variant, groups in doc["variants"].items():
        seg = [r["variants"][variant]["segmentation"] for r in rows]
        mot = [r["variants"][variant]["motion"] for r in rows]
        assert groups["segmentation"]["n_segments"] == sum(s["n_segments"] for s in seg)
        assert groups["segmentation"]["curve_length_mm"] == pytest.approx(sum(s["curve_length_mm"] for s in seg))
        assert groups["motion"]["cycle_time_s"] == pytest.approx(sum(m["cycle_time_s"] for m in mot), abs=1e-5)
        assert groups["motion"]["stops"] == sum(m["stops"] for m in mot)
    assert doc["variants"]["polysegment"]["segmentation"]["max_deviation_mm"] == 0.0
    assert doc["passed"] is True

    toolpath = read_toolpath(out / "polysegment.as")
    assert toolpath.process.contour_order == (1, 3, 2)
    log = read_trajectory_csv(out / "polysegment.trajectory.csv")
    assert np.count_nonzero(np.diff(log.spray.astype(int)) == 1) == 3
    html = (out / "report.html").read_text(encoding="utf-8")
    assert "The part&#x27;s contours and their polysegments" in html and "ignored 1 TEXT" in html


USER = """\
name: drawn_part_user
curve: {file: plate.dxf, layer: CUT}
segmentation: {tolerance_mm: 0.05}
workpiece: {kind: plate, size_mm: [200.0, 150.0]}
gun: {footprint: "gaussian:sigma=5", target_thickness_um: 16.0}
motion: {speed_mm_s: 200.0, accuracy_mm: 0.5, lead_in_mm: 10.0, lead_out_mm: 10.0}
coating: {spacing_mm: 2.5, band_halfwidth_mm: 2.5}
fast: {coating_spacing_mm: 3.0, sample_step_mm: 2.0}
variants: [polysegment, {name: mine, program: mine.as}]
"""


@pytest.mark.slow
def test_user_program_variant_on_a_drawn_part(tmp_path, run_cli):
    """A user's program of the part (here coatsim's own, written with `coatsim program`) runs
    beside coatsim's; its segmentation is measured against the contour it sprays longest."""
    _plate(tmp_path / "plate.dxf")
    code, _, err = run_cli(["program", str(tmp_path / "plate.dxf"), "--tol", "0.05", "--layer", "CUT", "--center",
                            "--speed", "200", "--lead-in", "10", "--lead-out", "10", "-o", str(tmp_path / "mine.as")])
    assert code == 0, err
    (tmp_path / "user.yaml").write_text(USER, encoding="utf-8")
    code, _, err = run_cli(["run", str(tmp_path / "user.yaml"), "--fast", "-o", str(tmp_path / "run")])
    assert code == 0, err
    doc = json.loads((tmp_path / "run" / "metrics.json").read_text(encoding="utf-8"))
    mine = doc["variants"]["mine"]["segmentation"]
    outline = doc["contours"][0]["variants"]["polysegment"]["segmentation"]
    # its longest sprayed stretch is the closed outline, sprayed once around
    assert mine["curve_length_mm"] == pytest.approx(outline["curve_length_mm"], rel=1e-6)
    # measured against the outline's samples: chords within the flattening distance σ/20 of its arcs
    assert mine["max_deviation_mm"] <= 0.05 / 20 + 1e-9
    assert [r["contour"] for r in doc["contours"]] == [1, 2, 3] and "mine" not in doc["contours"][0]["variants"]
