"""Scenario keys of a 3-D part (part, paths): defaults, one-line errors naming the key, the
schema, and the files a run reads and writes."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from coatsim.core import defaults
from coatsim.core.errors import InputError
from coatsim.geometry.surface import Box, Everything, Facing
from coatsim.run.part_run import part_output_names, region_of
from coatsim.run.scenario import json_schema, load_scenario
from coatsim.run.scenario_inputs import input_files

PART = """\
name: part_job
part:
  mesh: parts/p.stl
"""


def write(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "job.yaml"
    path.write_text(text, encoding="utf-8")
    return path


def error(tmp_path: Path, text: str) -> str:
    with pytest.raises(InputError) as info:
        load_scenario(write(tmp_path, text))
    message = str(info.value)
    assert "\n" not in message
    return message


def test_a_part_alone_gets_the_documented_defaults(tmp_path: Path) -> None:
    spec = load_scenario(write(tmp_path, PART)).spec
    assert spec.workpiece is None and spec.curve is None and spec.paths is None
    assert spec.part.units == defaults.PLAN_UNITS and spec.part.pose == list(defaults.WORKPIECE_FRAME)
    planned = spec.planned
    assert (planned.pattern, planned.order, planned.edge_band_mm) == (defaults.PLAN_PATTERN, defaults.PLAN_ORDER,
                                                                        defaults.PLAN_EDGE_BAND_MM)
    assert planned.speed_on == defaults.SCENARIO_SPEED_ON and planned.angle_tol_deg == defaults.ANGLE_TOL_DEG
    assert region_of(spec.part.region) == Facing(None, defaults.PLAN_FACING_DEG)


@pytest.mark.parametrize("region, expected", [
    ("{facing: [0, 0, 1], max_angle_deg: 45}", Facing((0.0, 0.0, 1.0), 45.0)),
    ("{box: [-1, -2, -3, 1, 2, 3]}", Box((-1.0, -2.0, -3.0), (1.0, 2.0, 3.0))),
    ("{all: true}", Everything()),
])
def test_regions_become_the_planners(tmp_path: Path, region: str, expected) -> None:
    spec = load_scenario(write(tmp_path, PART + f"  region: {region}\n")).spec
    assert region_of(spec.part.region) == expected


@pytest.mark.parametrize("extra, words", [
    ("workpiece: {kind: plate, size_mm: [10, 10]}\n", "exactly one of 'workpiece'"),
    ("curve: {builtin: raster}\n", "a curve or a user's program over a mesh"),
    ("paths: {spacing_mm: 10, ripple_pct: 3}\n", "at most one of 'spacing_mm' or 'ripple_pct'"),
    ("paths: {pattern: geodesic, direction: [0, 1, 0]}\n", "'direction' applies to the raster pattern"),
    ("paths: {spacing_mm: -1}\n", "paths.spacing_mm"),
    ("paths: {speed_on: spot}\n", "paths.speed_on"),
    ("paths: {angle_tol_deg: 95}\n", "paths.angle_tol_deg"),
])
def test_bad_part_keys_are_one_line_errors_naming_them(tmp_path: Path, extra: str, words: str) -> None:
    assert words in error(tmp_path, PART + extra)


@pytest.mark.parametrize("region, words", [
    ("{facing: [0, 0, 1], all: true}", "at most one of 'facing', 'box' or 'all: true'"),
    ("{box: [0, 0, 0, 1, 1, 1], max_angle_deg: 30}", "'max_angle_deg' applies to a facing region"),
    ("{box: [1, 0, 0, 0, 1, 1]}", "each min below its max"),
    ("{facing: [0, 1]}", "part.region.facing"),
])
def test_bad_regions_name_the_key(tmp_path: Path, region: str, words: str) -> None:
    assert words in error(tmp_path, PART + f"  region: {region}\n")


def test_paths_without_a_part_and_neither_part_nor_workpiece_are_refused(tmp_path: Path) -> None:
    curve = "name: c\ncurve: {builtin: raster}\n"
    assert "'paths' plans passes on a 'part'" in error(
        tmp_path, curve + "workpiece: {kind: plate, size_mm: [300, 200]}\npaths: {pattern: raster}\n")
    assert "exactly one of 'workpiece'" in error(tmp_path, curve)


def test_the_schema_documents_part_and_paths() -> None:
    schema = json.loads(json_schema())
    assert {"part", "paths", "workpiece"} <= set(schema["properties"])
    assert {"mesh", "units", "pose", "region"} == set(schema["$defs"]["PartSpec"]["properties"])
    assert {"pattern", "spacing_mm", "ripple_pct", "standoff_mm", "direction", "margin_mm",
            "edge_band_mm"} <= set(schema["$defs"]["PathsSpec"]["properties"])


def test_a_part_run_reads_the_mesh_and_writes_paths_programs_and_report(tmp_path: Path) -> None:
    loaded = load_scenario(write(tmp_path, PART + "variants: [polysegment, {variant: polyline-stop, language: "
                                                  "abb-rapid}]\n"))
    assert ("part.mesh", tmp_path / "parts/p.stl") in input_files(loaded)
    names = part_output_names(loaded)
    assert names[0] == "paths.json" and names[-1] == "report.html"
    assert {"polysegment.as", "polysegment.trajectory.csv", "polyline-stop-abb-rapid.trajectory.csv",
            "polysegment.thickness.glb", "metrics.json"} <= set(names)
    assert any(n.endswith(".mod") for n in names)
