"""A 3-D curve sprayed with the gun along one fixed direction (program --spray-axis): one pass of
a surface program, its moves within σ of the curve set back the stand-off along the axis, the
axis the same at every pose, the program read back and run; planar input refused."""

from __future__ import annotations

import math

import numpy as np
import pytest

from coatsim.core.errors import InputError
from coatsim.geometry.space.curve import make_space_curve
from coatsim.geometry.space.polysegment_json import write_chain_json
from coatsim.geometry.space.segment import segment_space_curve
from coatsim.path.fixed_axis import fixed_axis_paths

TOL = 0.1
FRAME = np.array([700.0, 0.0, 200.0])  # the default workpiece frame: a translation


def helix(n: int = 3000) -> np.ndarray:
    t = np.linspace(0.0, 4 * math.pi, n)
    return np.column_stack((40 * np.cos(t), 40 * np.sin(t), 6 * t))


def write_csv(path, points: np.ndarray) -> None:
    np.savetxt(path, points, delimiter=",", header="x,y,z", comments="")


def moves_of(run_cli, tmp_path, spec: str, axis: str, *extra: str):
    from coatsim.cli.program import run_surface_program
    from coatsim.languages.registry import language
    from coatsim.path.build import ProgramOptions

    built = run_surface_program(spec, ProgramOptions(), tol=TOL if not spec.endswith(".json") else None, frame=None,
                                standoff_mm=None, lead_in_mm=None, lead_out_mm=None, roll_deg=0.0,
                                follow_tangent=False, angle_tol_deg=2.0, speed_on="tcp", tool_accel_mm_s2=None,
                                language=language("kawasaki-as"),
                                spray_axis=tuple(float(v) for v in axis.split(",")))
    return built, [m for m in built.plan.paths[0].segments if m.part == "curve"]


@pytest.mark.parametrize("axis", ["0,0,-1", "1,0,0", "0.6,0,-0.8"])
def test_the_moves_follow_the_curve_set_back_along_the_axis(tmp_path, run_cli, axis):
    write_csv(tmp_path / "helix.csv", helix())
    built, moves = moves_of(run_cli, tmp_path, str(tmp_path / "helix.csv"), axis)
    unit = np.array([float(v) for v in axis.split(",")])
    unit /= np.linalg.norm(unit)
    wanted = helix(20_000) - 100.0 * unit + FRAME  # the tool centre point: the stand-off back along the axis
    got = np.vstack([m.geometry.points(np.linspace(0.0, m.geometry.length, 40)) for m in moves])
    nearest = np.min(np.linalg.norm(got[:, None, :] - wanted[None, ::4, :], axis=2), axis=1)
    assert nearest.max() <= TOL + 0.02  # within σ of the curve (the dense reference sampled every 0.05 mm)
    assert sum(m.is_arc for m in moves) >= len(moves) - 2 and len(moves) <= 40
    for m in moves:  # the spray axis (the tool's z) is the one given, at every pose
        for pose in (m.start, m.end):
            assert np.allclose(pose.rotation[:, 2], unit, atol=1e-9)


def test_a_3d_polysegment_is_programmed_along_its_own_tolerance(tmp_path, run_cli):
    seg = segment_space_curve(make_space_curve(helix(), "helix", "no"), TOL)
    write_chain_json(tmp_path / "helix.json", seg.chain, TOL, {})
    from_curve = (write_csv(tmp_path / "helix.csv", helix()), moves_of(run_cli, tmp_path, str(tmp_path / "helix.csv"), "0,0,-1"))[1]
    from_json = moves_of(run_cli, tmp_path, str(tmp_path / "helix.json"), "0,0,-1")
    assert abs(len(from_json[1]) - len(from_curve[1])) <= 2


def test_the_program_reads_back_and_runs_on_the_arm(tmp_path, run_cli):
    write_csv(tmp_path / "helix.csv", helix())
    code, _, err = run_cli(["program", str(tmp_path / "helix.csv"), "--tol", "0.1", "--spray-axis", "0,0,-1",
                            "-o", str(tmp_path / "helix.as")])
    assert code == 0, err
    text = (tmp_path / "helix.as").read_text()
    assert "C1MOVE" in text and "C2MOVE" in text
    code, out, err = run_cli(["execute", str(tmp_path / "helix.as"), "-o", str(tmp_path / "run")])
    assert code == 0, err
    assert "0 stops" in out + err


@pytest.mark.parametrize("body, name", [("x,y\n0,0\n10,0\n20,5\n", "flat.csv"), (None, "builtin:circle")])
def test_a_planar_curve_with_a_spray_axis_is_refused_in_one_line(tmp_path, run_cli, body, name):
    spec = name if body is None else str(tmp_path / name)
    if body is not None:
        (tmp_path / name).write_text(body)
    code, _, err = run_cli(["program", spec, "--tol", "0.1", "--spray-axis", "0,0,-1"])
    assert code == 2 and len(err.strip().splitlines()) == 1 and "--spray-axis is for 3-D curves" in err


def test_a_spray_axis_of_zero_length_is_refused(tmp_path):
    write_csv(tmp_path / "helix.csv", helix())
    with pytest.raises(InputError, match="spray_axis must be three finite numbers"):
        fixed_axis_paths(str(tmp_path / "helix.csv"), (0.0, 0.0, 0.0), TOL)


def test_a_3d_curve_without_a_spray_axis_names_it(tmp_path, run_cli):
    write_csv(tmp_path / "helix.csv", helix())
    code, _, err = run_cli(["program", str(tmp_path / "helix.csv"), "--tol", "0.1"])
    assert code == 2 and "--spray-axis" in err


def test_a_3d_polysegment_is_known_by_its_format_anywhere_and_needs_a_tolerance(tmp_path, run_cli):
    """Its "format" may come after its segments (another writer's key order); without a usable
    tolerance_mm the program asks for --tol in one line (it was an internal error)."""
    import json

    seg = segment_space_curve(make_space_curve(helix(), "helix", "no"), TOL)
    write_chain_json(tmp_path / "helix.json", seg.chain, TOL, {})
    doc = json.loads((tmp_path / "helix.json").read_text())
    late = {k: v for k, v in doc.items() if k != "format"} | {"format": doc["format"]}
    (tmp_path / "late.json").write_text(json.dumps(late))
    code, _, err = run_cli(["program", str(tmp_path / "late.json"), "--spray-axis", "0,0,-1", "-o", str(tmp_path / "a.as")])
    assert code == 0, err
    for name, value in (("none.json", None), ("text.json", "0.1"), ("zero.json", 0)):
        bad = dict(doc)
        bad.pop("tolerance_mm") if value is None else bad.update(tolerance_mm=value)
        (tmp_path / name).write_text(json.dumps(bad))
        code, _, err = run_cli(["program", str(tmp_path / name), "--spray-axis", "0,0,-1"])
        assert code == 2 and len(err.strip().splitlines()) == 1 and "--tol" in err, err
