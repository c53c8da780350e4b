"""Kawasaki O-A-T angles <-> rotation matrices.

O-A-T is the z-y'-z'' Euler convention, R = Rz(O) . Ry(A) . Rz(T), angles in degrees.
At A = 0 only O + T is defined and at A = 180 only O - T (gimbal lock), so poses must be
compared by rotation matrix; :func:`matrix_to_oat` returns T = 0 in those two cases.
"""

from __future__ import annotations

import math

import numpy as np

# Below this sin(A) the decomposition treats the pose as gimbal-locked.  At 1e-12 the
# rebuilt matrix differs from the input by about 1e-12, far below the 6-decimal degrees
# the AS writer emits.
_GIMBAL_SIN = 1e-12


def rot_z(angle: float) -> np.ndarray:
    """Rotation about z by ``angle`` rad."""
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def rot_y(angle: float) -> np.ndarray:
    """Rotation about y by ``angle`` rad."""
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def oat_to_matrix(o_deg: float, a_deg: float, t_deg: float) -> np.ndarray:
    """Rotation matrix Rz(O) . Ry(A) . Rz(T) for O-A-T in degrees."""
    return rot_z(math.radians(o_deg)) @ rot_y(math.radians(a_deg)) @ rot_z(math.radians(t_deg))


def _wrap_deg(angle: float) -> float:
    """Angle in degrees wrapped into (-180, 180]."""
    wrapped = math.fmod(angle, 360.0)
    if wrapped <= -180.0:
        wrapped += 360.0
    elif wrapped > 180.0:
        wrapped -= 360.0
    return wrapped + 0.0  # no negative zero


def matrix_to_oat(rotation: np.ndarray) -> tuple[float, float, float]:
    """O-A-T in degrees of a rotation matrix: A in [0, 180], O and T in (-180, 180].

    In the gimbal cases (A = 0 or 180) T is 0 and O carries the whole rotation about z.
    """
    r = np.asarray(rotation, dtype=float)
    sin_a = math.hypot(r[0, 2], r[1, 2])
    a = math.atan2(sin_a, r[2, 2])
    if sin_a < _GIMBAL_SIN:
        o = math.atan2(-r[0, 1], r[1, 1])
        t = 0.0
    else:
        o = math.atan2(r[1, 2], r[0, 2])
        t = math.atan2(r[2, 1], -r[2, 0])
    return _wrap_deg(math.degrees(o)), math.degrees(a), _wrap_deg(math.degrees(t))


def rotation_angle(r1: np.ndarray, r2: np.ndarray) -> float:
    """Angle (rad) of the relative rotation between two rotation matrices."""
    rel = np.asarray(r1, dtype=float).T @ np.asarray(r2, dtype=float)
    cos_angle = (float(np.trace(rel)) - 1.0) / 2.0
    sin_angle = float(np.linalg.norm(rel - rel.T)) / (2.0 * math.sqrt(2.0))
    return math.atan2(sin_angle, cos_angle)
