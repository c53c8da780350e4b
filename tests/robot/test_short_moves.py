"""Short moves: blends that meet in the middle of a chord, coarse sampling of tiny moves."""

from __future__ import annotations

import numpy as np
import pytest

from coatsim.program.toolpath import ToolPath
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


def test_a_reversal_stops_the_tool_instead_of_blending_through_a_cusp(cell):
    """Out and back along one line with CP ON (a degenerate ellipse segmented to two lines): the
    blend of a 180 degree turn would have a cusp (NaN curvature, failed timing); the tool stops."""
    import warnings

    pts = [(700.0, -60.0), (700.0, 60.0), (700.0, -60.0)]
    path = ToolPath("reversal", (approach(pts[0]), *lines(pts, speed=300.0, accuracy=5.0, stop=False)))
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        pieces = plan_pieces(path, step=1.0)
        result = execute(path, cell)
    assert sum(hasattr(p, "position") for p in pieces) == 2  # split at the reversal
    at_turn = np.abs(result.log.position[:, 1] - 60.0) < 0.5
    assert at_turn.any() and result.log.speed[at_turn].min() < 5.0  # at rest where it turns back
    sprayed = result.log.spray
    np.testing.assert_allclose(result.log.position[sprayed, 0], 700.0, atol=0.2)  # never leaves the line
