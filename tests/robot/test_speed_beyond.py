"""The twin's warning for a programmed SPEED the arm cannot hold: everywhere on a stretch, or on a
part of it (the joints hold the tool below the speed that counts as at speed there)."""

from __future__ import annotations

import numpy as np
import pytest

from coatsim.robot.cell import load_cell
from coatsim.robot.reachable import speed_event
from coatsim.robot.sampling import CartesianPiece


@pytest.fixture(scope="module")
def cell():
    return load_cell()


def _piece(speed_mm_s: float, n: int = 301) -> CartesianPiece:
    s = np.linspace(0.0, 300.0, n)
    return CartesianPiece(s=s, position=np.column_stack((s, np.zeros(n), np.zeros(n))),
                          rotation=np.repeat(np.eye(3)[None], n, axis=0), tangent=np.tile([1.0, 0, 0], (n, 1)),
                          curvature=np.zeros(n), speed=np.full(n, speed_mm_s), move=np.zeros(n, int),
                          spray=np.ones(n, bool), ref_s=s, reference=(), reference_moves=(0,))


def _joints(cell, rate_rad_mm: np.ndarray, s: np.ndarray) -> np.ndarray:
    """JT1 turning at ``rate`` (rad/mm) along s, the others still."""
    q = np.zeros((len(s), 6))
    q[:, 0] = np.concatenate(([0.0], np.cumsum(rate_rad_mm[1:] * np.diff(s))))
    return q


def test_a_part_of_the_stretch_beyond_the_joints_is_warned_with_its_length(cell):
    piece = _piece(300.0)
    allowed_slow = 120.0  # mm/s the joints allow on the middle 100 mm
    rate = np.where((piece.s > 100) & (piece.s < 200), cell.v_max[0] / allowed_slow, cell.v_max[0] / 3000.0)
    event = speed_event(cell, piece, _joints(cell, rate, piece.s), "p: line 3 (linear move)")
    assert event is not None and "SPEED 300 mm/s is beyond the arm on" in event, event
    beyond_mm = float(event.split("beyond the arm on ")[1].split(" mm")[0])
    assert 95 <= beyond_mm <= 105, event
    down_to = float(event.split("allow down to ")[1].split(" mm/s")[0])
    assert down_to == pytest.approx(allowed_slow, rel=0.05), event


def test_within_the_at_speed_share_or_everywhere_within_the_limits_no_warning(cell):
    piece = _piece(300.0)
    rate = np.where(piece.s > 150, cell.v_max[0] / 290.0, cell.v_max[0] / 3000.0)  # 290 >= 95 % of 300
    assert speed_event(cell, piece, _joints(cell, rate, piece.s), "p") is None
    assert speed_event(cell, piece, _joints(cell, np.full(len(piece.s), cell.v_max[0] / 3000.0), piece.s), "p") is None


def test_beyond_everywhere_keeps_the_stretch_message(cell):
    piece = _piece(300.0)
    event = speed_event(cell, piece, _joints(cell, np.full(len(piece.s), cell.v_max[0] / 100.0), piece.s), "p")
    assert event is not None and "allow at most 100 mm/s on this stretch" in event, event
