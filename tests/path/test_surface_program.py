"""Programs of 3-D surface passes: reading surfacepaths, the fitted and polyline variants, the roll
rules, speeds on the trace, lines for a language without arcs in any plane, travel clearance, and
the O-A-T of every written pose read back."""

from __future__ import annotations

import json
import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from coatsim.core.errors import InputError
from coatsim.geometry.space.orient import slerp_axes
from coatsim.geometry.space.pose import Pose, log_rotation, slerp
from coatsim.geometry.space.primitives import Arc3, Line3
from coatsim.geometry.space.rotations import oat_to_matrix, rot_y, rot_z
from coatsim.languages.registry import language
from coatsim.path.build import ProgramOptions
from coatsim.path.language import ReadOptions
from coatsim.path.leads import lead_move
from coatsim.path.expressible import expressible
from coatsim.path.placement import PlacedMove, PlacedPath
from coatsim.path.roll import Oriented
from coatsim.path import surface_program
from coatsim.path.build import VARIANTS
from coatsim.path.pass_fits import fit_passes, pass_tcp
from coatsim.path.surface_program import (SurfaceOptions, _axis_notes, build_surface_program, oriented_polyline,
                                          surface_fit_settings)
from coatsim.path.surfacepaths import SurfacePass, SurfacePaths, read_surfacepaths
from coatsim.path.travel import travel_clearances
from coatsim.path.unfold import MIN_ADVANCE
from surface_parts import cylinder, saddle, torus_section, write_surfacepaths

AS = language("kawasaki-as")


@pytest.fixture(scope="module")
def torus(tmp_path_factory) -> Path:
    return write_surfacepaths(tmp_path_factory.mktemp("torus"), torus_section(), points_per_pass=300)[0]


def build(path: Path, variant: str = "polysegment", **surface) -> object:
    return build_surface_program(read_surfacepaths(path), ProgramOptions(variant=variant), SurfaceOptions(**surface), AS)


def read_back(text: str, tmp_path: Path):
    path = tmp_path / "p.as"
    path.write_text(text, encoding="ascii")
    return AS.read([path], ReadOptions())


def test_every_pose_round_trips_through_its_oat(torus, tmp_path):
    """The controller's poses read back from the text are the plan's poses (6 decimals of degree)."""
    prog = build(torus, roll="follow")
    planned = [p for path in prog.plan.paths for m in path.segments
               for p in ((m.via_pose, m.end) if m.is_arc else (m.end,))]
    toolpath = read_back(prog.text, tmp_path)
    read = [p for m in toolpath.moves if m.kind != "joint" for p in ((m.via, m.end) if m.kind == "arc" else (m.end,))]
    for pose in planned:  # every planned pose is among the poses read (travel moves come in between)
        best = min(read, key=lambda r: float(np.abs(r.translation_mm - pose.translation_mm).max()))
        assert np.abs(best.translation_mm - pose.translation_mm).max() < 1e-7
        assert pose.angle_to(best) < 1e-7
    text = prog.text.split(".TRANS\n")[1].splitlines()[:-1]
    for line in text:
        o, a, t = (float(v) for v in line.split()[4:7])
        r = oat_to_matrix(o, a, t)
        assert np.abs(r.T @ r - np.eye(3)).max() < 1e-12


def test_fitted_passes_are_arcs_in_3d_and_the_polylines_lines(torus):
    fitted, stop, blend = (build(torus, v) for v in ("polysegment", "polyline-stop", "polyline-blend"))
    assert all(n_lines == 0 and n_arcs >= 1 for n_lines, n_arcs in fitted.counts)  # latitude circles: arcs
    assert all(n_arcs == 0 and n_lines > 10 for n_lines, n_arcs in stop.counts)
    assert stop.counts == blend.counts and "CP OFF" in stop.text and "CP ON" in blend.text
    assert fitted.text.count("C1MOVE") >= 3 and "C1MOVE" not in stop.text
    assert fitted.max_axis_error_rad <= math.radians(2.0)
    assert len(fitted.plan.paths) == 3 and fitted.plan.process.contour_order == (1, 2, 3)


def test_the_same_passes_give_the_same_bytes(torus):
    assert build(torus).text == build(torus).text


@pytest.mark.parametrize("rule", ["fixed", "follow"])
def test_roll_rules(torus, rule):
    """fixed: consecutive poses differ by the smallest turn of the axis (no spin about it; across
    an arc, a spin of the second order of its turn, as carrying the tool through the via's axis
    gives); follow: the tool's x lies along the line of travel at every pose a move starts or
    ends at. An arc's via pose is halfway along the turn from its start to its end pose."""
    prog = build(torus, roll=rule)
    for path in prog.plan.paths:
        curve = [m for m in path.segments if m.part == "curve"]
        for m in curve:
            if m.is_arc:
                np.testing.assert_allclose(m.via_pose.rotation, slerp(m.start.rotation, m.end.rotation, 0.5)[0],
                                           atol=1e-12)
            if rule == "fixed":
                rel = m.start.rotation.T @ m.end.rotation  # in the tool frame: a turn about an axis across z
                axis = np.array([rel[2, 1] - rel[1, 2], rel[0, 2] - rel[2, 0], rel[1, 0] - rel[0, 1]]) / 2
                turn = float(np.linalg.norm(axis))
                assert abs(axis[2]) <= (turn ** 2 / 4 if m.is_arc else 1e-9 * max(1.0, turn))
            else:
                tangents = [m.geometry.start_tangent, m.geometry.end_tangent]
                for pose, t in zip((m.start, m.end), tangents):
                    across = t - (t @ pose.rotation[:, 2]) * pose.rotation[:, 2]
                    assert abs(abs(float(pose.rotation[:, 0] @ across)) / np.linalg.norm(across) - 1.0) < 1e-9


def test_speed_on_the_trace_moves_the_spot_at_the_programmed_speed(tmp_path):
    """Each move's own speed times the spot's path length over the TCP's is the trace speed; on
    the cylinder (R 60, stand-off 100) that is v (R + h) / R."""
    path = write_surfacepaths(tmp_path, cylinder(), points_per_pass=200)[0]
    prog = build_surface_program(read_surfacepaths(path), ProgramOptions(speed_mm_s=150.0),
                                 SurfaceOptions(speed_on="trace"), AS)
    assert prog.plan.process.speed_on == "trace" and "speed_on=trace" in prog.text
    for p in prog.plan.paths:
        for m in p.segments:
            assert m.speed_mm_s == pytest.approx(150.0 * 160.0 / 60.0, rel=1e-3)
    toolpath = read_back(prog.text, tmp_path)
    sprayed = [m.settings.speed_mm_s for m in toolpath.moves if m.spray]
    assert min(sprayed) == pytest.approx(400.0, rel=1e-3) and toolpath.process.speed_on == "trace"


def test_arcs_become_lines_within_the_tolerance_for_a_language_without_them(torus):
    prog = build(torus)
    moves = [m for p in prog.plan.paths for m in p.segments]
    lines, changed = expressible(moves, "none", 0.05)
    assert changed == sum(m.is_arc for m in moves) and not any(m.is_arc for m in lines)
    arcs = [m for m in moves if m.is_arc]
    for arc in arcs:
        pts = arc.geometry.points(np.linspace(0.0, arc.length, 400))
        chords = [m for m in lines if m.part == arc.part]
        d = np.min([m.geometry.distance(pts) for m in chords], axis=0)
        assert d.max() <= 0.05 + 1e-9
    assert expressible(moves, "any", 0.05) == (moves, 0)
    flat = [m for m in moves if m.is_arc and abs(abs(m.geometry.normal[2]) - 1.0) < 1e-9]
    kept, _ = expressible(flat, "principal", 0.05)
    assert kept == flat  # the latitude circles lie in horizontal planes: principal ones


def test_oriented_polyline_keeps_position_and_axis():
    """A straight pass over a wavy surface: position alone needs two points; the axis, which tilts
    ±10 degrees, needs more, and every point's axis stays within the bound of the slerped one."""
    x = np.linspace(0.0, 200.0, 801)
    tilt = np.radians(10.0) * np.sin(x / 200.0 * 4 * math.pi)
    points = np.column_stack((x, np.zeros_like(x), np.zeros_like(x)))
    axes = np.column_stack((np.sin(tilt), np.zeros_like(x), -np.cos(tilt)))
    tol, angle = 0.1, math.radians(0.5)
    keep = oriented_polyline(points, axes, tol, angle)
    assert len(oriented_polyline(points, axes, tol, math.pi)) == 2 and len(keep) > 10
    for i, j in zip(keep[:-1], keep[1:]):
        u = (x[i:j + 1] - x[i]) / (x[j] - x[i])
        got = slerp_axes(axes[i], axes[j], u)
        cos = np.einsum("ij,ij->i", got, axes[i:j + 1])
        assert np.arccos(np.clip(cos, -1, 1)).max() <= angle + 1e-12


def test_travel_between_passes_keeps_clear_of_the_part(tmp_path):
    """Passes on a saddle are joined by travel at the approach clearance or higher, never closer to
    any surface point than the stand-off."""
    path = write_surfacepaths(tmp_path, saddle(), points_per_pass=200)[0]
    prog = build_surface_program(read_surfacepaths(path), ProgramOptions(approach_mm=5.0), SurfaceOptions(), AS)
    surface = np.vstack([np.array(p["points"]) for p in json.loads(path.read_text())["passes"]]) + [900.0, 0.0, 300.0]
    paths = prog.plan.paths
    for a, b in zip(paths[:-1], paths[1:]):
        c = a.depart_clearance_mm
        assert b.approach_clearance_mm == c
        p, q = a.end.translation_mm - c * a.end.rotation[:, 2], b.start.translation_mm - c * b.start.rotation[:, 2]
        u = np.linspace(0, 1, 400)[:, None]
        line = p + u * (q - p)
        assert np.min(np.linalg.norm(line[:, None] - surface[None], axis=2)) >= 100.0 - 1e-6
        assert c >= 5.0


@pytest.mark.parametrize("edit, message", [
    (lambda d: d.update(format="coatsim.polysegment/2"), "format: expected 'coatsim.surfacepaths/1'"),
    (lambda d: d["passes"][1].update(normals=d["passes"][1]["normals"][:-1]), r"passes\[1\].normals: 199 normals for 200"),
    (lambda d: d["passes"][0]["normals"].__setitem__(3, [0.0, 0.0, 2.0]), r"passes\[0\].normals\[3\]: length 2"),
    (lambda d: d["passes"][0]["points"].__setitem__(5, [0.0, "x", 1.0]), r"passes\[0\].points: expected a list"),
    (lambda d: d.update(passes=[]), "passes: expected a non-empty list"),
    (lambda d: d.update(standoff_mm=-5), "standoff_mm: expected a positive number"),
    (lambda d: d["mesh"].update(pose=[1, 2, 3]), r"mesh.pose: expected \[x, y, z, o, a, t\]"),
])
def test_bad_surfacepaths_are_refused_naming_the_field(tmp_path, edit, message):
    path = write_surfacepaths(tmp_path, saddle(), points_per_pass=200)[0]
    doc = json.loads(path.read_text())
    edit(doc)
    path.write_text(json.dumps(doc))
    with pytest.raises(InputError, match=message):
        read_surfacepaths(path)


def test_the_program_command_writes_one_program_for_all_passes(torus, tmp_path, run_cli):
    out = tmp_path / "t.as"
    code, stdout, err = run_cli(["program", str(torus), "--variant", "polyline-blend", "--follow-tangent", "-o", str(out)])
    assert code == 0, err
    assert "over 3 passes" in stdout and out.read_text().count("LAPPRO") == 2
    code, _, err = run_cli(["program", "builtin:ellipse", "--tol", "0.1", "--speed-on", "trace"])
    assert code == 2 and "--speed-on" in err and err.count("\n") == 1


def test_slerp_of_written_follow_poses_stays_near_the_normal(torus):
    """The axis the controller turns between consecutive written poses (slerp) stays within the
    angle tolerance of the sampled normal along every curve move (the roll's share included)."""
    doc = json.loads(torus.read_text())
    prog = build(torus, roll="follow")
    for path, spec in zip(prog.plan.paths, doc["passes"]):
        pts = np.array(spec["points"]) + [900.0, 0.0, 300.0]
        normals = np.array(spec["normals"])
        tcp = pts + 100.0 * normals
        for m in path.segments:
            if m.part != "curve":
                continue
            u = np.linspace(0.0, 1.0, 41)
            if m.is_arc:
                rot = np.concatenate((slerp(m.start.rotation, m.via_pose.rotation, u[:21] * 2),
                                      slerp(m.via_pose.rotation, m.end.rotation, u[21:] * 2 - 1)))
                x = m.geometry.points(u * m.length)
            else:
                rot = slerp(m.start.rotation, m.end.rotation, u)
                x = m.geometry.points(u * m.length)
            near = np.argmin(np.linalg.norm(x[:, None] - tcp[None], axis=2), axis=1)
            cos = np.einsum("ij,ij->i", rot[:, :, 2], -normals[near])
            assert np.degrees(np.arccos(np.clip(cos, -1, 1))).max() <= 2.0 + 0.05  # + the input's sampling


@pytest.mark.parametrize("name, suffix, arc", [("fanuc-tp", ".ls", ":  P["), ("urscript", ".script", "movec("),
                                               ("kuka-krl", ".src", "CIRC ")])
def test_the_program_command_writes_surface_passes_in_the_language_asked(torus, tmp_path, run_cli, name, suffix, arc):
    out = tmp_path / f"passes{suffix}"
    code, _, err = run_cli(["program", str(torus), "--language", name, "-o", str(out)])
    assert code == 0, err
    assert arc in out.read_text() and ".PROGRAM" not in out.read_text()
    if name == "kuka-krl":
        assert out.with_suffix(".dat").exists()  # the language's files, not one text


def test_gcode_refuses_surface_passes_that_tilt_the_gun(torus, tmp_path, run_cli):
    code, _, err = run_cli(["program", str(torus), "--language", "gcode", "-o", str(tmp_path / "p.ngc")])
    assert code == 2 and "no tool orientation" in err and err.count("\n") == 1


def _trough_pass(folder: Path, radius_mm: float) -> Path:
    """One pass across the trough of z = 20 cos(kx) whose radius there is ``radius_mm``: at a
    stand-off of 100 mm beyond it the TCP path folds back on itself (a swallowtail)."""
    k = math.sqrt(1.0 / (radius_mm * 20.0))
    x = np.linspace(math.pi / k - 40.0, math.pi / k + 40.0, 400)
    normals = np.column_stack((20.0 * k * np.sin(k * x), 0.0 * x, np.ones_like(x)))
    normals /= np.linalg.norm(normals, axis=1)[:, None]
    doc = {"format": "coatsim.surfacepaths/1", "units": "mm",
           "mesh": {"file": "trough.stl", "sha256": "", "vertices": 3, "faces": 1, "pose": [700, 0, 0, 0, 0, 0]},
           "pattern": "raster", "spacing_mm": 10.0, "standoff_mm": 100.0, "ripple_pct": 0.0,
           "passes": [{"points": np.column_stack((x, 0.0 * x, 20.0 * np.cos(k * x))).tolist(),
                       "normals": normals.tolist(), "closed": False, "lead_in": [], "lead_out": []}],
           "stats": {"passes": 1}}
    path = folder / f"trough{radius_mm:g}.json"
    path.write_text(json.dumps(doc), encoding="utf-8")
    return path


def test_a_trough_tighter_than_the_stand_off_tilts_the_axis_and_keeps_the_tool_advancing(tmp_path):
    """On the normal 100 mm over a trough of radius 95 or 60 mm the TCP would run backwards (a
    swallowtail: the fit cut across it, the nearest normal jumped from side to side and the
    pass took 140 arcs over 80 mm at 95 mm). The axis turns only as fast as keeps the TCP
    advancing by 5 % of the spot's way on every step: a few arcs, the axis within the tolerance
    of the axes it follows, and a note where it leaves the normal by more than that; over a
    trough of 110 mm the axis stays on the normal and nothing is said. (At 95 mm the TCP runs on
    a circle of about 5 mm while the axis turns: 6 arcs hold the axis, the rest are poses that
    keep the tool's turning rate from jumping, 52 in all.)"""
    for radius, tilted in ((95.0, 1.0), (60.0, 7.0), (110.0, 0.0)):
        source = _trough_pass(tmp_path, radius)
        program = build(source)
        paths = read_surfacepaths(source)
        along = pass_tcp(paths.passes[0], 100.0, paths.pose)
        step = np.diff(paths.pose.apply(paths.passes[0].points), axis=0)
        advance = np.einsum("ij,ij->i", np.diff(along.tcp_mm, axis=0), step) / np.einsum("ij,ij->i", step, step)
        assert advance.min() >= MIN_ADVANCE * (1 - 1e-6)
        assert math.degrees(along.max_tilt_rad) == pytest.approx(tilted, abs=0.5)
        assert math.degrees(program.max_axis_error_rad) <= 2.0
        if tilted > 2.0:
            (note,) = program.notes
            assert f"leaves the normal by up to {math.degrees(along.max_tilt_rad):.1f} deg (passes[0]" in note
            assert note[:60] in program.text
        else:
            assert program.notes == () and sum(program.counts[0]) <= 60, program.counts


def test_an_axis_that_strays_further_than_asked_is_said():
    """The guard on the fit's axis error: how far, on which pass and how many, against the
    tolerance asked; nothing within it."""
    (note,) = _axis_notes([0.01, math.radians(6.66), math.radians(2.5)], SurfaceOptions())
    assert note.startswith("the tool axis strays up to 6.7 deg from the axis planned (passes[1]; 2 of 3 passes "
                           "above the 2 deg asked)")
    assert _axis_notes([math.radians(2.0), 0.0], SurfaceOptions()) == ()


def test_each_travel_is_raised_on_its_own_as_little_as_keeps_it_clear():
    """Three passes along x at the stand-off over a plate, a pillar of surface points between the
    end of the first and the start of the second: that travel is raised (doubling from the
    approach) until it keeps the stand-off from the pillar, the next one is not (a travel that
    needed room once raised every later one: the engine bracket's passes left at 3.2 m)."""
    down = np.array([[1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, -1.0]])  # spray axis -z
    def flat(y: float, backwards: bool) -> PlacedPath:
        a, b = np.array([0.0, y, 100.0]), np.array([100.0, y, 100.0])
        a, b = (b, a) if backwards else (a, b)
        return PlacedPath((PlacedMove(Line3(a, b), Pose(down, a), Pose(down, b)),), np.array([0.0, 0.0, 1.0]),
                          100.0, 0.0, 0.0, 100.0)
    paths = [flat(0.0, False), flat(20.0, True), flat(40.0, False)]
    plate = np.array([(x, y, 0.0) for x in np.linspace(0, 100, 11) for y in np.linspace(0, 40, 5)])
    pillar = np.array([(100.0, 10.0, z) for z in np.linspace(0.0, 150.0, 31)])
    placed = travel_clearances(paths, 5.0, np.vstack((plate, pillar)), 100.0, "pillar")
    assert [(p.approach_clearance_mm, p.depart_clearance_mm) for p in placed] == [(5.0, 160.0), (160.0, 5.0), (5.0, 5.0)]
    with pytest.raises(InputError, match=r"pillar: the travel from pass 1 to pass 2 passes closer to the part than "
                                         r"the stand-off even 320 mm off it"):
        travel_clearances(paths, 5.0, np.vstack((plate, pillar * [1, 1, 10])), 100.0, "pillar")


@pytest.mark.parametrize("name", ["kawasaki-as", "abb-rapid", "kuka-krl", "fanuc-tp", "urscript"])
def test_every_language_leaves_and_enters_each_pass_at_its_own_clearances(tmp_path, name):
    """Each pass of the saddle given its own approach and depart clearances (all different):
    every language's program, read back, travels from the point its depart clearance above the
    end of one pass to the point its approach clearance above the start of the next (the
    languages other than AS wrote the plan's approach everywhere)."""
    path = write_surfacepaths(tmp_path, saddle(), points_per_pass=200)[0]
    target = language(name)
    prog = build_surface_program(read_surfacepaths(path), ProgramOptions(), SurfaceOptions(), target)
    paths = tuple(replace(p, approach_clearance_mm=20.0 + 10 * k, depart_clearance_mm=25.0 + 10 * k)
                  for k, p in enumerate(prog.plan.paths))
    files = []
    for suffix, text in target.files(target.write(replace(prog.plan, paths=paths))):
        files.append(tmp_path / f"saddle{suffix}")
        files[-1].write_text(text, encoding="ascii")
    travel = [(m.start.translation_mm, m.end.translation_mm) for m in target.read(files, ReadOptions()).moves
              if m.kind == "line" and not m.spray]
    for a, b in zip(paths[:-1], paths[1:]):
        left = a.end.translation_mm - a.depart_clearance_mm * a.end.rotation[:, 2]
        came = b.start.translation_mm - b.approach_clearance_mm * b.start.rotation[:, 2]
        assert min(np.linalg.norm(p - left) + np.linalg.norm(q - came) for p, q in travel) < 2e-3


def _lead_turn_deg(move: PlacedMove) -> float:
    return math.degrees(float(np.linalg.norm(log_rotation(move.start.rotation.T @ move.end.rotation))))


def test_a_lead_turns_the_tool_on_at_the_pass_end_rate_but_not_round():
    """A lead turns the tool on at the rate the end piece turns it (its rotation axis kept), by 10°
    at most: at the end of a pass inside a trough a 0.16 mm end piece turning 1.1° made a scanned
    part's 15 mm lead-in turn the tool by 102° (the arm could not reach it). A gentle rate is kept
    as it is, on a line and on a lead continuing a circle."""
    down = np.diag([1.0, -1.0, -1.0])
    tiny = Oriented(Line3(np.zeros(3), np.array([0.16, 0.0, 0.0])), down, None, down @ rot_y(math.radians(1.1)))
    lead = lead_move(tiny, 15.0, "lead_in", None)
    assert _lead_turn_deg(lead) == pytest.approx(10.0, abs=1e-9)
    turned = log_rotation(lead.start.rotation.T @ lead.end.rotation)
    assert abs(turned[1]) == pytest.approx(np.linalg.norm(turned))  # about the piece's own axis
    gentle = Oriented(Line3(np.zeros(3), np.array([20.0, 0.0, 0.0])), down, None, down @ rot_y(math.radians(2.0)))
    assert _lead_turn_deg(lead_move(gentle, 15.0, "lead_out", None)) == pytest.approx(1.5, abs=1e-9)
    sweep, radius = 0.3, 250.0
    arc = Arc3(np.array([radius, 0.0, 0.0]), radius * np.array([math.cos(sweep), math.sin(sweep), 0.0]), np.zeros(3),
               np.array([0.0, 0.0, 1.0]), radius, sweep)
    circle = Oriented(arc, down, down @ rot_z(sweep / 2), down @ rot_z(sweep))
    lead = lead_move(circle, 30.0, "lead_out", None)
    assert isinstance(lead.geometry, Arc3) and _lead_turn_deg(lead) == pytest.approx(math.degrees(30.0 / radius), abs=1e-6)


def _flat_passes() -> SurfacePaths:
    """Two straight passes over a flat plate facing +Z, 20 mm apart."""
    x = np.linspace(0.0, 120.0, 61)
    passes = tuple(SurfacePass(np.column_stack((x, np.full_like(x, y), np.zeros_like(x))),
                               np.tile([0.0, 0.0, 1.0], (len(x), 1)), False, np.zeros((0, 3)), np.zeros((0, 3)))
                   for y in (0.0, 20.0))
    return SurfacePaths("plate.json", passes, 100.0, Pose.from_translation(np.array([600.0, 0.0, 200.0])), None)


def test_a_language_without_tool_orientation_refuses_tilted_passes_before_any_fit(torus, monkeypatch):
    def no_fit(*_args):
        raise AssertionError("fitted before the tilt was checked")

    monkeypatch.setattr(surface_program, "fit_passes", no_fit)
    with pytest.raises(InputError, match=r"passes\[0\] point \d+ tilts the gun .* deg from -Z: G-code .*has no tool "):
        build_surface_program(read_surfacepaths(torus), ProgramOptions(), SurfaceOptions(), language("gcode"))
    with pytest.raises(AssertionError, match="fitted before"):  # an untilted plate goes on to its fit
        build_surface_program(_flat_passes(), ProgramOptions(), SurfaceOptions(), language("gcode"))


def test_untilted_passes_are_written_in_gcode():
    prog = build_surface_program(_flat_passes(), ProgramOptions(), SurfaceOptions(), language("gcode"))
    assert prog.counts == ((1, 0), (1, 0)) and "G1 " in prog.text


def test_the_variants_share_one_fit_made_with_their_settings(torus, monkeypatch):
    """Passes fitted once give every variant the program it gets when fitting them itself; a fit
    made with other settings (another speed, tolerance or stand-off) is not used."""
    paths, surface = read_surfacepaths(torus), SurfaceOptions()
    fitted = fit_passes(paths, surface_fit_settings(paths, surface, ProgramOptions().speed_mm_s))
    own = {v: build_surface_program(paths, ProgramOptions(variant=v), surface, AS).text for v in VARIANTS}
    calls = []
    monkeypatch.setattr(surface_program, "fit_passes", lambda *args: calls.append(args) or fit_passes(*args))
    for v in VARIANTS:
        assert build_surface_program(paths, ProgramOptions(variant=v), surface, AS, fitted).text == own[v]
    assert calls == []
    for options, other in ((ProgramOptions(speed_mm_s=300.0), surface), (ProgramOptions(), SurfaceOptions(tolerance_mm=0.5)),
                           (ProgramOptions(), SurfaceOptions(standoff_mm=80.0))):
        build_surface_program(paths, options, other, AS, fitted)
    assert len(calls) == 3
