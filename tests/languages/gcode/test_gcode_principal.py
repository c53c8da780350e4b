"""End to end: ``coatsim segment --arc-planes principal`` fits a 3-D curve whose every arc the
G-code writer writes as one G2/G3 (G17, G18 or G19, no arc written as lines), and
``coatsim check-program`` reads the program back onto the fitted path; where G-code writes an arc
as lines, the program and the command's note name the option."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

from coatsim.geometry.space.chain import SpaceChain
from coatsim.geometry.space.polysegment_json import read_chain_json
from coatsim.geometry.space.primitives import Arc3
from coatsim.geometry.space.rotations import rot_y
from coatsim.geometry.space.pose import Pose
from coatsim.languages.gcode.language import GCODE
from coatsim.path.placement import PlacedMove, PlacedPath
from coatsim.path.build import ProgramOptions
from coatsim.path.plan import ProgramPlan
from coatsim.path.process import ProcessInfo
from coatsim.path.surface_program import SurfaceOptions, build_surface_program
from coatsim.path.surfacepaths import SurfacePass, SurfacePaths

from language_plans import distance_to_plan, sprayed_points
from test_gcode_writer import mini_read

CELL_MM = np.array([700.0, 0.0, 250.0])  # where the curve is put in front of the arm


def cylinder_pass() -> np.ndarray:
    """Around a cylinder whose axis is X (radius 60 mm): a circle in x = 20, arcs about X (G19)."""
    t = np.linspace(0.3, 2.8, 400)
    return np.column_stack((20 + 0 * t, 60 * np.cos(t), 60 * np.sin(t)))


def contour_z30() -> np.ndarray:
    """A closed planar contour (an ellipse with a bump) at z = 30 (G17)."""
    t = np.linspace(0, 2 * math.pi, 600)
    r = 40 + 6 * np.cos(3 * t)
    return np.column_stack((r * np.cos(t), 0.7 * r * np.sin(t), 30 + 0 * t))


def stepped() -> np.ndarray:
    """A quarter circle at z = 30 that runs on along +Y, then turns up in the plane x = 0 (G17 then G19)."""
    a = np.linspace(-math.pi / 2, 0, 100)
    y = np.linspace(0, 30, 60)[1:]
    b = np.linspace(0, math.pi / 2, 100)[1:]
    return np.vstack((np.column_stack((40 * np.cos(a) - 40, 40 * np.sin(a), 30 + 0 * a)),
                      np.column_stack((0 * y, y, 30 + 0 * y)),
                      np.column_stack((0 * b, 30 + 25 * np.sin(b), 55 - 25 * np.cos(b)))))


def gun_down_plan(chain, name: str) -> ProgramPlan:
    """The chain as one sprayed path in front of the arm, the gun pointing down (G-code's gun)."""
    down = lambda p: Pose(rot_y(math.pi), p)  # noqa: E731
    moved = [s.transformed(Pose(np.eye(3), CELL_MM)) for s in chain.segments]
    path = PlacedPath(tuple(PlacedMove(s, down(s.start), down(s.end)) for s in moved), np.array([0.0, 0.0, 1.0]),
                      100.0, 0.0, 0.0, float(sum(s.length for s in moved)))
    return ProgramPlan(name, (path,), 200.0, 0.5, False, 50.0, 1, Pose.identity(), ProcessInfo())


@pytest.mark.parametrize(("name", "curve", "planes"), [("cylinder", cylinder_pass, {"G19"}),
                                                      ("contour", contour_z30, {"G17"}),
                                                      ("stepped", stepped, {"G17", "G19"})])
def test_principal_arcs_are_written_as_g2_g3_and_read_back(tmp_path, run_cli, name, curve, planes):
    points = tmp_path / f"{name}.csv"
    np.savetxt(points, curve(), delimiter=",")
    fitted = tmp_path / f"{name}.json"
    code, stdout, stderr = run_cli(["segment", str(points), "--tol", "0.1", "--arc-planes", "principal",
                                    "-o", str(fitted)])
    assert code == 0, stderr
    chain = read_chain_json(fitted)
    assert chain.n_arcs > 0
    plan = gun_down_plan(chain, name.upper())
    text = GCODE.write(plan)
    assert "outside G17/G18/G19" not in text
    arcs = [line for line in text.splitlines() if re.search(r"\bG[23]\b", line.split("(")[0])]
    half_turns = sum(math.ceil(s.sweep / math.pi - 1e-12) for s in chain.segments if isinstance(s, Arc3))
    assert len(arcs) == half_turns  # every arc one G2/G3 a half turn at most: none became lines
    written = {p for p in ("G17", "G18", "G19") if p in text.replace("G21 G90 G94 G17", "")}
    assert written | ({"G17"} if "G17" in planes else set()) == planes
    moves = mini_read(text)
    assert distance_to_plan(sprayed_points([p for p, on in moves if on]), plan.paths) < 1e-3
    program = tmp_path / f"{name}.ngc"
    program.write_text(text)
    code, stdout, stderr = run_cli(["check-program", str(program)])
    assert code == 0, stderr
    assert f"{half_turns} arc" in stdout and "no problems found" in stdout
    sprayed_mm = float(re.search(r"sprayed: .* moves?, ([0-9.]+) mm", stdout).group(1))
    assert sprayed_mm == pytest.approx(sum(s.length for s in chain.segments), abs=2e-3)


def test_the_notes_on_arcs_written_as_lines_name_the_option():
    """A pass whose arcs leave the principal planes (a helix turn, the gun kept vertical): G-code
    writes them as lines, and both the program's comment and the command's note say that a curve
    segmented with arc_planes principal has none."""
    t = np.linspace(0.0, 1.5 * math.pi, 300)
    points = np.column_stack((40 * np.cos(t), 40 * np.sin(t), 10 * t))
    up = np.tile([0.0, 0.0, 1.0], (len(t), 1))
    paths = SurfacePaths("helix.json", (SurfacePass(points, up, False, np.empty((0, 3)), np.empty((0, 3))),),
                         100.0, None, None)
    program = build_surface_program(paths, ProgramOptions(), SurfaceOptions(), GCODE)
    assert any("circular moves only in principal planes" in n and "arc_planes 'principal'" in n
               for n in program.notes)
    assert not re.search(r"\bG[23]\b", program.text)
    slant = Arc3(points[0], points[100], [0.0, 0.0, 0.0], [0.0, 0.0, 1.0], 40.0, 0.5 * math.pi)
    slant = slant.transformed(Pose(rot_y(0.3), np.zeros(3)))
    text = GCODE.write(gun_down_plan(SpaceChain((slant,)), "SLANT"))
    assert "arc outside G17/G18/G19 as" in text and "arc_planes principal has none" in text
