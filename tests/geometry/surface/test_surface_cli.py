"""``coatsim plan`` end to end: the file it writes, exit codes, one-line errors, the output guard."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
import trimesh

from coatsim.geometry.surface import read_surfacepaths
from coatsim.geometry.surface.mesh import load_part
from coatsim.geometry.surface.surfacepaths import FORMAT, dumps


@pytest.fixture(scope="module")
def box_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("part") / "box.stl"
    trimesh.creation.box((100.0, 80.0, 20.0)).export(path)
    return path


def test_plan_writes_the_contract(box_file, tmp_path, run_cli):
    out = tmp_path / "paths.json"
    code, stdout, stderr = run_cli(["plan", str(box_file), "-o", str(out), "--region", "facing:0,0,1",
                                    "--pose", "700,0,200,0,0,0", "--timings"])
    assert code == 0, stderr
    assert stdout.startswith("raster: 8 passes") and f"wrote {out}" in stdout
    assert "timings:" in stderr and "note: units auto" in stderr
    doc = json.loads(out.read_text())
    assert list(doc) == ["format", "units", "mesh", "pattern", "spacing_mm", "standoff_mm", "ripple_pct", "passes",
                         "stats"]
    assert doc["format"] == FORMAT and doc["units"] == "mm" and doc["pattern"] == "raster"
    assert list(doc["mesh"]) == ["file", "sha256", "vertices", "faces", "pose"]
    assert doc["mesh"]["pose"] == [700.0, 0.0, 200.0, 0.0, 0.0, 0.0]
    assert (doc["mesh"]["vertices"], doc["mesh"]["faces"]) == (8, 12)
    assert doc["spacing_mm"] == 10.0 and doc["standoff_mm"] == 100.0
    assert doc["ripple_pct"] == pytest.approx(400 * math.exp(-2 * math.pi**2 * 25 / 100), abs=1e-4)
    first = doc["passes"][0]
    assert list(first) == ["points", "normals", "closed", "lead_in", "lead_out"]
    assert first["closed"] is False and len(first["lead_in"]) == 1
    stats = doc["stats"]
    assert stats["passes"] == 8 and stats["seconds"] is None and stats["coverage"] == pytest.approx(1.0)
    assert stats["region_area_mm2"] == pytest.approx(8000.0)
    assert set(stats["spacing_along_surface_mm"]) == {"min", "median", "max"}
    paths = read_surfacepaths(out)
    assert dumps(paths) == out.read_text()  # the reader gives back every written value
    tcp = paths.tcp_mm()[0]
    assert tcp[:, 2] == pytest.approx(110.0)  # the top at z = 10, stand-off 100 along +z


def test_plan_is_deterministic(box_file, tmp_path, run_cli):
    for name in ("a.json", "b.json"):
        assert run_cli(["plan", str(box_file), "-o", str(tmp_path / name), "--pattern", "boundary"])[0] == 0
    assert (tmp_path / "a.json").read_bytes() == (tmp_path / "b.json").read_bytes()


def test_an_output_coatsim_did_not_write_is_kept(box_file, tmp_path, run_cli):
    out = tmp_path / "paths.json"
    out.write_text("my notes\n")
    code, _, stderr = run_cli(["plan", str(box_file), "-o", str(out)])
    assert code == 2 and len(stderr.splitlines()) == 1 and "not written by coatsim" in stderr
    assert out.read_text() == "my notes\n"
    assert run_cli(["plan", str(box_file), "-o", str(out), "--force"])[0] == 0
    assert run_cli(["plan", str(box_file), "-o", str(out)])[0] == 0  # its own output: replaced


def test_the_output_cannot_be_the_part(box_file, run_cli):
    code, _, stderr = run_cli(["plan", str(box_file), "-o", str(box_file)])
    assert code == 2 and "same file" in stderr


@pytest.mark.parametrize("flags, words", [
    (["--spacing", "0"], "--spacing must be a positive number"),
    (["--spacing", "8", "--ripple", "3"], "give --spacing or --ripple, not both"),
    (["--ripple", "150"], "--ripple must be between 0 and 100"),
    (["--pattern", "spiral"], "--pattern must be one of raster, geodesic, boundary"),
    (["--order", "random"], "--order must be one of serpentine, oneway"),
    (["--pattern", "geodesic", "--direction", "1,0,0"], "--direction applies to the raster --pattern"),
    (["--from", "plane:0,0,0,0,0,1"], "--from applies to the geodesic --pattern"),
    (["--direction", "1,0"], "--direction: expected X,Y,Z"),
    (["--direction", "0,0,0"], "--direction must be three finite numbers"),
    (["--region", "facing:0,0,1,0"], "--region facing angle must be in (0, 180]"),
    (["--region", "sphere:1"], "--region: expected facing"),
    (["--region", "box:0,0,0,1,1"], "--region box: expected"),
    (["--region", "box:0,0,0,-1,1,1"], "--region box must have max > min"),
    (["--region", "box:200,200,200,300,300,300"], "no face of the part that the gun sees lies in the --region"),
    (["--pattern", "geodesic", "--from", "points:0,0,500"], "--from point"),
    (["--pattern", "geodesic", "--from", "plane:0,0,500,0,0,1"], "the --from does not touch the region"),
    (["--units", "furlong"], "--units must be one of"),
    (["--pose", "1,2,3"], "--pose: expected X,Y,Z,O,A,T"),
    (["--gun", "gaussian:sigma=-1"], "--gun: footprint"),
    (["--edge-band", "60"], "use a smaller --edge-band"),
    (["--margin", "-1"], "--margin must be a non-negative number"),
])
def test_bad_settings_get_one_line_naming_the_flag(box_file, tmp_path, run_cli, flags, words):
    out = tmp_path / "paths.json"
    code, stdout, stderr = run_cli(["plan", str(box_file), "-o", str(out), *flags])
    assert code == 2 and stdout == "" and len(stderr.splitlines()) == 1, stderr
    assert stderr.startswith("coatsim: error: ") and words in stderr
    assert not out.exists()


@pytest.mark.parametrize("pattern, words", [("boundary", "boundary passes need a --region with a border"),
                                            ("geodesic", "give a plane or points as the --from")])
def test_a_closed_smooth_part_has_no_border_to_start_from(tmp_path, run_cli, pattern, words):
    # a box's sharp edges bound each of its faces; a sphere's surface has no border and no edge
    sphere = tmp_path / "ball.stl"
    trimesh.creation.icosphere(3, radius=50.0).export(sphere)
    out = tmp_path / "paths.json"
    code, stdout, stderr = run_cli(["plan", str(sphere), "-o", str(out), "--pattern", pattern, "--region", "all"])
    assert code == 2 and stdout == "" and stderr.splitlines()[-1].startswith("coatsim: error: ")
    assert words in stderr and not out.exists()


def test_ripple_sets_the_largest_spacing_that_keeps_it(box_file, tmp_path, run_cli):
    out = tmp_path / "paths.json"
    assert run_cli(["plan", str(box_file), "-o", str(out), "--ripple", "1", "--gun", "gaussian:sigma=4"])[0] == 0
    paths = read_surfacepaths(out)
    assert paths.ripple_pct == pytest.approx(1.0, abs=1e-4)
    assert paths.spacing_mm == pytest.approx(math.pi * 4 * math.sqrt(2 / math.log(400)), rel=1e-6)
    assert np.diff([p.points[:, 1].mean() for p in paths.passes]) == pytest.approx(
        paths.spacing_mm * np.sign(paths.passes[1].points[0, 1] - paths.passes[0].points[0, 1]), rel=1e-6)


def test_a_part_over_the_budget_at_a_guessed_unit_names_the_guess(tmp_path, run_cli):
    """A 2.4-inch plate without units is read as 2.4 m (extent below the metres threshold): the
    budget error then names the guess and --units, the fix that is right, besides the budget."""
    path = tmp_path / "plate_in.stl"
    trimesh.creation.box((2.4, 1.8, 0.2)).export(path)
    code, stdout, stderr = run_cli(["plan", str(path), "-o", str(tmp_path / "p.json"), "--region", "facing:0,0,1"])
    assert code == 2 and len(stderr.splitlines()) == 1, stderr
    assert "or give the --units (largest extent 2.4 read as metres (2400 mm))" in stderr
    code, _, stderr = run_cli(["plan", str(path), "-o", str(tmp_path / "q.json"), "--region", "facing:0,0,1",
                               "--units", "in"])
    assert code == 0, stderr


@pytest.mark.parametrize("extent, unit, size_mm", [(2.4, "metres", 2400.0), (3.0, "inches", 76.2),
                                                   (8.0, "inches", 203.2), (12.0, "millimetres", 12.0)])
def test_auto_units_guess_from_the_extent(tmp_path, extent, unit, size_mm):
    """Without a unit in the file: below 2.5 metres, up to 10 inches (as many metres fit no arm's
    reach; CAD exports without units are often in inches), from 10 millimetres; the note says which."""
    path = tmp_path / "plate.stl"
    trimesh.creation.box((extent, extent / 2, extent / 20)).export(path)
    part = load_part(path, "auto")
    assert np.ptp(part.vertices_mm, axis=0).max() == pytest.approx(size_mm, rel=1e-6)  # STL: float32
    assert f"read as {unit}" in part.notes[0]
