"""coatsim convert of a process path that lies in no plane: fitted in space (each arc in its own
plane), every new pose with the tool the original has there, poses added where the controller
would turn the tool further from the original's than the angle tolerance; measured on the
program written, in every language that turns the gun."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from scipy.spatial import cKDTree
from hypothesis import given, settings, strategies as st

from coatsim.core.errors import InputError
from coatsim.geometry.space.curve import make_space_curve
from coatsim.geometry.space.pose import exp_rotation, slerp
from coatsim.geometry.space.primitives import arc_through
from coatsim.geometry.space.rotations import matrix_to_oat
from coatsim.geometry.space.segment import segment_space_curve
from coatsim.languages.kawasaki_as.files import read_toolpath
from coatsim.languages.registry import language
from coatsim.path.arcs import move_rotations, sample_move
from coatsim.path.convert import ConvertOptions, conversion_summary, convert_program
from coatsim.path.process_path import ProcessPath, spray_runs
from coatsim.path.taught_orientation import orient_as_taught, rotation_angles, tool_angle
from coatsim.path.toolpath import CircularMove
from program_helpers import convert_as

TOL = 0.1
RADIUS, STANDOFF, CENTRE_X, CENTRE_Z = 150.0, 80.0, 700.0, 100.0


def _as_program(points: np.ndarray, rotations: np.ndarray, name: str) -> str:
    """An AS program spraying LMOVEs through the poses (one per point), taught as .TRANS."""
    trans = "\n".join(f"c[{i}] " + " ".join(f"{v:.4f}" for v in (*p, *matrix_to_oat(r)))
                      for i, (p, r) in enumerate(zip(points, rotations)))
    body = "\n".join(f"  LMOVE c[{i}]" for i in range(1, len(points)))
    return (f".PROGRAM {name}()\n  SPEED 200 MM/S ALWAYS\n  JMOVE c[0]\n  BREAK\n  SIGNAL 1\n{body}\n"
            f"  BREAK\n  SIGNAL -1\n.END\n.TRANS\n{trans}\n.END\n")


def _cylinder_tool(theta: np.ndarray, roll: str, centre: tuple[float, float] = (CENTRE_X, CENTRE_Z)
                   ) -> tuple[np.ndarray, np.ndarray]:
    """TCP points and tool rotations of a wavy pass over a cylinder parallel to the base y axis
    through ``centre`` (x, z), the gun on the normal at the stand-off; the tool's x along y
    (``fixed``) or turning with the wave (``turning``)."""
    points, rotations = [], []
    for t in theta:
        normal = np.array([math.sin(t), 0.0, math.cos(t)])
        surface = np.array([centre[0] + RADIUS * math.sin(t), 20.0 * math.sin(3 * t), centre[1] + RADIUS * math.cos(t)])
        z = -normal
        x = np.array([0.0, 1.0, 0.0]) if roll == "fixed" else np.array([math.cos(t), 0.3 * math.cos(3 * t), -math.sin(t)])
        x = x - (x @ z) * z
        x /= np.linalg.norm(x)
        points.append(surface + STANDOFF * normal)
        rotations.append(np.column_stack((x, np.cross(z, x), z)))
    return np.array(points), np.array(rotations)


def _cylinder(tmp_path: Path, n: int, roll: str) -> Path:
    points, rotations = _cylinder_tool(np.radians(np.linspace(-60.0, 60.0, n)), roll)
    path = tmp_path / f"cyl_{n}_{roll}.as"
    path.write_text(_as_program(points, rotations, "cyl"))
    return path


def _axis_error_deg(moves) -> float:
    """The largest angle between the tool axis along ``moves`` (as the controller turns it) and
    the cylinder's inward normal at the same place: an oracle independent of the fit."""
    worst = 0.0
    for m in moves:
        u = np.linspace(0.0, 1.0, 41)
        points, rotations = sample_move(m, u)[0], move_rotations(m, u)
        normal = points - np.array([CENTRE_X, 0.0, CENTRE_Z])
        normal[:, 1] = 0.0
        normal /= np.linalg.norm(normal, axis=1)[:, None]
        cos = np.clip(np.einsum("ij,ij->i", rotations[:, :, 2], -normal), -1.0, 1.0)
        worst = max(worst, float(np.degrees(np.arccos(cos)).max()))
    return worst


def test_a_helix_of_moves_becomes_arcs_each_in_its_own_plane(tmp_path):
    """Once refused ("not planar"): 199 LMOVEs along 3 turns of a helix become a dozen arcs in
    place, within the tolerance measured on the program written, the rest of the file kept."""
    i = np.arange(200)
    points = np.column_stack((700 + 50 * np.cos(i / 10), 50 * np.sin(i / 10), 300 + i / 5))
    src = tmp_path / "helix.as"
    src.write_text(_as_program(points, np.broadcast_to(np.diag([1.0, -1.0, -1.0]), (200, 3, 3)), "helix"))
    result = convert_as(src, ConvertOptions(TOL))
    (report,) = result.paths
    assert report.moves_before == 199 and report.moves_after <= 15 and report.n_arcs >= 10
    assert report.deviation_mm <= TOL and report.plane_deviation_mm is None and report.tool_angle_deg < 1e-6
    assert "in space, arcs each in its own plane" in conversion_summary(result)
    out = tmp_path / "arcs.as"
    out.write_text(result.text, encoding="latin-1", newline="")
    arcs = [m for m in read_toolpath(out).moves if isinstance(m, CircularMove)]
    normals = np.array([arc_through(m.start.translation_mm, m.via.translation_mm, m.end.translation_mm).normal
                        for m in arcs])
    assert len(arcs) == report.n_arcs and np.ptp(normals, axis=0).max() > 0.01  # not one plane's arcs
    assert result.text.startswith(".PROGRAM helix()\n  SPEED 200 MM/S ALWAYS\n  JMOVE c[0]\n  BREAK\n  SIGNAL 1\n")


@pytest.mark.parametrize("n,roll", [(60, "fixed"), (60, "turning"), (300, "turning")])
def test_a_gun_tilting_over_a_cylinder_keeps_its_tool(tmp_path, n, roll):
    """The gun on the normal of a cylinder turns 120 degrees along the pass (and about its own
    axis with ``turning``): the arc program has a third of the moves or fewer, the path within
    the tolerance and the tool within the angle tolerance of the original's, and its axis
    within that of the cylinder's normal by an oracle that knows only the cylinder."""
    src = _cylinder(tmp_path, n, roll)
    result = convert_as(src, ConvertOptions(TOL))
    (report,) = result.paths
    assert report.moves_after <= (n - 1) / 3 and report.deviation_mm <= TOL
    assert report.tool_angle_deg <= 2.0 and report.plane_deviation_mm is None
    out = tmp_path / "arcs.as"
    out.write_text(result.text, encoding="latin-1", newline="")
    new = read_toolpath(out)
    (run,) = spray_runs(new)
    assert _axis_error_deg([new.moves[i] for i in run]) <= 2.0 + 0.05


def test_a_tighter_angle_tolerance_gives_more_poses_and_holds(tmp_path):
    src = _cylinder(tmp_path, 60, "turning")
    loose, tight = (convert_as(src, ConvertOptions(TOL, angle_tol_deg=a)).paths[0] for a in (2.0, 0.2))
    assert tight.moves_after > loose.moves_after and tight.tool_angle_deg <= 0.2 < loose.tool_angle_deg


@pytest.mark.parametrize("name", ["kawasaki-as", "abb-rapid", "kuka-krl", "fanuc-tp", "urscript"])
def test_standalone_in_every_language_that_turns_the_gun(tmp_path, name):
    """Read back in its language (RAPID, KRL and URScript turn the tool from an arc's start to
    its end whatever the via's orientation; the vias are written on that turn), the program
    keeps the path and the tool."""
    src = _cylinder(tmp_path, 60, "turning")
    result = convert_program(src, ConvertOptions(TOL, standalone=True), language=language("kawasaki-as"),
                             target=language(name))
    (report,) = result.paths
    assert report.moves_after <= 20 and report.deviation_mm <= TOL and report.tool_angle_deg <= 2.0


def test_g_code_cannot_tilt_the_gun_and_says_so_in_one_line(tmp_path):
    src = _cylinder(tmp_path, 60, "fixed")
    with pytest.raises(InputError) as info:
        convert_program(src, ConvertOptions(TOL, standalone=True), language=language("kawasaki-as"),
                        target=language("gcode"))
    assert "no tool orientation" in str(info.value) and "\n" not in str(info.value)


def test_the_angle_tolerance_is_checked():
    with pytest.raises(InputError, match=r"angle_tol_deg 0.0: must be between 0 and 90 \(deg\)"):
        ConvertOptions(TOL, angle_tol_deg=0.0)


@settings(max_examples=25, deadline=None)
@given(amplitude=st.floats(0.05, 1.2), frequency=st.floats(0.5, 4.0), phase=st.floats(0.0, 6.3),
       axis=st.tuples(*[st.floats(-1.0, 1.0)] * 3).filter(lambda a: np.linalg.norm(a) > 0.2),
       angle_tol_deg=st.sampled_from([0.5, 2.0, 5.0]))
def test_the_tool_stays_within_the_angle_tolerance_of_any_smoothly_turning_original(amplitude, frequency, phase,
                                                                                     axis, angle_tol_deg):
    """Property: along a helix taught with a tool that wobbles about a random axis, the moves
    keep the tool within the angle tolerance of the original's everywhere, by a brute-force
    oracle (dense samples, the original's rotation at the nearest of its dense samples)."""
    s = np.linspace(0.0, 1.0, 121)
    points = np.column_stack((60 * np.cos(4 * s), 60 * np.sin(4 * s), 80 * s))
    axis = np.asarray(axis) / np.linalg.norm(axis)
    rotations = exp_rotation((amplitude * np.sin(2 * math.pi * frequency * s + phase))[:, None] * axis)
    path = ProcessPath((), points, rotations)
    segments = segment_space_curve(make_space_curve(points, "p", "no"), 0.2).chain.segments
    moves = orient_as_taught(segments, path, 0.2, math.radians(angle_tol_deg))
    assert tool_angle(moves, path, 0.2) <= math.radians(angle_tol_deg) + 1e-9
    dense_s = np.linspace(0.0, 1.0, 6001)  # the original, densely: positions and its controller's rotations
    k = np.clip(np.searchsorted(s, dense_s, side="right") - 1, 0, len(s) - 2)
    f = (dense_s - s[k]) / (s[k + 1] - s[k])
    dense_p = points[k] + f[:, None] * (points[k + 1] - points[k])
    dense_r = np.array([slerp(rotations[a], rotations[a + 1], b)[0] for a, b in zip(k, f)])
    tree = cKDTree(dense_p)
    length = float(np.linalg.norm(np.diff(points, axis=0), axis=1).sum())
    slack = amplitude * 2 * math.pi * frequency / length * 0.2  # the turn over a tolerance's mismatch of place
    for m in moves:
        u = np.linspace(0.0, 1.0, 33)
        here = m.point_tangent(u)[0]
        got = np.array([m.pose_at(float(v)).rotation for v in u]) if m.is_arc else slerp(m.start.rotation, m.end.rotation, u)
        want = dense_r[tree.query(here)[1]]
        assert rotation_angles(got, want).max() <= math.radians(angle_tol_deg) + slack + 1e-3


def test_the_twin_runs_both_and_the_gun_stays_on_the_normal(tmp_path):
    """End to end on the real stack (a cylinder placed where the arm reaches it): the taught
    polyline and its arc version run; along the arc version's sprayed run the twin's spray axis
    stays within the angle tolerance of the cylinder's normal, and the path it sprays is as long."""
    from coatsim.robot.cell import load_cell
    from coatsim.robot.execute import execute
    from coatsim.robot.kinematics import CellKinematics

    cell = load_cell()
    kin = CellKinematics(cell)
    points, rotations = _cylinder_tool(np.radians(np.linspace(-30.0, 30.0, 60)), "turning", (1000.0, 300.0))
    src = tmp_path / "cyl.as"
    src.write_text(_as_program(points, rotations, "cyl"))
    result = convert_as(src, ConvertOptions(TOL), kinematics=kin)
    out = tmp_path / "arcs.as"
    out.write_text(result.text, encoding="latin-1", newline="")
    runs = {name: execute(read_toolpath(path, kinematics=kin), cell) for name, path in (("user", src), ("arcs", out))}
    sprayed = {}
    for name, ex in runs.items():
        log = ex.log
        assert ex.metrics.max_path_error_mm < 0.5 and log.spray.any()
        sprayed[name] = float(np.linalg.norm(np.diff(log.position[log.spray], axis=0), axis=1).sum())
    log = runs["arcs"].log
    normal = log.position[log.spray] - np.array([1000.0, 0.0, 300.0])
    normal[:, 1] = 0.0
    normal /= np.linalg.norm(normal, axis=1)[:, None]
    cos = np.clip(np.einsum("ij,ij->i", log.axis[log.spray], -normal), -1.0, 1.0)
    assert np.degrees(np.arccos(cos)).max() <= 2.05
    assert sprayed["arcs"] == pytest.approx(sprayed["user"], rel=0.01) and result.paths[0].moves_after <= 6


def _rapid_module(points: np.ndarray, rotations: np.ndarray) -> str:
    """A RobotStudio-style module: quaternion robtargets, MoveL through them, the gun a named
    signal (``doGun``: no number in its name)."""
    from scipy.spatial.transform import Rotation

    targets = []
    for i, (p, r) in enumerate(zip(points, rotations)):
        x, y, z, w = Rotation.from_matrix(r).as_quat()
        targets.append(f"    CONST robtarget Target_{10 * i + 10}:=[[{p[0]:.3f},{p[1]:.3f},{p[2]:.3f}],"
                       f"[{w:.6f},{x:.6f},{y:.6f},{z:.6f}],[0,0,0,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];")
    moves = "\n".join(f"        MoveL Target_{10 * i + 10},v300,z1,tSpray\\WObj:=wobj0;" for i in range(1, len(points)))
    return ("MODULE Module1\n    PERS tooldata tSpray:=[TRUE,[[0,0,200],[1,0,0,0]],[1.5,[0,0,80],[1,0,0,0],0,0,0]];\n"
            + "\n".join(targets) + "\n    PROC main()\n        MoveJ Target_10,v1000,fine,tSpray\\WObj:=wobj0;\n"
            "        SetDO doGun,1;\n" + moves + "\n        SetDO doGun,0;\n    ENDPROC\nENDMODULE\n")


def test_a_rapid_module_with_a_named_gun_signal(tmp_path):
    """A RAPID pass over a cylinder whose gun is ``doGun``: without a number for it, convert says
    which statement switches it and how to number it; numbered (doGun=1), it is converted."""
    points, rotations = _cylinder_tool(np.radians(np.linspace(-60.0, 60.0, 60)), "turning")
    src = tmp_path / "Module1.mod"
    src.write_text(_rapid_module(points, rotations))
    rapid = language("abb-rapid")
    with pytest.raises(InputError) as info:
        convert_program(src, ConvertOptions(TOL, standalone=True), language=rapid)
    assert "it switches signal doGun (" in str(info.value) and "Module1.mod:" in str(info.value)
    result = convert_program(src, ConvertOptions(TOL, standalone=True), language=rapid, variables={"doGun": "1"})
    (report,) = result.paths
    assert report.moves_after <= 20 and report.deviation_mm <= TOL and report.tool_angle_deg <= 2.0
    assert "MoveC" in result.text


def test_g_code_keeps_the_spray_axis_and_says_the_roll_is_not_its_own(tmp_path):
    """A planar contour sprayed with the gun turned 90 degrees about its axis: G-code writes no
    roll (its reader gives the work frame's), so the angle measured is the spray axis's, 0, and
    a note says so; RAPID keeps the roll."""
    t = np.linspace(0.0, 2 * math.pi, 181)[:-1]
    points = np.column_stack((700 + 60 * np.cos(t), 30 * np.sin(t), np.full_like(t, 300.0)))
    rolled = np.diag([1.0, -1.0, -1.0]) @ np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    src = tmp_path / "rolled.as"
    src.write_text(_as_program(points, np.broadcast_to(rolled, (len(points), 3, 3)), "rolled"))
    for name, note in (("gcode", True), ("abb-rapid", False)):
        result = convert_program(src, ConvertOptions(TOL, standalone=True), language=language("kawasaki-as"),
                                 target=language(name))
        assert result.paths[0].tool_angle_deg < 1e-3 and result.paths[0].moves_after <= 20
        assert any("does not turn the gun: the angle given is the spray axis's" in n for n in result.notes) == note
