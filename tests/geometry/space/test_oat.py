"""O-A-T (Rz.Ry.Rz, degrees) conversions."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from coatsim.geometry.space.rotations import matrix_to_oat, oat_to_matrix, rot_y, rot_z
from coatsim.geometry.space.pose import rotation_angle

angles = st.floats(-720.0, 720.0, allow_nan=False)


def test_tool_pointing_down_is_0_180_0():
    r = oat_to_matrix(0.0, 180.0, 0.0)
    assert np.allclose(r[:, 2], [0.0, 0.0, -1.0], atol=1e-15)
    assert np.allclose(r, np.diag([-1.0, 1.0, -1.0]), atol=1e-15)
    assert matrix_to_oat(np.diag([-1.0, 1.0, -1.0])) == (0.0, 180.0, 0.0)


def test_identity_and_single_axis_cases():
    assert np.allclose(oat_to_matrix(0, 0, 0), np.eye(3))
    assert np.allclose(oat_to_matrix(90, 0, 0), [[0, -1, 0], [1, 0, 0], [0, 0, 1]], atol=1e-15)
    # A alone tilts the tool z axis towards +x.
    assert np.allclose(oat_to_matrix(0, 90, 0)[:, 2], [1, 0, 0], atol=1e-15)
    # O turns the tilt direction: tool z towards +y.
    assert np.allclose(oat_to_matrix(90, 90, 0)[:, 2], [0, 1, 0], atol=1e-15)
    # T spins about the tool's own z axis and leaves it in place.
    assert np.allclose(oat_to_matrix(30, 40, 77)[:, 2], oat_to_matrix(30, 40, 0)[:, 2])


def test_known_decomposition():
    o, a, t = matrix_to_oat(oat_to_matrix(30.0, 40.0, 50.0))
    assert (o, a, t) == pytest.approx((30.0, 40.0, 50.0), abs=1e-12)
    o, a, t = matrix_to_oat(oat_to_matrix(-150.0, 120.0, 170.0))
    assert (o, a, t) == pytest.approx((-150.0, 120.0, 170.0), abs=1e-12)


@pytest.mark.parametrize("a", [0.0, 180.0])
@pytest.mark.parametrize("o,t", [(30.0, 0.0), (10.0, 20.0), (-170.0, 95.0), (0.0, 180.0)])
def test_gimbal_cases_compare_rotation_matrices(o, a, t):
    r = oat_to_matrix(o, a, t)
    o2, a2, t2 = matrix_to_oat(r)
    assert a2 == a and t2 == 0.0
    assert np.allclose(oat_to_matrix(o2, a2, t2), r, atol=1e-12)
    # Only O+T (A = 0) or O-T (A = 180) is defined.
    assert abs(math.remainder(o2 - (o + t if a == 0.0 else o - t), 360.0)) < 1e-9


@given(angles, angles, angles)
def test_matrix_round_trip(o, a, t):
    r = oat_to_matrix(o, a, t)
    assert np.allclose(r.T @ r, np.eye(3), atol=1e-12) and np.linalg.det(r) == pytest.approx(1.0)
    o2, a2, t2 = matrix_to_oat(r)
    assert 0.0 <= a2 <= 180.0 and -180.0 < o2 <= 180.0 and -180.0 < t2 <= 180.0
    assert rotation_angle(oat_to_matrix(o2, a2, t2), r) < 1e-9


@given(angles, angles, angles)
def test_near_gimbal_rebuilds_the_matrix(o, t, tiny):
    a = 180.0 - abs(tiny) * 1e-9
    r = oat_to_matrix(o, a, t)
    assert rotation_angle(oat_to_matrix(*matrix_to_oat(r)), r) < 1e-9


def test_no_negative_zero():
    for value in matrix_to_oat(rot_z(0.0) @ rot_y(math.pi)):
        assert math.copysign(1.0, value) == 1.0


def test_rotation_angle_small_and_large():
    assert rotation_angle(np.eye(3), rot_z(1e-9)) == pytest.approx(1e-9, rel=1e-6)
    assert rotation_angle(np.eye(3), rot_z(2.0)) == pytest.approx(2.0)
    assert rotation_angle(np.eye(3), rot_y(math.pi)) == pytest.approx(math.pi)
