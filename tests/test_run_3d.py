"""`coatsim run` on the shipped 3-D parts end to end (the real stack at coarse numerics): plan,
programs of the passes, the twin with the part in the cell, the coat on the mesh with shadows,
metrics against closed forms where the tube gives them, the files and the report's sections."""

from __future__ import annotations

import json
import math
import re

import numpy as np
import pytest

from part_scenarios import cheap_scenario

from coatsim.run.pipeline import run_scenario


def check_run(result, variants: list[str]) -> None:
    """What every run on a part must hold, whatever the part."""
    doc = json.loads((result.outdir / "metrics.json").read_text(encoding="utf-8"))
    assert list(doc["variants"]) == variants and doc["passed"]
    plan = doc["plan"]
    assert plan["passes"] == len(doc["passes"]) >= 1
    for row in doc["passes"]:
        assert set(row["variants"]) == set(variants)
    for name in variants:
        seg, motion, coating = (doc["variants"][name][g] for g in ("segmentation", "motion", "coating"))
        assert seg["max_deviation_mm"] <= seg["tolerance_mm"] * (1 + 1 / 8) + 1e-9
        assert seg["n_segments"] == seg["n_lines"] + seg["n_arcs"] > 0
        assert coating["coated_fraction"] > 0.99 and coating["thickness_mean_um"] > 0
        assert 0 < coating["deposition_efficiency"] <= 1
        cycle = sum(row["variants"][name]["cycle_time_s"] for row in doc["passes"])
        assert cycle == pytest.approx(motion["cycle_time_s"], rel=0.02)
        for suffix in ("trajectory.csv", "thickness.ply", "thickness.glb"):
            assert (result.outdir / f"{name}.{suffix}").stat().st_size > 0
    if "polyline-stop" in variants:  # an exact stop at the vertices inside passes, none on the arcs
        stop = doc["variants"]["polyline-stop"]
        inner_vertices = stop["segmentation"]["n_segments"] - plan["passes"]
        assert (stop["motion"]["stops"] > 0) == (inner_vertices > 0)
        assert doc["variants"]["polysegment"]["motion"]["stops"] == 0
    paths = json.loads((result.outdir / "paths.json").read_text(encoding="utf-8"))
    assert paths["format"] == "coatsim.surfacepaths/1" and len(paths["passes"]) == plan["passes"]


ALL = ["polysegment", "polyline-stop", "polyline-blend"]


# the exact-stop polyline on the blade and the scan: the twin once overshot their wrists'
# accelerations at its stops and refused it (the wear plate's passes are straight: no stop)
@pytest.mark.parametrize("name, variants", [("blade_3d", ALL), ("wear_plate_3d", ["polysegment", "polyline-blend"]),
                                            ("scan_patch_3d", ALL)])
def test_each_shipped_part_runs_end_to_end(tmp_path, name: str, variants: list[str]) -> None:
    scenario = cheap_scenario(tmp_path, name, variants, spacing_mm=40.0, coating_mm=5.0, sample_mm=4.0)
    result = run_scenario(scenario, tmp_path / "out", fast=True, progress=False, report=False)
    check_run(result, variants)
    assert not (tmp_path / "out" / "report.html").exists()


def test_the_tube_runs_end_to_end(tube_run) -> None:
    result, _ = tube_run
    check_run(result, ["polysegment", "polyline-stop", "polyline-blend"])


def test_on_the_tube_the_field_gets_q_over_v_times_spacing(tube_run) -> None:
    """Passes along the axis at one speed of the spray spot, evenly spaced along the surface: the
    field's mean thickness is the volume per length over the spacing, Q / (v s), the ripple of
    the overlaps averaging out over whole gaps (within 3 %); the gun stays square to the surface."""
    result, _ = tube_run
    doc = result.document
    spec = doc["scenario"]
    q, v, s = spec["gun"]["flow_mm3_s"], spec["motion"]["speed_mm_s"], spec["paths"]["spacing_mm"]
    assert doc["plan"]["spacing_min_mm"] == pytest.approx(s, rel=0.01)
    assert doc["plan"]["spacing_max_mm"] == pytest.approx(s, rel=0.01)
    coating = doc["variants"]["polysegment"]["coating"]
    assert coating["thickness_mean_um"] == pytest.approx(1000 * q / (v * s), rel=0.03)
    assert coating["low_angle_fraction"] == 0.0
    assert 99.5 <= coating["standoff_min_mm"] <= coating["standoff_max_mm"] <= 110.0


def test_the_tubes_region_is_its_upper_third(tube_run) -> None:
    """Faces within 60 deg of +z on a tube of 64 facets: 2 pi R / 3 x L, give or take a facet row
    on each side."""
    result, _ = tube_run
    r, length, facet = 60.0, 200.0, 2 * 60.0 * math.sin(math.pi / 64)
    assert result.document["plan"]["region_area_mm2"] == pytest.approx(2 * math.pi * r / 3 * length,
                                                                       abs=2 * facet * length)


def test_the_spot_keeps_its_speed_on_the_arcs_and_stops_at_polyline_vertices(tube_run) -> None:
    result, _ = tube_run
    passes = result.document["passes"]
    for row in passes:
        arcs, stop = row["variants"]["polysegment"], row["variants"]["polyline-stop"]
        assert arcs["spot_min_ratio"] > 0.95 and arcs["stops"] == 0
        assert stop["spot_min_ratio"] < 0.1


def test_the_report_has_the_part_sections_in_order(tube_run) -> None:
    from coatsim.report.part_document import PART_SECTION_IDS

    result, _ = tube_run
    html = (result.outdir / "report.html").read_text(encoding="utf-8")
    assert re.findall(r'<section id="([^"]+)"', html) == list(PART_SECTION_IDS)
    assert "Thickness histogram over the region of interest" in html and "coatsim-viewer-data" in html


def test_a_part_run_is_deterministic(tube_run, tmp_path) -> None:
    """The same scenario again: byte-identical metrics, paths and programs."""
    result, scenario = tube_run
    again = run_scenario(scenario, tmp_path / "again", fast=True, progress=False, report=False)
    for name in ("metrics.json", "paths.json", "polysegment.as", "polyline-stop.as"):
        assert (again.outdir / name).read_bytes() == (result.outdir / name).read_bytes(), name


def test_a_video_of_a_part_run_is_refused(tube_run, tmp_path) -> None:
    from coatsim.core.errors import InputError

    _, scenario = tube_run
    with pytest.raises(InputError, match="video"):
        run_scenario(scenario, tmp_path / "v", fast=True, progress=False, video=True)


def test_thickness_scale_is_shared_by_the_variants_glbs(tube_run) -> None:
    import trimesh

    result, _ = tube_run
    tops = set()
    for name in ("polysegment", "polyline-stop", "polyline-blend"):
        head = (result.outdir / f"{name}.thickness.ply").read_bytes().split(b"end_header")[0].decode("ascii")
        tops.add(re.search(r"colours viridis from (\S+) to (\S+) um", head).groups())
        scene = trimesh.load(result.outdir / f"{name}.thickness.glb", process=False)
        assert "thickness" in scene.geometry and len(scene.geometry) >= 2  # the part and the passes
    assert len(tops) == 1
    assert np.isfinite(float(next(iter(tops))[1]))


def test_a_gun_mounted_at_an_angle_coats_the_tube_as_the_straight_one(tube_run, tmp_path) -> None:
    """A cell whose gun leaves the flange 30 deg off its axis: the programs carry that TOOL, the
    arm takes other joint paths, and the spray point runs the same path at the same speed, so the
    coat is the straight gun's."""
    from importlib.resources import files

    import yaml

    models = files("coatsim") / "models"
    cells = tmp_path / "cells"
    cells.mkdir()
    for name in ("coating_cell.xml", "rs013n_arm.xml"):
        (cells / name).write_text((models / name).read_text(encoding="utf-8"), encoding="utf-8")
    straight = '<site name="tcp" pos="0.25 0 0" quat="0.70710678 0 0.70710678 0"'
    gun = (models / "plasma_gun.xml").read_text(encoding="utf-8")
    assert straight in gun
    # the spray axis turned 30 deg about the flange's y axis, the nozzle 250 mm out along it
    (cells / "plasma_gun.xml").write_text(gun.replace(straight, '<site name="tcp" pos="0.21650635 0 0.125" '
                                                                'quat="0.8660254 0 0.5 0"'), encoding="utf-8")
    doc = yaml.safe_load(tube_run[1].read_text(encoding="utf-8"))
    doc["variants"], doc["robot"] = ["polysegment"], {"model": str(cells / "coating_cell.xml")}
    scenario = tmp_path / "angled.yaml"
    scenario.write_text(yaml.safe_dump(doc, sort_keys=False), encoding="utf-8")
    result = run_scenario(scenario, tmp_path / "out", fast=True, progress=False, report=False)
    check_run(result, ["polysegment"])
    program = (tmp_path / "out" / "polysegment.as").read_text(encoding="utf-8")
    assert re.search(r"TOOL TRANS\(-125\.0+,0\.0+,216\.50635\d*,180\.0+,30\.0+,180\.0+\)", program)
    angled = json.loads((tmp_path / "out" / "metrics.json").read_text(encoding="utf-8"))["variants"]["polysegment"]
    ref = json.loads((tube_run[0].outdir / "metrics.json").read_text(encoding="utf-8"))["variants"]["polysegment"]
    for group, key, rel in (("coating", "thickness_mean_um", 1e-3), ("coating", "thickness_cv", 1e-2),
                            ("motion", "cycle_time_s", 1e-2), ("motion", "min_speed_ratio", 1e-3)):
        assert angled[group][key] == pytest.approx(ref[group][key], rel=rel), (group, key)


def test_a_part_wound_inwards_is_coated_as_the_same_part_wound_outwards(tube_run, tmp_path) -> None:
    """The tube's file with every triangle (and then a strip of them) wound the other way: the
    planner turns them, and the coat and the cell must see the surface it planned on (the coat
    took the file's winding, found the region of interest empty and refused the run)."""
    import trimesh
    import yaml

    doc = yaml.safe_load(tube_run[1].read_text(encoding="utf-8"))
    mesh = trimesh.load(doc["part"]["mesh"], force="mesh", process=False)
    ref = json.loads((tube_run[0].outdir / "metrics.json").read_text(encoding="utf-8"))["variants"]["polysegment"]
    for label, flipped in (("all", np.ones(len(mesh.faces), bool)), ("strip", np.arange(len(mesh.faces)) % 7 == 0)):
        faces = mesh.faces.copy()
        faces[flipped] = faces[flipped][:, ::-1]
        path = tmp_path / f"tube_{label}.stl"
        trimesh.Trimesh(mesh.vertices, faces, process=False).export(path)
        doc["part"]["mesh"], doc["variants"] = str(path), ["polysegment"]
        scenario = tmp_path / f"{label}.yaml"
        scenario.write_text(yaml.safe_dump(doc, sort_keys=False), encoding="utf-8")
        result = run_scenario(scenario, tmp_path / label, fast=True, progress=False, report=False)
        check_run(result, ["polysegment"])
        got = json.loads((tmp_path / label / "metrics.json").read_text(encoding="utf-8"))["variants"]["polysegment"]
        for key in ("thickness_mean_um", "thickness_cv", "coated_fraction"):
            assert got["coating"][key] == pytest.approx(ref["coating"][key], rel=1e-6, abs=1e-9), (label, key)
