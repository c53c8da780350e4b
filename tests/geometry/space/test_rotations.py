"""Rotation conventions: each pair round-trips through the rotation matrix (to 1e-9) for any
orientation, the singular ones included; O-A-T matches the first AS writer bit for bit."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from coatsim.geometry.space import rotations as rot
from coatsim.geometry.space.pose import exp_rotation

angle = st.floats(-180.0, 180.0, allow_nan=False)
unit = st.floats(-1.0, 1.0, allow_nan=False)
tiny = st.sampled_from([0.0, 1e-15, 1e-13, 1e-11, 1e-9, 1e-7, 1e-5, 1e-3])  # rad off a singularity


def close(r1: np.ndarray, r2: np.ndarray) -> bool:
    return float(np.abs(np.asarray(r1) - np.asarray(r2)).max()) <= 1e-9


@st.composite
def rotations(draw) -> np.ndarray:
    """Any rotation: a random axis-angle, or one of the singular families at and near their
    limit, with the round-off of a product of rotations (``base.T @ base``) that makes the
    coupled angles ill-conditioned there (the first AS writer's angles rebuilt such matrices
    only to ~5e-5)."""
    axis = np.array([draw(unit), draw(unit), draw(unit)])
    if np.linalg.norm(axis) < 1e-3:
        axis = np.array([0.0, 0.0, 1.0])
    theta = draw(st.floats(0.0, math.pi))
    base = exp_rotation(axis / np.linalg.norm(axis) * theta)
    kind = draw(st.sampled_from(["any", "oat0", "oat180", "b90", "b-90", "pi"]))
    eps, a, b = draw(tiny), math.radians(draw(angle)), math.radians(draw(angle))
    if kind == "oat0":
        return rot.rot_z(a) @ rot.rot_y(eps) @ rot.rot_z(b) @ base.T @ base
    if kind == "oat180":
        return rot.rot_z(a) @ rot.rot_y(math.pi - eps) @ rot.rot_z(b) @ base.T @ base
    if kind in ("b90", "b-90"):
        sign = 1.0 if kind == "b90" else -1.0
        return rot.rot_z(a) @ rot.rot_y(sign * (math.pi / 2 - eps)) @ rot.rot_x(b) @ base.T @ base
    if kind == "pi":
        return exp_rotation(axis / np.linalg.norm(axis) * (math.pi - eps))
    return base


@settings(max_examples=400, deadline=None)
@given(rotations())
def test_oat_round_trip(r):
    o, a, t = rot.matrix_to_oat(r)
    assert 0.0 <= a <= 180.0 and -180.0 < o <= 180.0 and -180.0 < t <= 180.0
    assert close(rot.oat_to_matrix(o, a, t), r)


@settings(max_examples=400, deadline=None)
@given(rotations())
def test_abc_round_trip(r):
    a, b, c = rot.matrix_to_abc(r)
    assert -90.0 <= b <= 90.0 and -180.0 < a <= 180.0 and -180.0 < c <= 180.0
    assert close(rot.abc_to_matrix(a, b, c), r)


@settings(max_examples=400, deadline=None)
@given(rotations())
def test_wpr_round_trip(r):
    w, p, rr = rot.matrix_to_wpr(r)
    assert -90.0 <= p <= 90.0
    assert close(rot.wpr_to_matrix(w, p, rr), r)


@settings(max_examples=400, deadline=None)
@given(rotations())
def test_quaternion_round_trip(r):
    q = rot.matrix_to_quaternion(r)
    assert q[0] >= 0.0 and abs(math.fsum(v * v for v in q) - 1.0) < 1e-12
    assert close(rot.quaternion_to_matrix(*q), r)


@settings(max_examples=400, deadline=None)
@given(rotations())
def test_rotvec_round_trip(r):
    v = rot.matrix_to_rotvec(r)
    assert np.linalg.norm(v) <= math.pi + 1e-12
    assert close(rot.rotvec_to_matrix(*v), r)



@pytest.mark.parametrize("a_deg", [0.0, 180.0])
def test_oat_singular_choice(a_deg):
    """At A = 0 / 180 T is 0 and O carries the rotation about z (the AS writer's choice)."""
    o, a, t = rot.matrix_to_oat(rot.oat_to_matrix(30.0, a_deg, 20.0))
    assert t == 0.0 and a == pytest.approx(a_deg)
    assert o == pytest.approx(50.0 if a_deg == 0.0 else 10.0)


def test_conventions_analytic():
    """Each convention's meaning, on a quarter turn about one axis."""
    qz = rot.rot_z(math.pi / 2)
    assert close(rot.abc_to_matrix(90, 0, 0), qz) and close(rot.wpr_to_matrix(0, 0, 90), qz)
    assert close(rot.abc_to_matrix(0, 0, 90), rot.rot_x(math.pi / 2))
    assert close(rot.wpr_to_matrix(90, 0, 0), rot.rot_x(math.pi / 2))
    s = math.sqrt(0.5)
    assert close(rot.quaternion_to_matrix(s, 0, 0, s), qz)
    assert close(rot.rotvec_to_matrix(0, 0, math.pi / 2), qz)
    # intrinsic z-y'-x'' (KRL) equals extrinsic x-y-z (Fanuc) with the angles reversed
    assert close(rot.abc_to_matrix(10, 20, 30), rot.wpr_to_matrix(30, 20, 10))
    # and KRL's B turns about the *new* y: Rz(A) then Ry(B)
    assert close(rot.abc_to_matrix(90, 90, 0), qz @ rot.rot_y(math.pi / 2))
    assert rot.matrix_to_quaternion(rot.quaternion_to_matrix(-s, 0, 0, -s))[0] > 0  # q1 >= 0


def test_gimbal_lock_choice():
    a, b, c = rot.matrix_to_abc(rot.abc_to_matrix(40.0, 90.0, 25.0))
    assert c == 0.0 and b == pytest.approx(90.0) and a == pytest.approx(15.0)
    w, p, r = rot.matrix_to_wpr(rot.wpr_to_matrix(25.0, -90.0, 40.0))
    assert w == 0.0 and p == pytest.approx(-90.0) and r == pytest.approx(65.0)


def test_bad_quaternion_and_rotvec():
    with pytest.raises(ValueError, match="not all zero"):
        rot.quaternion_to_matrix(0, 0, 0, 0)
    with pytest.raises(ValueError, match="finite"):
        rot.rotvec_to_matrix(math.nan, 0, 0)
