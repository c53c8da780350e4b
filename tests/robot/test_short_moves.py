"""Short moves: blends that meet in the middle of a chord, coarse sampling of tiny moves."""

from __future__ import annotations

import numpy as np
import pytest

from coatsim.languages.kawasaki_as.language import KAWASAKI_AS
from coatsim.path.toolpath import ToolPath
from coatsim.robot.cell import load_cell
from coatsim.robot.execute import execute
from coatsim.robot.sampling import plan_pieces

from robot_helpers import approach, lines


@pytest.fixture(scope="module")
def cell():
    return load_cell()


def zigzag(chord: float, n: int, accuracy: float, stop: bool) -> ToolPath:
    """A zig-zag of ``n`` chords of length ``chord`` mm with 30° turns."""
    heading = np.radians(np.where(np.arange(n) % 2 == 0, 15.0, -15.0))
    steps = chord * np.column_stack((np.cos(heading), np.sin(heading)))
    pts = np.vstack(([0.0, 0.0], np.cumsum(steps, axis=0))) + [650.0, 0.0]
    pts = [tuple(p) for p in pts]
    return ToolPath("zigzag", (approach(pts[0]), *lines(pts, speed=200.0, accuracy=accuracy, stop=stop)))


def test_blends_that_meet_mid_chord_leave_no_duplicate_samples(cell):
    # accuracy >= half the chord: the blends at both ends of every chord meet in its middle
    path = zigzag(chord=2.0, n=12, accuracy=1.0, stop=False)
    for piece in plan_pieces(path, step=1.0):
        if hasattr(piece, "position"):
            gaps = np.linalg.norm(np.diff(piece.position, axis=0), axis=1)
            assert gaps.min() > 1e-9
    result = execute(path, cell)
    assert result.metrics.stops == 0


@pytest.mark.parametrize("step", [2.0, 5.0])
def test_exact_stops_on_moves_shorter_than_the_sampling_step(cell, step):
    result = execute(zigzag(chord=1.5, n=6, accuracy=1.0, stop=True), cell, step_mm=step)
    assert np.isfinite(result.log.t).all() and result.log.t[-1] > 0


@pytest.mark.parametrize("travel", [1e-8, 2e-7, 1e-6, 1e-5, 9e-5])
def test_tiny_joint_moves_are_timed_within_the_limits(travel):
    """toppra fails on joint moves of 2e-7 to 1e-5 rad; a program may ask for one (JMOVE to a
    joint value a hair off where the arm stands)."""
    from coatsim.robot.cell import load_cell
    from coatsim.robot.timing import time_joint

    cell = load_cell()
    q1 = cell.home.copy()
    q1[[1, 2]] += travel
    timed = time_joint(cell, cell.home, q1, 500.0, "tiny")
    assert np.allclose(timed.q[0], cell.home) and np.allclose(timed.q[-1], q1, atol=1e-15)
    assert np.all(np.abs(timed.qdd) <= cell.a_max + 1e-9) and np.all(np.abs(timed.qd) <= cell.v_max)


def test_a_reversal_stops_instead_of_folding_a_blend():
    """a -> b -> a with CP ON: no blend can turn the tool round; it stops at b."""
    import warnings

    from coatsim.path.toolpath import LinearMove
    from robot_helpers import pose, settings

    toolpath = ToolPath("reverse", (approach((700.0, -50.0)),
                                    LinearMove(pose(700.0, -50.0), pose(700.0, 50.0), settings(accuracy=5.0), True, 10),
                                    LinearMove(pose(700.0, 50.0), pose(700.0, -50.0), settings(stop=True), True, 11)))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        pieces = plan_pieces(toolpath)
    assert [type(p).__name__ for p in pieces] == ["JointPiece", "CartesianPiece", "CartesianPiece"]
    assert all(np.isfinite(p.curvature).all() for p in pieces[1:])


def circle_chords(radius: float, chord: float, accuracy: float, speed: float) -> ToolPath:
    """A blended polyline around a circle, chords of about ``chord`` mm (one lap and a half),
    their lengths a micrometre apart as an RDP polyline's are."""
    step = 2 * np.arcsin(chord / (2 * radius))
    n = int(3 * np.pi / step)
    phi = np.concatenate(([0.0], np.cumsum(step * (1.0 + 3e-4 * np.sin(np.arange(n))))))
    pts = [(700.0 + radius * np.cos(a), radius * np.sin(a)) for a in phi]
    return ToolPath("chords", (approach(pts[0]), *lines(pts, speed=speed, accuracy=accuracy, stop=False)))


@pytest.mark.parametrize("chord", [3.74, 4.0, 4.09])
def test_blends_meeting_mid_chord_leave_no_sliver_samples(chord):
    """Chords at most a little longer than two accuracy radii are all blend: nothing of them is
    sampled a fraction of a micrometre from a blend end."""
    path = circle_chords(radius=60.0, chord=chord, accuracy=2.0, speed=300.0)
    (piece,) = [p for p in plan_pieces(path, step=1.0) if hasattr(p, "position")]
    assert np.diff(piece.s).min() > 1e-3
    assert piece.length == pytest.approx(piece.ref_s[-1], rel=0.01)


def test_blended_polyline_with_blends_meeting_mid_chord_keeps_the_speed(cell):
    """The RDP polyline of an epitrochoid (vertices ~3.7 mm apart, 3.6 deg turns) at 300 mm/s
    with ACCURACY 2: the blends' radii (~60 mm) allow the speed everywhere, and the tool keeps
    it (sliver samples between blends used to make the joint spline swing and the tool slow to a
    third of the speed on part of the curve)."""
    from coatsim.geometry import builtin_curve
    from coatsim.languages.kawasaki_as import interpret, parse_as
    from coatsim.path.build import ProgramOptions, build_program, polyline_of
    from coatsim.path.placement import Placement, centering_offset

    curve = builtin_curve("epitrochoid")
    poly = polyline_of(curve.points, True, 0.1)
    built = build_program(poly, Placement(lead_in_mm=20.0, lead_out_mm=20.0, offset_xy=centering_offset(poly)),
                          ProgramOptions(variant="polyline-blend", speed_mm_s=300.0, accuracy_mm=2.0),
                          language=KAWASAKI_AS, tolerance_mm=0.1, source="epitrochoid", points=curve.points)
    result = execute(interpret(parse_as(built.text)), cell)
    assert result.metrics.min_speed_ratio > 0.98 and result.metrics.fraction_at_speed > 0.99
