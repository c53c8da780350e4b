"""The files a point's scenario reads travel with it: found, renamed by content, digested."""

from __future__ import annotations

from pathlib import Path

import pytest

from coatsim.core.errors import InputError
from coatsim.run.scenario import as_dict, load_scenario
from coatsim.sweep.inputs import bundle, with_absolute_paths

ROOT = Path(__file__).resolve().parents[2]


def scenario_with_files(tmp_path: Path) -> dict:
    """The shipped user-program scenario, its gun on a footprint table and its robot an MJCF
    that includes a file and a mesh, everything in ``tmp_path``."""
    data = as_dict(load_scenario(ROOT / "scenarios" / "user_program.yaml").spec)
    (tmp_path / "progs").mkdir()
    for k, entry in enumerate(e for e in data["variants"] if isinstance(e, dict)):
        for j, name in enumerate(entry["program"]):
            text = (ROOT / "scenarios" / name).read_text(encoding="latin-1")
            (tmp_path / "progs" / f"p{k}{j}.as").write_text(text, encoding="latin-1")
            entry["program"][j] = f"progs/p{k}{j}.as"
    (tmp_path / "spot.csv").write_text("r_mm,rate\n0,1\n5,0.5\n10,0\n")
    data["gun"]["footprint"] = "table: spot.csv"
    cell = tmp_path / "cell"
    (cell / "parts" / "meshes").mkdir(parents=True)
    (cell / "arm.xml").write_text('<mujoco><compiler meshdir="parts/meshes"/><include file="parts/gun.xml"/></mujoco>')
    (cell / "parts" / "gun.xml").write_text('<mujocoinclude><asset><mesh file="nozzle.stl"/></asset></mujocoinclude>')
    (cell / "parts" / "meshes" / "nozzle.stl").write_bytes(b"solid n\nendsolid n\n")
    data["robot"]["model"] = "cell/arm.xml"
    return data


def test_every_file_is_found_renamed_and_digested(tmp_path):
    data = scenario_with_files(tmp_path)
    b = bundle(data, tmp_path)
    assert set(b.digests) >= {"gun.footprint", "robot.model"} and any(k.startswith("variants[") for k in b.digests)
    robot_files = sorted(n.split("/", 2)[2] for n in b.files if n.startswith("inputs/robot_"))
    assert robot_files == ["arm.xml", "parts/gun.xml", "parts/meshes/nozzle.stl"]
    assert b.scenario["robot"]["model"].endswith("/arm.xml") and b.scenario["robot"]["model"] in b.files
    assert b.scenario["gun"]["footprint"].startswith("table:inputs/footprint_")
    programs = [n for e in b.scenario["variants"] if isinstance(e, dict) for n in e["program"]]
    assert programs and all(n in b.files and n.startswith("inputs/program_") for n in programs)
    assert data["gun"]["footprint"] == "table: spot.csv"  # the input is not changed
    # editing a file the robot includes changes the robot's digest, and only it
    (tmp_path / "cell" / "parts" / "meshes" / "nozzle.stl").write_bytes(b"solid m\nendsolid m\n")
    again = bundle(data, tmp_path)
    assert again.digests["robot.model"] != b.digests["robot.model"]
    assert {k: v for k, v in again.digests.items() if k != "robot.model"} == \
        {k: v for k, v in b.digests.items() if k != "robot.model"}


def test_absolute_paths_for_the_kept_scenario(tmp_path):
    data = scenario_with_files(tmp_path)
    out = with_absolute_paths(data, tmp_path)
    assert out["gun"]["footprint"] == f"table:{(tmp_path / 'spot.csv').resolve()}"
    assert out["robot"]["model"] == str((tmp_path / "cell" / "arm.xml").resolve())


def test_a_missing_file_names_its_key(tmp_path):
    data = scenario_with_files(tmp_path)
    (tmp_path / "spot.csv").unlink()
    with pytest.raises(InputError, match=r"^gun\.footprint: .*spot\.csv: no such file$"):
        bundle(data, tmp_path)
