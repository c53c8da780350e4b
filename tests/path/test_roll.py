"""Poses added along a 3-D pass for the tool's orientation (coatsim.path.roll): halving a piece
where the turning rate jumps must bring the jump down, or it is not done."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings, strategies as st

from coatsim.geometry.space.along import AlongPass
from coatsim.geometry.space.primitives import Line3
from coatsim.path.roll import MAX_RATE_JUMP_RAD_MM, RATE_MIN_PIECE_MM, AxisPiece, _checked, orient, oriented_pieces

REFERENCE = np.array([-1.0, 0.0, 0.0])


def _axes(s: np.ndarray, tilt_rad: np.ndarray) -> np.ndarray:
    """Unit axes down -z, tilted about the x axis by ``tilt_rad`` at each arc length."""
    return np.column_stack((np.zeros_like(s), np.sin(tilt_rad), -np.cos(tilt_rad)))


def _pass(tilt: np.ndarray, length_mm: float = 100.0) -> tuple[list[AxisPiece], AlongPass]:
    s = np.linspace(0.0, length_mm, len(tilt))
    points = np.column_stack((s, np.zeros_like(s), np.zeros_like(s)))
    axes = _axes(s, tilt)
    line = Line3(points[0], points[-1])
    wanted = AlongPass([line], points, axes, 0.1)
    mid = wanted(np.array([line.via]))[0]
    return [AxisPiece(line, (axes[0], mid, axes[-1]))], wanted


@settings(max_examples=15, deadline=None)
@given(st.integers(0, 2**32 - 1), st.floats(0.1, 1.0))
def test_noisy_axes_do_not_split_a_pass_into_micrometre_moves(seed, noise_deg):
    """A scanned part's normals wobble from point to point: 201 axes 0.5 mm apart with up to
    ``noise_deg`` of noise on a gentle turn. Halving for the rate would chase the noise down to
    1 µm moves (thousands of poses); the poses stay at the input's own scale."""
    s = np.linspace(0.0, 100.0, 201)
    tilt = 0.2 * np.sin(s / 30.0) + np.radians(noise_deg) * np.random.default_rng(seed).uniform(-1, 1, len(s))
    pieces, wanted = _pass(tilt)
    out = oriented_pieces(pieces, "fixed", 0.0, REFERENCE, wanted, math.radians(2.0))
    lengths = np.array([o.geometry.length for o in out])
    assert len(out) <= len(s) and lengths.min() >= 0.1


def test_smooth_axes_still_get_poses_where_the_rate_changes():
    """On axes that turn smoothly at a changing rate, halving lowers every jump below the bound."""
    s = np.linspace(0.0, 100.0, 401)
    pieces, wanted = _pass(0.3 * (s / 100.0) ** 2)
    out = oriented_pieces(pieces, "fixed", 0.0, REFERENCE, wanted, math.radians(2.0))
    _, jump = _checked(out, wanted, math.radians(2.0))
    assert len(out) > 1 and jump.max() <= MAX_RATE_JUMP_RAD_MM
    assert orient(pieces, "fixed", 0.0, REFERENCE) and len(out) < 64


def test_no_piece_is_halved_for_the_rate_below_the_controller_s_blend():
    """A 30 mm pass whose axis turns at a changing rate, within the angle tolerance all along:
    halving for the rate stops at pieces of RATE_MIN_PIECE_MM (the controller blends the
    orientation of shorter ones with their neighbours' and slows more than for the jump; a
    saddle's pass went to 0.51 of its speed where two 2.3 mm pieces replaced one of 4.5 mm)."""
    s = np.linspace(0.0, 30.0, 121)
    pieces, wanted = _pass(0.2 * (s / 30.0) ** 2, length_mm=30.0)
    out = oriented_pieces(pieces, "fixed", 0.0, REFERENCE, wanted, math.radians(2.0))
    stray, _ = _checked(out, wanted, math.radians(2.0))
    assert not stray.any() and len(out) == 2
    assert min(o.geometry.length for o in out) >= RATE_MIN_PIECE_MM
