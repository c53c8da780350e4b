"""The twin in 3-D: the tool tilts with the surface as executed, the spray spot's speed against its
closed form, IK with orientation, reachability reasons, configuration flips and collisions."""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from coatsim.core.errors import ExecutionError
from coatsim.geometry.space.pose import Pose
from coatsim.geometry.space.xyzoat import pose_from_xyzoat
from coatsim.languages.kawasaki_as.files import read_toolpath
from coatsim.languages.registry import language
from coatsim.path.build import ProgramOptions
from coatsim.path.surface_program import SurfaceOptions, build_surface_program
from coatsim.path.surfacepaths import read_surfacepaths
from coatsim.robot.cell import load_cell
from coatsim.robot.collisions import Collision, convex_pieces, load_part, with_part
from coatsim.robot.configuration import ConfigurationFlip, branch_values, check_no_flip, kept_goal, wrist_over
from coatsim.robot.execute import execute
from coatsim.robot.ik import Tracker
from coatsim.path.toolpath import JointMove, LinearMove, MotionSettings, ToolPath
from coatsim.robot.motion_metrics import spot_speed
from coatsim.robot.reachability import diagnose, reachable_fraction
from coatsim.robot.turns import turns_near, within_turns
from surface_parts import cylinder, saddle, torus_section, write_surfacepaths

AS = language("kawasaki-as")
STANDOFF = 100.0


@pytest.fixture(scope="module")
def cell():
    return load_cell()


def program(folder: Path, part, speed: float = 300.0, pose=None, **surface) -> Path:
    source = write_surfacepaths(folder, part, pose=pose, points_per_pass=250)[0]
    prog = build_surface_program(read_surfacepaths(source), ProgramOptions(speed_mm_s=speed), SurfaceOptions(**surface), AS)
    path = folder / f"{part.name}.as"
    path.write_text(prog.text, encoding="ascii")
    return path


def test_the_orientation_bound_holds_along_a_torus_section_as_executed(cell, tmp_path):
    """The simulated spray axis against the torus's own normal at the point the spot is over, on
    every sprayed row: within the 2 degree tolerance (the fit's bound, the roll's share, the
    controller's orientation zone and the servo together)."""
    part = torus_section()
    result = execute(read_toolpath(program(tmp_path, part, roll="follow")), cell)
    log = result.log
    rows = log.spray
    x = log.position[rows] - np.array(part.pose[:3]) + [150.0, 0.0, 0.0]  # torus frame: ring about z
    ring = np.column_stack((x[:, :2] / np.linalg.norm(x[:, :2], axis=1)[:, None] * 150.0, np.zeros(len(x))))
    normal = (x - ring) / np.linalg.norm(x - ring, axis=1)[:, None]
    angle = np.degrees(np.arccos(np.clip(np.einsum("ij,ij->i", log.axis[rows], -normal), -1.0, 1.0)))
    assert rows.sum() > 500 and angle.max() <= 2.0
    assert result.metrics.stops == 0


@pytest.mark.parametrize("concave", [False, True])
def test_spot_speed_on_a_cylinder_is_the_closed_form(cell, tmp_path, concave):
    """At a constant tool speed v on the normal at stand-off h the spot moves at v R / (R + h) over
    a convex cylinder and v R / (R - h) inside a concave one."""
    radius = 250.0 if concave else 60.0
    result = execute(read_toolpath(program(tmp_path, cylinder(radius, concave=concave))), cell)
    expected = radius / (radius - STANDOFF) if concave else radius / (radius + STANDOFF)
    log, trace = result.log, result.trace
    steady = log.spray & (np.abs(log.speed - 300.0) < 0.5)  # at the programmed speed, not ramping
    assert steady.sum() > 300
    assert np.median(log.trace_speed[steady] / log.speed[steady]) == pytest.approx(expected, rel=2e-3)
    assert trace.standoff_mm == STANDOFF and trace.min_ratio == pytest.approx(expected, rel=0.02)


def test_spot_speed_of_a_tool_turning_about_a_centre():
    t = np.linspace(0.0, 1.0, 501)
    phi = 0.5 * t  # rad: the tool on a circle of radius 160 about the origin, axis pointing at it
    position = 160.0 * np.column_stack((np.sin(phi), np.zeros_like(t), np.cos(phi)))
    axis = -position / 160.0
    assert np.allclose(spot_speed(t, position, axis, 100.0), 0.5 * 60.0, rtol=1e-4)
    assert np.allclose(spot_speed(t, position, axis, 0.0), 0.5 * 160.0, rtol=1e-4)


def test_speed_on_the_trace_keeps_the_spot_at_the_programmed_speed(cell, tmp_path):
    result = execute(read_toolpath(program(tmp_path, cylinder(), speed=150.0, speed_on="trace")), cell)
    assert result.trace.target_mm_s == 150.0
    assert 0.97 <= result.trace.min_ratio <= result.trace.max_ratio <= 1.1
    assert result.metrics.stops == 0


def test_ik_with_orientation_reaches_poses_of_known_joint_solutions(cell):
    rng = np.random.default_rng(7)
    tracker = Tracker(cell)
    data_tcp = []
    for _ in range(12):
        q = cell.home + rng.uniform(-0.6, 0.6, 6)
        q[4] = math.copysign(max(abs(q[4]), 0.4), q[4])  # away from the wrist singularity
        p, r = cell.forward(tracker._single, q)
        start = q + rng.uniform(-0.15, 0.15, 6)
        solved = tracker.solve_pose(start, p, r, "known")
        p2, r2 = cell.forward(tracker._single, solved)
        assert np.linalg.norm(p2 - p) < 1e-3 and Pose(r, p).angle_to(Pose(r2, p2)) < 1e-5
        assert np.abs(solved - q).max() < 1e-4  # the same branch, so the same joints
        data_tcp.append(p)
    assert np.ptp(np.array(data_tcp), axis=0).min() > 50.0  # the poses spread over the workspace


def test_unreachable_poses_are_counted_with_their_reason(cell, tmp_path):
    path = program(tmp_path, saddle(), pose=(1600.0, 0.0, 300.0, 0.0, 0.0, 0.0))
    toolpath = read_toolpath(path)
    reach = reachable_fraction(toolpath, cell)
    assert reach.checked > 10 and reach.fraction < 0.5
    assert all("out of reach" in reason for _, reason in reach.unreachable)
    with pytest.raises(ExecutionError, match=r"line \d+ \(joint move\): cannot reach pose .*: out of reach"):
        execute(toolpath, cell)
    assert reachable_fraction(read_toolpath(program(tmp_path, saddle())), cell).fraction == 1.0


def test_a_joint_move_turns_a_joint_the_other_way_round_where_the_pose_needs_it(cell):
    """From JT1 at 175 deg to a pose the arm reaches with JT1 at 185 deg, outside its range of
    ±180: the search inside the range stalls at the limit; the same arm pose with JT1 at -175 deg
    is inside it, and a joint move goes there the other way round. No such turn for JT2, whose
    range is narrower than a turn: that pose stays unreachable."""
    tracker = Tracker(cell)
    goal = cell.home.copy()
    goal[0] = math.radians(185.0)
    p, r = cell.forward(tracker._single, goal)
    start = cell.home.copy()
    start[0] = math.radians(175.0)
    q = tracker.solve_pose(start, p, r, "joint move")
    assert math.degrees(q[0]) == pytest.approx(-175.0, abs=1e-3) and np.allclose(q[1:], goal[1:], atol=1e-5)
    assert np.all(q >= cell.q_min) and np.all(q <= cell.q_max)
    goal = cell.home.copy()
    goal[1] = cell.q_max[1] + math.radians(5.0)
    p, r = cell.forward(tracker._single, goal)
    with pytest.raises(ExecutionError, match="joint move: cannot reach"):
        tracker.solve_pose(cell.home, p, r, "joint move")


@settings(max_examples=40, deadline=None)
@given(st.lists(st.floats(0.0, 1.0), min_size=6, max_size=6))
def test_the_wrist_turned_over_is_the_same_arm_pose(cell, share):
    q = cell.q_min + np.array(share) * (cell.q_max - cell.q_min)
    data = Tracker(cell)._single
    p0, r0 = cell.forward(data, q)
    p1, r1 = cell.forward(data, wrist_over(q))
    assert np.allclose(p0, p1, atol=1e-9) and np.allclose(r0, r1, atol=1e-12)


def test_a_joint_move_keeps_the_configuration_and_turns_each_joint_the_shortest_way(cell):
    """From home (JT4 0, JT5 +55, JT6 0 deg) to a pose that the IK, searching from home, reaches with
    JT4 at -195.7 and JT6 at 274.7 deg (5 deg from JT4's limit: on a bracket the first pass then ran
    JT4 out of range at once): a controller's joint move keeps the wrist side and turns each joint
    the shortest way, to JT4 164.3 and JT6 -85.3 deg. The goal the other wrist side gives comes
    back on home's side too; the twin's joint move goes there."""
    tracker = Tracker(cell)
    wanted = np.radians([-13.8, -13.0, 86.1, 164.3, 56.2, -85.3])
    p, r = cell.forward(tracker._single, wanted)
    searched = tracker.solve_pose(cell.home, p, r, "joint move")
    assert math.degrees(searched[3]) == pytest.approx(-195.7, abs=0.1)  # what the search alone gives
    assert np.allclose(kept_goal(cell, cell.home, searched), wanted, atol=1e-4)
    assert np.allclose(kept_goal(cell, cell.home, wrist_over(wanted) - [0, 0, 0, 2 * math.pi, 0, 0]), wanted, atol=1e-4)
    below = cell.home.copy()
    below[4] = -below[4]  # from the other wrist side, the goal stays on that side
    assert math.degrees(kept_goal(cell, below, searched)[4]) == pytest.approx(-56.2, abs=1e-3)
    move = MotionSettings(200.0, 1.0, True, True)
    start, end = Pose(r, p), Pose(r, p - 30.0 * r[:, 2])
    run = execute(ToolPath("turns", (JointMove(None, start, move, False, 1), LinearMove(start, end, move, False, 2))), cell)
    jt4, jt5, jt6 = np.degrees(run.log.q[-1, 3:])  # 30 mm on from the goal: near it on the same turn and side
    assert 150.0 < jt4 < 180.0 and jt5 > 0.0 and -100.0 < jt6 < -70.0


def test_whole_turns_of_a_joint():
    q_min, q_max = np.radians([-180.0, -200.0]), np.radians([180.0, 200.0])
    q = np.radians([1261.6, -205.0])
    assert np.degrees(turns_near(q, np.radians([170.0, 0.0]))) == pytest.approx([181.6, 155.0])
    assert np.degrees(within_turns(q, np.zeros(2), q_min, q_max)) == pytest.approx([-178.4, 155.0])
    assert np.degrees(within_turns(np.radians([10.0, 170.0]), np.radians([0.0, -170.0]), q_min, q_max)) \
        == pytest.approx([10.0, -190.0])  # two equivalents inside: the one nearest the reference
    assert within_turns(np.radians([0.0, 10.0]), np.zeros(2), q_min, np.radians([180.0, -170.0])) is None


def test_a_wrist_joint_driven_out_of_range_near_the_wrist_singularity_is_named_as_the_singularity(cell):
    """Near JT5 = 0 the IK turns JT4 and JT6 fast to hold the orientation (seen on a scanned part
    where JT5 fell to 3.7 deg and JT4 raced from 46 to 200 deg): the reason names the singularity,
    then the range; the same range reached with the wrist well bent stays a joint limit."""
    tracker = Tracker(cell)
    for jt5_deg, expected in ((3.0, r"^near a wrist singularity \(JT5 at 3\.0 deg.*\): JT4 would have to be at 21\d\.\d deg"),
                              (40.0, r"^joint limit: JT4 would have to be at 21\d\.\d deg")):
        target = cell.home.copy()
        target[3], target[4] = math.radians(212.0), math.radians(jt5_deg)
        p, r = cell.forward(tracker._single, target)
        near = target.copy()
        near[3] = math.radians(195.0)  # inside the range, short of the pose
        assert re.match(expected, diagnose(tracker, near, p, r))


def test_a_flip_inside_a_pass_is_reported(cell, tmp_path):
    """The cylinder's passes tilt the gun 40 degrees away from the robot on its near side: the wrist
    passes JT5 = 0 inside the pass."""
    path = program(tmp_path, cylinder(), pose=(900.0, 0.0, 300.0, 0.0, 0.0, 0.0))
    with pytest.raises(ConfigurationFlip) as info:
        execute(read_toolpath(path), cell)
    assert info.value.branch == "wrist" and info.value.exit_code == 3
    assert "flips its wrist configuration inside a sprayed pass" in str(info.value) and "line" in info.value.step


def test_flip_check_looks_only_inside_sprayed_passes(cell):
    q = np.tile(cell.home, (5, 1))
    q[:, 4] = [0.3, 0.1, 0.0, -0.1, -0.3]  # JT5 through zero: the wrist flips
    assert np.sign(branch_values(cell, q)[[0, -1], 2]).tolist() == [1.0, -1.0]
    check_no_flip(cell, q, np.array([True, True, False, False, False]), str)  # flips with the gun off
    with pytest.raises(ConfigurationFlip, match="^3: the arm flips its wrist"):
        check_no_flip(cell, q, np.ones(5, dtype=bool), str)
    q[:, 4] = [0.3, 0.1, 0.0, 0.1, 0.3]  # to the singularity and back: no flip
    check_no_flip(cell, q, np.ones(5, dtype=bool), str)


def test_a_gun_driven_into_the_part_stops_naming_the_step(cell, tmp_path, run_cli):
    source, mesh = write_surfacepaths(tmp_path, saddle(), points_per_pass=200)
    prog = tmp_path / "low.as"
    code, _, err = run_cli(["program", str(source), "--standoff", "10", "-o", str(prog)])
    assert code == 0, err
    raised = pose_from_xyzoat((900.0, 0.0, 330.0, 0.0, 0.0, 0.0))  # the part 30 mm higher: the TCP 20 mm inside
    with pytest.raises(Collision) as info:
        execute(read_toolpath(prog), with_part(cell, load_part(mesh, raised)))
    assert info.value.bodies == ("gun", "part") and info.value.exit_code == 3
    line = int(info.value.step.split("line ")[1].split()[0])
    assert prog.read_text().splitlines()[line - 1].split()[0] in ("LMOVE", "C1MOVE", "C2MOVE")
    code, out, err = run_cli(["execute", str(prog), "--part", str(mesh), "--part-pose", "900,0,330,0,0,0",
                              "-o", str(tmp_path / "out")])
    assert code == 3 and err.count("\n") == 1 and "the gun touches the part" in err and f"line {line} " in err
    code, out, err = run_cli(["execute", str(prog), "--part", str(mesh), "--part-pose", "900,0,300,0,0,0",
                              "-o", str(tmp_path / "out2")])
    assert code == 0, err  # at its stand-off the same program clears the part
    code, out, err = run_cli(["execute", str(prog), "--part", str(mesh), "-o", str(tmp_path / "out3")])
    assert code == 0, err  # placed where the program's passes were planned, as the record says
    assert "note: the part placed at 900,0,300,0,0,0 (the frame the program's passes were planned in" in out


def test_the_part_is_covered_by_convex_slabs(tmp_path):
    mesh = write_surfacepaths(tmp_path, saddle())[1]
    part = load_part(mesh, Pose.identity())
    pieces = convex_pieces(part)
    assert 40 <= len(pieces) <= 200
    covered = np.vstack(pieces)
    assert np.isin(part.vertices.round(9), covered.round(9)).all(axis=1).all()  # every vertex in some slab


def test_a_part_takes_the_place_of_the_cells_own_workpiece(cell, tmp_path):
    """The part replaces the body holding the site ``workpiece`` (the shipped cell's plate, 190
    to 200 mm up, on the table whose top is at 190): in a bowl sunk through the plate (its floor
    at 100 mm) the gun runs with its tip (the tool point) at 196 mm, where the plate was (with it,
    "the gun touches the plate") and above the table, which stays."""
    import trimesh

    sphere = trimesh.creation.icosphere(subdivisions=4, radius=200.0)
    cap = sphere.vertices[:, 2] < -150.0
    bowl = trimesh.Trimesh(sphere.vertices, sphere.faces[cap[sphere.faces].all(axis=1)])
    bowl.remove_unreferenced_vertices()
    bowl.invert()  # its inside faces up
    mesh = tmp_path / "bowl.stl"
    bowl.export(mesh)
    placed = with_part(cell, load_part(mesh, pose_from_xyzoat((800.0, 0.0, 300.0, 0.0, 0.0, 0.0))))
    names = {placed.model.body(b).name for b in range(placed.model.nbody)}
    assert "part" in names and "table" in names and "plate" not in names
    assert {cell.model.body(b).name for b in range(cell.model.nbody)} - names == {"plate"}
    program = tmp_path / "inside.as"  # the gun's tip 96 mm over the bowl's floor, where the plate was
    program.write_text(".PROGRAM inside()\n  SPEED 100 MM/S ALWAYS\n  JMOVE TRANS(800, -20, 400, 0, 180, 0)\n"
                       "  LMOVE TRANS(800, -20, 196, 0, 180, 0)\n  LMOVE TRANS(800, 20, 196, 0, 180, 0)\n.END\n")
    execute(read_toolpath(program), placed)
    with pytest.raises(Collision) as info:
        execute(read_toolpath(program), with_part(cell, load_part(mesh, pose_from_xyzoat((800.0, 0.0, 400.0, 0.0, 0.0,
                                                                                         0.0)))))
    assert info.value.bodies[1] == "part"  # raised 100 mm, the floor is above the tool


def _pipe(tmp_path: Path, scale: float, name: str) -> Path:
    """A pipe of radius 50.8 mm and length 152.4 mm along x, its axis through its frame's origin,
    written in file units of ``scale`` mm."""
    import trimesh

    pipe = trimesh.creation.cylinder(radius=50.8 / scale, height=152.4 / scale, sections=64)
    pipe.apply_transform(trimesh.transformations.rotation_matrix(math.pi / 2, [0, 1, 0]))
    path = tmp_path / name
    pipe.export(path)
    return path


@pytest.mark.parametrize("scale, units", [(1.0, "mm"), (25.4, "in"), (1000.0, "m"), (1000.0, "auto")])
def test_a_part_is_read_in_its_units(tmp_path, scale, units):
    """A part in inches or metres is put in the cell at its size in mm (read as its numbers, a
    part in metres was a thousandth of its size, and no contact with it could be found)."""
    part = load_part(_pipe(tmp_path, scale, "pipe.stl"), Pose.identity(), units)
    assert np.allclose(np.ptp(part.vertices, axis=0), [152.4, 101.6, 101.6], rtol=1e-3)
    assert any("metres" in note for note in part.notes) is (units == "auto")


def test_a_part_sunk_into_the_table_is_told(cell, tmp_path, run_cli):
    """The pipe's axis on the table's top (190 mm, the top 40 mm thick): the part overlaps the
    table through its whole thickness, and execute says so before it runs; 110 mm higher,
    nothing is said."""
    from coatsim.robot.collisions import part_overlaps

    mesh = _pipe(tmp_path, 25.4, "pipe_in.stl")
    sunk = part_overlaps(with_part(cell, load_part(mesh, pose_from_xyzoat((700.0, 0.0, 190.0, 0, 0, 0)), "in")))
    assert len(sunk) == 1 and "the part overlaps the cell's table (40.0 mm deep)" in sunk[0]
    assert part_overlaps(with_part(cell, load_part(mesh, pose_from_xyzoat((700.0, 0.0, 300.0, 0, 0, 0)), "in"))) == ()
    program = tmp_path / "above.as"
    program.write_text(".PROGRAM above()\n  SPEED 100 MM/S ALWAYS\n  JMOVE TRANS(700, -20, 450, 0, 180, 0)\n"
                       "  LMOVE TRANS(700, 20, 450, 0, 180, 0)\n.END\n")
    code, out, err = run_cli(["execute", str(program), "--part", str(mesh), "--part-units", "in",
                              "--part-pose", "700,0,190,0,0,0", "-o", str(tmp_path / "run")])
    assert code == 0, err
    assert "warning: the part overlaps the cell's table (40.0 mm deep)" in err
    code, _, err = run_cli(["execute", str(program), "--part-units", "in", "-o", str(tmp_path / "run2")])
    assert code == 2 and "--part-units reads the part given with --part" in err
