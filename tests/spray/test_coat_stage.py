"""The stage end to end: mass balance on random paths, coat(), coatsim coat, bad input."""

from __future__ import annotations

import json
import math
import sys

import numpy as np
import pytest
import trimesh
from hypothesis import given, settings
from scipy.special import i0e

from coatsim.cli import main
from coatsim.spray.coat import coat, run_coat
from coatsim.spray.deposition import deposit
from coatsim.spray.surfaces import plate
from spray_helpers import H0, PLATE, Q, SIGMA, V, gun, line_log, make_log, random_paths, volume

@given(random_paths())
@settings(max_examples=25, deadline=None)
def test_12_deposited_volume_is_q_times_spray_time(log):
    """All spray lands on the plate (see PLATE), so the volume is Q x spray time to quadrature error."""
    result = deposit(PLATE, log, gun())
    on_time = float(np.sum(np.diff(log.t)[log.spray[:-1]]))
    assert result.steps.spray_time_s == pytest.approx(on_time, rel=1e-12, abs=1e-15)
    assert volume(PLATE, result.thickness_mm) == pytest.approx(Q * on_time, rel=1e-6, abs=1e-12)


def test_coat_on_a_closed_contour_meets_the_mass_balance():
    rho, n = 60.0, 800
    phase = np.linspace(0, 2 * math.pi, n + 1)
    log = make_log(phase * rho / V, np.column_stack([rho * np.cos(phase), rho * np.sin(phase), np.full(n + 1, H0)]))
    result = coat(log, plate(200, 200, SIGMA / 3), gun(), roi="band", target_um=4.0)
    m = result.metrics
    assert abs(m["deposited_volume_mm3"] / m["sprayed_volume_mm3"] - 1) < 0.005
    assert m["sprayed_volume_mm3"] == pytest.approx(Q * 2 * math.pi * rho / V)
    r = np.linspace(rho - 10, rho + 10, 20001)
    ring = Q * rho / (V * SIGMA**2) * np.exp(-(r - rho) ** 2 / (2 * SIGMA**2)) * i0e(r * rho / SIGMA**2) * 1000
    assert m["thickness_max_um"] == pytest.approx(ring.max(), rel=3e-3)  # §1.4 circle profile
    assert 0 < m["coverage_fraction"] < 1 and m["target_um"] == 4.0
    assert result.roi.sum() == m["roi_vertices"]


def write_pass_csv(path, spray=True):
    log = line_log((-60, 0, H0), (60, 0, H0), step_mm=2.0)
    log = make_log(log.t, log.position, spray=spray)
    log.write_csv(path)
    return path


def run_cli(monkeypatch, capsys, *args):
    monkeypatch.setattr(sys, "argv", ["coatsim", "coat", *map(str, args)])
    with pytest.raises(SystemExit) as exit_info:
        main()
    out, err = capsys.readouterr()
    return exit_info.value.code, out, err


def test_cli_writes_every_output_deterministically(tmp_path, monkeypatch, capsys):
    csv = write_pass_csv(tmp_path / "pass.csv")
    outputs = []
    for run in ("a", "b"):
        code, out, err = run_cli(monkeypatch, capsys, csv, "--surface", "plate:200x100@0,0,0", "--spacing", "2",
                                 "--target-um", "5", "-o", tmp_path / run)
        assert code == 0, err
        assert "deposited" in out
        outputs.append({p.name: p.read_bytes() for p in sorted((tmp_path / run).iterdir())})
    # the outputs and the folder's record of what coatsim wrote (coatsim.core.outputs_guard)
    assert sorted(outputs[0]) == [".coatsim-outputs.json", "coating.json", "heatmap.png", "section.png", "thickness.ply"]
    assert outputs[0] == outputs[1]
    doc = json.loads(outputs[0]["coating.json"])
    assert doc["format"] == "coatsim.coating/1" and doc["target_um"] == 5.0
    for key in ("thickness_max_um", "thickness_mean_um", "thickness_cv", "deposited_volume_mm3",
                "sprayed_volume_mm3", "on_part_efficiency", "coverage_fraction", "thick_spot_fraction",
                "thickness_p05_um", "thickness_p95_um", "thickness_min_um", "thickness_std_um"):
        assert isinstance(doc[key], float), key
    assert doc["sprayed_volume_mm3"] == pytest.approx(Q * 120 / V)
    assert doc["deposited_volume_mm3"] == pytest.approx(doc["sprayed_volume_mm3"], rel=1e-6)
    assert doc["thickness_max_um"] == pytest.approx(6.383, rel=2e-3)
    ply = trimesh.load(tmp_path / "a" / "thickness.ply", process=False)
    assert ply.metadata["_ply_raw"]["vertex"]["data"]["thickness"].max() == pytest.approx(doc["part_thickness_max_um"], rel=1e-6)


def test_cli_on_a_cylinder_and_a_mesh_file(tmp_path, monkeypatch, capsys):
    csv = write_pass_csv(tmp_path / "pass.csv")
    code, out, err = run_cli(monkeypatch, capsys, csv, "--surface", "cylinder:40x200@0,0,-40", "--spacing", "2",
                             "--roi", "part", "-o", tmp_path / "cyl")
    assert code == 0, err
    doc = json.loads((tmp_path / "cyl" / "coating.json").read_text())
    assert doc["inputs"]["roi"] == "part" and 0.5 < doc["on_part_efficiency"] <= 1.0
    mesh = tmp_path / "sheet.obj"
    trimesh.creation.box((200, 100, 2)).export(mesh)
    code, out, err = run_cli(monkeypatch, capsys, csv, "--surface", f"{mesh}@0,0,-1", "--spacing", "4",
                             "--footprint", "beta:radius=12,beta=2", "-o", tmp_path / "obj")
    assert code == 0, err
    doc = json.loads((tmp_path / "obj" / "coating.json").read_text())
    assert doc["deposited_volume_mm3"] == pytest.approx(Q * 120 / V, rel=0.01)


@pytest.mark.parametrize("args, words", [
    (["--surface", "plate:100x100", "--spacing", "0"], "spacing must be a positive"),
    (["--surface", "plate:100x100", "--spacing", "-2"], "spacing must be a positive"),
    (["--surface", "plate:100x100", "--rate", "0"], "rate must be positive"),
    (["--surface", "plate:100x100", "--rate", "-5"], "rate must be positive"),
    (["--surface", "plate:100x100", "--standoff", "0"], "stand-off must be positive"),
    (["--surface", "missing_part.stl"], "missing_part.stl: no such file"),
    (["--surface", "EMPTY"], "no triangles"),
    (["--surface", "plate:100x100", "--footprint", "gaussian:sigma=-1"], "sigma must be positive"),
    (["--surface", "plate:100x100", "--roi", "all"], "ROI must be one of"),
    (["--surface", "plate:100x100", "--section", "1,2,3"], "--section must be"),
])
def test_bad_input_exits_2_with_one_line(tmp_path, monkeypatch, capsys, args, words):
    csv = write_pass_csv(tmp_path / "pass.csv")
    empty = tmp_path / "empty.stl"
    empty.write_text("solid empty\nendsolid empty\n")
    args = [str(empty) if a == "EMPTY" else a for a in args]
    code, out, err = run_cli(monkeypatch, capsys, csv, *args, "-o", tmp_path / "out")
    assert code == 2
    assert err.startswith("coatsim: error:") and err.count("\n") == 1 and words in err


def test_missing_trajectory_and_dry_trajectory(tmp_path, monkeypatch, capsys):
    code, _, err = run_cli(monkeypatch, capsys, tmp_path / "none.csv", "--surface", "plate:100x100", "-o", tmp_path / "o")
    assert code == 2 and "none.csv: no such file" in err
    dry = write_pass_csv(tmp_path / "dry.csv", spray=False)
    code, _, err = run_cli(monkeypatch, capsys, dry, "--surface", "plate:200x100", "-o", tmp_path / "o")
    assert code == 2 and "never sprays" in err


def test_run_coat_returns_the_result(tmp_path):
    csv = write_pass_csv(tmp_path / "pass.csv")
    result, files = run_coat(csv, "plate:200x100", spacing=2.0, outdir=tmp_path / "o")
    assert [f.name for f in files] == ["thickness.ply", "coating.json", "heatmap.png", "section.png"]
    assert result.thickness_um.shape == (result.surface.n_vertices,)
    assert result.metrics["thickness_max_um"] == pytest.approx(6.383, rel=2e-3)


def test_cli_on_a_mesh_part_with_a_leaning_gun_and_shadows(tmp_path, monkeypatch, capsys):
    """A shelf over a floor as an OBJ file and a pass whose spray axis leans 15 deg (the CSV's
    ax, ay, az): shadows are on by default there, off on request; the mass balance is printed."""
    from spray_helpers import shelf_over_floor

    scene, _ = shelf_over_floor(10.0)
    mesh = tmp_path / "shelf.obj"
    trimesh.Trimesh(scene.vertices, scene.faces, process=False).export(mesh)
    lean = math.radians(15)
    csv = tmp_path / "lean.csv"
    log = line_log((6, -40, H0), (6, 40, H0), step_mm=2.0)
    make_log(log.t, log.position, (-math.sin(lean), 0.0, -math.cos(lean))).write_csv(csv)
    docs = {}
    for shadows in ("auto", "off"):
        code, out, err = run_cli(monkeypatch, capsys, csv, "--surface", str(mesh), "--spacing", "2", "--roi", "part",
                                 "--edge-band", "0", "--shadows", shadows, "--efficiency", "angle", "-o", tmp_path / shadows)
        assert code == 0, err
        assert "= deposited" in out and "missed" in out
        docs[shadows] = json.loads((tmp_path / shadows / "coating.json").read_text())
    auto, off = docs["auto"], docs["off"]
    assert auto["inputs"]["shadows_cast"] and auto["inputs"]["rays"] > 0 and not off["inputs"]["shadows_cast"]
    assert auto["inputs"]["efficiency"] == "angle"
    sprayed = auto["sprayed_volume_mm3"]
    assert auto["deposited_volume_mm3"] + auto["lost_volume_mm3"] + auto["missed_volume_mm3"] == pytest.approx(sprayed)
    assert abs(auto["missed_volume_mm3"]) < 0.02 * sprayed  # 2 mm vertices along the shadow's edge
    assert off["deposited_volume_mm3"] + off["lost_volume_mm3"] > 1.2 * sprayed  # the floor under the shelf counted twice
    assert auto["shadowed_volume_mm3"] > 0 == off["shadowed_volume_mm3"]
    assert auto["coated_fraction"] < off["coated_fraction"]


@pytest.mark.parametrize("args, words", [
    (["--shadows", "sometimes"], "--shadows must be one of auto, on, off"),
    (["--efficiency", "angle:100=1"], "spray angle must be between 0 and 90"),
    (["--efficiency", "table:missing.csv"], "missing.csv: no such file"),
    (["--tolerance-pct", "-1"], "--tolerance-pct: the thickness tolerance must be a percentage >= 0"),
])
def test_bad_coating_options_exit_2_with_one_line(tmp_path, monkeypatch, capsys, args, words):
    csv = write_pass_csv(tmp_path / "pass.csv")
    code, _, err = run_cli(monkeypatch, capsys, csv, "--surface", "plate:200x100", *args, "-o", tmp_path / "out")
    assert code == 2 and err.startswith("coatsim: error:") and err.count("\n") == 1 and words in err
