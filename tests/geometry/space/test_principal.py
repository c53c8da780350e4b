"""Arcs kept in the principal planes (``arc_planes="principal"``): every arc's normal along ±X, ±Y
or ±Z, the chain within σ against a dense brute-force oracle, G1 except at listed corners (each a
real break); curves in no principal plane come back as lines, but for stretches that lie within σ
of one; curves already in one unchanged."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from hypothesis import assume, example, given, settings
from hypothesis import strategies as st

from coatsim.core.errors import InputError
from coatsim.geometry import builtin_curve
from coatsim.geometry.space.chain import SpaceChain
from coatsim.geometry.space.curve import make_space_curve
from coatsim.geometry.space.primitives import Arc3, Line3
from coatsim.geometry.space.principal import CORNER_BREAK_RAD, is_principal, plane_pose
from coatsim.geometry.space.rotations import rot_z
from coatsim.geometry.space.segment import segment_space_curve

from strategies import unit_vectors
from test_segment3d import assert_g1, brute_hausdorff

STEP_MM = 0.25  # sampling of the generated curves


def assert_principal(chain: SpaceChain) -> None:
    """Every arc's normal is an axis (its other components within 1e-9) and every listed corner
    breaks the tangent (the option lists no corner that is not one)."""
    for seg in chain.segments:
        if isinstance(seg, Arc3):
            assert np.sort(np.abs(seg.normal))[:2].max() <= 1e-9, seg.normal
    breaks = chain.junction_breaks()
    assert all(breaks[k] > CORNER_BREAK_RAD for k in chain.corners if k < len(breaks))


def principal_path(start_axis: int, moves: list[tuple[int, int, float, float, float]]) -> np.ndarray:
    """Points every STEP_MM of a G1 curve made of arcs in principal planes and lines: it starts
    along ``start_axis``; each move is (which of the two planes containing the tangent, turn sign,
    radius, quarter turns 1 or 2, line after it): a quarter or half turn leaves the tangent along an
    axis, so the next arc may lie in another principal plane, meeting along the axis both share."""
    point, tangent = np.zeros(3), np.eye(3)[start_axis]
    pieces = [point[None]]
    for choice, sign, radius, quarters, line in moves:
        along = int(np.flatnonzero(tangent)[0])
        normal_axis = [a for a in range(3) if a != along][choice]
        normal = np.eye(3)[normal_axis] * sign
        centre = point + radius * np.cross(normal, tangent)
        sweep = quarters * math.pi / 2
        arc = Arc3(point, point, centre, normal, radius, sweep)
        angles = np.linspace(0.0, sweep, max(2, int(radius * sweep / STEP_MM)))[1:]
        pts = arc.at_angles(angles)
        point, tangent = pts[-1], np.round(arc.tangents_at_angles(np.array([sweep]))[0])
        n = max(1, int(line / STEP_MM))
        straight = point + np.outer(np.linspace(0.0, line, n + 1)[1:], tangent)
        pieces += [pts, straight]
        point = straight[-1]
    return np.vstack(pieces)


moves = st.lists(st.tuples(st.integers(0, 1), st.sampled_from([-1.0, 1.0]), st.floats(8.0, 60.0),
                           st.integers(1, 2), st.floats(0.0, 30.0)), min_size=1, max_size=4)


@settings(max_examples=15, deadline=None)
@given(st.integers(0, 2), moves, st.sampled_from([0.05, 0.1, 0.3]))
def test_curves_of_principal_arcs_come_back_with_principal_arcs_only(start_axis, path_moves, tol):
    pts = principal_path(start_axis, path_moves) + [100.0, -50.0, 30.0]
    fit = segment_space_curve(make_space_curve(pts, "principal", "no"), tol, arc_planes="principal")
    assert_principal(fit.chain)
    assert_g1(fit.chain)
    assert fit.max_deviation_mm <= tol
    assert brute_hausdorff(pts, fit.chain, tol / 20) <= tol * 1.01
    assert fit.chain.n_arcs >= 1
    assert fit.chain.corners == ()  # it changes plane only along the axis both planes share: G1 there


@settings(max_examples=10, deadline=None)
@given(unit_vectors(), st.floats(0.0, 2 * math.pi), st.floats(20.0, 80.0), st.floats(0.3, 1.0))
@example(np.array([6.0, 2.0, 3.0]) / 7.0, 0.0, 46.0, 0.5)  # 31° from x = const: two 5 mm stretches lie within σ of it
def test_a_curve_in_a_tilted_plane_comes_back_as_lines_but_where_it_lies_in_a_principal_plane(normal, turn, radius, squash):
    assume(np.abs(normal).max() <= math.cos(math.radians(30)))  # 30° or more from every principal plane
    t = np.linspace(0.0, 1.6 * math.pi, 600)
    u = np.cross(normal, [1.0, 0.0, 0.0] if abs(normal[0]) < 0.9 else [0.0, 1.0, 0.0])
    u /= np.linalg.norm(u)
    v = np.cross(normal, u)
    c, s = radius * np.cos(t + turn), squash * radius * np.sin(t + turn)
    pts = np.outer(c, u) + np.outer(s, v) + [40.0, 10.0, -20.0]
    fit = segment_space_curve(make_space_curve(pts, "tilted", "no"), 0.1, arc_planes="principal")
    arcs = [seg for seg in fit.chain.segments if isinstance(seg, Arc3)]
    for arc in arcs:  # only where the curve itself stays within σ of a plane x, y or z = const
        near = np.argmin(np.linalg.norm(pts[:, None, :] - arc.at_angles(np.linspace(0, arc.sweep, 20))[None], axis=2), axis=0)
        along_normal = pts[near.min():near.max() + 1] @ arc.normal
        assert np.ptp(along_normal) <= 2 * 0.1 + 1e-9
    assert sum(arc.length for arc in arcs) <= 0.25 * fit.chain.length
    assert fit.max_deviation_mm <= 0.1 and brute_hausdorff(pts, fit.chain, 0.005) <= 0.101
    assert_principal(fit.chain)
    assert len(fit.chain.corners) == fit.chain.n_segments - 1  # every vertex of the lines is a corner
    assert any("line(s)" in note and "corner(s) added" in note for note in fit.notes)
    assert segment_space_curve(make_space_curve(pts, "tilted", "no"), 0.1).chain.n_arcs > 0  # "any" keeps arcs


@pytest.mark.parametrize("noise", [0.0, 0.02])
def test_a_circle_in_z_const_is_one_circle(noise):
    t = np.linspace(0, 2 * math.pi, 800)
    rng = np.random.default_rng(4)
    pts = np.column_stack((30 + 45 * np.cos(t), -10 + 45 * np.sin(t), 30 + noise * rng.uniform(-1, 1, len(t))))
    pts[-1] = pts[0]
    fit = segment_space_curve(make_space_curve(pts, "circle"), 0.1, arc_planes="principal")
    assert fit.chain.closed and fit.chain.corners == () and fit.planar_pose is not None
    for arc in fit.chain.segments:
        assert isinstance(arc, Arc3) and abs(abs(arc.normal[2]) - 1.0) <= 1e-12 and abs(arc.center[2] - 30) < 0.05
        assert np.linalg.norm(arc.center[:2] - [30, -10]) < 0.05 and abs(arc.radius - 45) < 0.05
    assert math.fsum(a.sweep for a in fit.chain.segments) == pytest.approx(2 * math.pi, abs=1e-6)
    assert fit.max_deviation_mm <= 0.1 and fit.chain.n_segments == 1


def test_a_pass_around_a_cylinder_about_x_is_one_arc_about_x():
    t = np.linspace(0.2, 2.8, 500)
    pts = np.column_stack((70 + 0 * t, 40 * np.cos(t), 40 * np.sin(t)))
    fit = segment_space_curve(make_space_curve(pts, "cylinder", "no"), 0.1, arc_planes="principal")
    (arc,) = fit.chain.segments
    assert isinstance(arc, Arc3) and abs(abs(arc.normal[0]) - 1) < 1e-12 and abs(arc.radius - 40) < 0.01


def test_a_stepped_curve_changes_plane_tangent_continuously_along_the_shared_axis():
    """z = 30 then x = 0, joined by a straight run along Y (in both planes): the chain changes plane
    in the middle of that run, G1 (the planar fits pinned to ±Y there); a kink elsewhere is a corner."""
    a = np.linspace(-math.pi / 2, 0, 100)
    flat = np.column_stack((40 * np.cos(a) - 40, 40 * np.sin(a), 30 + 0 * a))  # z = 30, ends along +Y
    y = np.linspace(0, 30, 60)[1:]
    b = np.linspace(0, math.pi / 2, 100)[1:]
    rise = np.column_stack((0 * b, 30 + 25 * np.sin(b), 55 - 25 * np.cos(b)))  # x = 0, from +Y up to +Z
    pts = np.vstack((flat, np.column_stack((0 * y, y, 30 + 0 * y)), rise))
    curve = make_space_curve(pts, "stepped", "no")
    fit = segment_space_curve(curve, 0.1, arc_planes="principal")
    normals = {tuple(np.round(s.normal).astype(int)) for s in fit.chain.segments if isinstance(s, Arc3)}
    assert normals == {(0, 0, 1), (1, 0, 0)}
    assert_principal(fit.chain)
    assert_g1(fit.chain)
    assert fit.chain.corners == () and [s.kind for s in fit.chain.segments] == ["arc", "line", "arc"]
    assert fit.max_deviation_mm <= 0.1
    assert brute_hausdorff(pts, fit.chain, 0.005) <= 0.101
    assert not all(is_principal(s.normal) for s in segment_space_curve(curve, 0.1).chain.segments if isinstance(s, Arc3))


def test_a_helix_comes_back_as_lines_with_a_note():
    t = np.linspace(0, 6 * math.pi, 1500)
    pts = np.column_stack((40 * np.cos(t), 40 * np.sin(t), 90 * t / (6 * math.pi)))
    fit = segment_space_curve(make_space_curve(pts, "helix"), 0.1, arc_planes="principal")
    assert_principal(fit.chain)
    assert fit.chain.n_lines > 0.9 * fit.chain.n_segments and fit.max_deviation_mm <= 0.1
    assert "corner(s) added" in fit.summary()


@pytest.mark.parametrize("name", ["ellipse", "cam", "rounded-rectangle", "paper-spiral"])
@pytest.mark.parametrize("axis", [0, 1, 2])
def test_the_option_changes_nothing_for_a_curve_in_a_principal_plane(name, axis):
    curve = builtin_curve(name)
    rng = np.random.default_rng(axis)
    flat = np.column_stack((curve.points, np.zeros(len(curve.points)))) @ rot_z(rng.uniform(0, 6.3)).T
    pts = plane_pose(axis, float(rng.uniform(-200, 200))).apply(flat)
    space = make_space_curve(pts, name, "yes" if curve.closed else "no")
    free = segment_space_curve(space, 0.1)
    kept = segment_space_curve(space, 0.1, arc_planes="principal")
    assert kept.notes == () and kept.chain.corners == free.chain.corners
    assert [s.kind for s in kept.chain.segments] == [s.kind for s in free.chain.segments]
    for a, b in zip(kept.chain.segments, free.chain.segments):
        assert np.array_equal(a.start, b.start) and np.array_equal(a.end, b.end)
    assert_principal(kept.chain)


def test_arc_planes_is_checked():
    curve = make_space_curve(np.column_stack((np.arange(10.0), np.zeros(10), np.arange(10.0) ** 2 / 10)), "c")
    with pytest.raises(InputError, match="arc_planes: expected any or principal") as info:
        segment_space_curve(curve, 0.1, arc_planes="xy")
    assert info.value.parameters == ("arc_planes",)


def test_a_planar_curve_keeps_its_fit_and_a_bad_value_is_one_line(tmp_path, run_cli):
    """A 2-column curve lies in XY: every arc already is G17, so the option changes nothing."""
    outs = []
    for extra in ([], ["--arc-planes", "principal"]):
        out = tmp_path / f"ellipse{len(extra)}.json"
        code, _, stderr = run_cli(["segment", "builtin:ellipse", "--tol", "0.1", "-o", str(out), *extra])
        assert code == 0, stderr
        outs.append(json.loads(out.read_text()))
    assert outs[0]["format"] == "coatsim.polysegment/1" and outs[0]["segments"] == outs[1]["segments"]
    code, _, stderr = run_cli(["segment", "builtin:ellipse", "--arc-planes", "xy"])
    assert code == 2 and stderr.count("\n") == 1 and "--arc-planes: expected any or principal" in stderr


@pytest.mark.parametrize("shift", [0, 50, 250, 330])
def test_a_closed_curve_of_two_half_circles_in_two_planes_wherever_it_starts(shift):
    """Half a circle in z = 0 and half a circle in x = 0 closing it: two arcs, the two 90° turns
    corners, whatever point the loop starts at."""
    a, b = np.linspace(-math.pi / 2, math.pi / 2, 200), np.linspace(0, math.pi, 200)[1:]
    loop = np.vstack((np.column_stack((30 * np.cos(a), 30 * np.sin(a), 0 * a)),
                      np.column_stack((0 * b, 30 * np.cos(b), 30 * np.sin(b)))))[:-1]
    pts = np.roll(loop, shift, axis=0)
    fit = segment_space_curve(make_space_curve(np.vstack((pts, pts[:1])), "D", "yes"), 0.1, arc_planes="principal")
    chain = fit.chain
    assert chain.closed and chain.n_arcs == 2 and chain.n_segments == 2 and chain.corners == (0, 1)
    assert {tuple(np.abs(s.normal).round().astype(int)) for s in chain.segments} == {(0, 0, 1), (1, 0, 0)}
    assert np.degrees(chain.junction_breaks()) == pytest.approx([90.0, 90.0], abs=0.5)
    assert fit.max_deviation_mm <= 0.1 and np.array_equal(chain.segments[-1].end, chain.segments[0].start)
    assert_principal(chain)

