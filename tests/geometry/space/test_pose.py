"""The pose type: composition, inverse, points and vectors, 4x4, mink, slerp."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings

from coatsim.geometry.space.pose import Pose, rotation_angle, slerp
from coatsim.geometry.space.rotations import rot_x, rot_z

from strategies import points3, poses, rotations

SETTINGS = settings(max_examples=150, deadline=None)


@SETTINGS
@given(poses(), poses(), points3(5))
def test_composition_applies_right_first(a, b, p):
    assert np.allclose((a @ b).apply(p), a.apply(b.apply(p)), atol=1e-9)
    assert np.allclose((a @ b).as_matrix4(), a.as_matrix4() @ b.as_matrix4(), atol=1e-9)


@SETTINGS
@given(poses(), points3(4))
def test_inverse_and_matrix4(a, p):
    assert (a @ a.inverse()).is_close(Pose.identity(), tol_mm=1e-9, tol_rad=1e-12)
    assert np.allclose(a.inverse().apply(a.apply(p)), p, atol=1e-9)
    assert np.array_equal(Pose.from_matrix4(a.as_matrix4()).rotation, a.rotation)
    assert np.allclose(a.apply_vectors(p), p @ a.rotation.T)
    # distances are kept, vectors ignore the translation
    assert np.isclose(np.linalg.norm(a.apply(p[0]) - a.apply(p[1])), np.linalg.norm(p[0] - p[1]))


@SETTINGS
@given(poses())
def test_mink_round_trip(a):
    assert Pose.from_mink(a.to_mink()).is_close(a, tol_mm=1e-12, tol_rad=1e-12)


@SETTINGS
@given(rotations(), rotations())
def test_slerp_constant_rate_about_one_axis(r0, r1):
    total = rotation_angle(r0, r1)
    u = np.linspace(0.0, 1.0, 7)
    rs = slerp(r0, r1, u)
    assert np.allclose(rs[0], r0, atol=1e-12) and np.allclose(rs[-1], r1, atol=1e-9)
    for k, r in enumerate(rs):
        assert rotation_angle(r0, r) == pytest.approx(u[k] * total, abs=1e-9)
        assert rotation_angle(r, r1) == pytest.approx((1 - u[k]) * total, abs=1e-9)


def test_interpolate_analytic():
    a = Pose(np.eye(3), np.zeros(3))
    b = Pose(rot_z(math.pi / 2), np.array([10.0, 0.0, 0.0]))
    mid = a.interpolate(b, 0.5)
    assert np.allclose(mid.rotation, rot_z(math.pi / 4)) and np.allclose(mid.translation_mm, [5, 0, 0])
    assert mid.angle_to(b) == pytest.approx(math.pi / 4)


def test_immutable_and_validated():
    a = Pose(rot_x(0.3), np.array([1.0, 2.0, 3.0]))
    with pytest.raises(ValueError):
        a.rotation[0, 0] = 2.0
    with pytest.raises(ValueError, match="not a rotation"):
        Pose(np.diag([1.0, 1.0, -1.0]), np.zeros(3))
    with pytest.raises(ValueError, match="translation"):
        Pose(np.eye(3), np.array([0.0, math.inf, 0.0]))
    with pytest.raises(ValueError, match="last row"):
        Pose.from_matrix4(np.ones((4, 4)))
