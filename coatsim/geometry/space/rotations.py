"""Robot languages' orientation conventions <-> rotation matrices, one function pair each.

Inside coatsim an orientation is a rotation matrix (``Pose.rotation``); a language's angles
exist only in its writer and reader, which convert here. Angles are degrees except the
Universal Robots rotation vector (radians). Sources: ``robot_languages.md`` (the project's
reference notes on the vendors' manuals) and the vendors' pose-format pages:

- Kawasaki AS O-A-T: z-y'-z'' Euler, R = Rz(O)·Ry(A)·Rz(T).
- ABB RAPID ``orient``: unit quaternion [q1, q2, q3, q4] = [w, x, y, z]; written with q1 >= 0.
- KUKA KRL A-B-C: A about z, B about the new y, C about the newer x (intrinsic z-y'-x''),
  R = Rz(A)·Ry(B)·Rx(C).
- Fanuc W-P-R: W about the fixed x, then P about the fixed y, then R about the fixed z
  (extrinsic x-y-z), R = Rz(R)·Ry(P)·Rx(W): the same matrix as KRL's with A = R, B = P, C = W.
- Universal Robots: rotation vector [rx, ry, rz] = angle · unit axis, angle in [0, π] (rad).

Where the angles are not unique (O-A-T at A = 0 or 180°, A-B-C at B = ±90°, W-P-R at
P = ±90°) the decomposition still returns angles that rebuild the same matrix (to ~1e-15;
the sum or difference of the two coupled angles comes from the well-conditioned part of the
matrix), with the last angle (T, C, W) set to 0 exactly at the singular orientation.
"""

from __future__ import annotations

import math

import numpy as np

from coatsim.geometry.space.pose import exp_rotation, log_rotation

# Below this sin(A) (or cos(B)) the orientation is treated as exactly singular: the last
# angle is 0. At 1e-12 the rebuilt matrix differs by about 1e-12, far below the 6 decimals
# of degrees a program carries. (Kawasaki: coatsim.path.oat's choice, kept bit for bit.)
GIMBAL_SIN = 1e-12
# Between GIMBAL_SIN and this, the O-A-T pair is corrected from the well-conditioned block
# (O and T alone are ill-conditioned there: their errors grow as 1e-16 / sin A).
NEAR_GIMBAL_SIN = 1e-6


def rot_x(angle: float) -> np.ndarray:
    """Rotation about x by ``angle`` rad."""
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def rot_y(angle: float) -> np.ndarray:
    """Rotation about y by ``angle`` rad."""
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def rot_z(angle: float) -> np.ndarray:
    """Rotation about z by ``angle`` rad."""
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def wrap_deg(angle: float) -> float:
    """Angle in degrees wrapped into (-180, 180], never -0.0."""
    wrapped = math.fmod(angle, 360.0)
    if wrapped <= -180.0:
        wrapped += 360.0
    elif wrapped > 180.0:
        wrapped -= 360.0
    return wrapped + 0.0


def _wrap_rad(angle: float) -> float:
    return math.remainder(angle, 2.0 * math.pi)


# ------------------------------------------------------------------ Kawasaki AS: O-A-T


def oat_to_matrix(o_deg: float, a_deg: float, t_deg: float) -> np.ndarray:
    """Rz(O)·Ry(A)·Rz(T) for Kawasaki O-A-T in degrees."""
    return rot_z(math.radians(o_deg)) @ rot_y(math.radians(a_deg)) @ rot_z(math.radians(t_deg))


def matrix_to_oat(rotation: np.ndarray) -> tuple[float, float, float]:
    """Kawasaki O-A-T (deg) of a rotation: A in [0, 180], O and T in (-180, 180].

    At A = 0 or 180 (sin A < 1e-12) T is 0 and O carries the rotation about z; elsewhere the
    angles are those of coatsim's first AS writer to the bit, except within 1e-6 rad of the
    singular orientations, where O + T (A near 0) or O − T (A near 180) is taken from the 2x2
    block so that the angles still rebuild the matrix.
    """
    r = np.asarray(rotation, dtype=float)
    sin_a = math.hypot(r[0, 2], r[1, 2])
    a = math.atan2(sin_a, r[2, 2])
    if sin_a < GIMBAL_SIN:
        o = math.atan2(-r[0, 1], r[1, 1])
        t = 0.0
    else:
        o = math.atan2(r[1, 2], r[0, 2])
        t = math.atan2(r[2, 1], -r[2, 0])
        if sin_a < NEAR_GIMBAL_SIN:
            if r[2, 2] > 0:  # (1 + cos A)·(cos, sin)(O + T) is the block's well-known part
                shift = _wrap_rad(math.atan2(r[1, 0] - r[0, 1], r[0, 0] + r[1, 1]) - (o + t)) / 2
                o, t = o + shift, t + shift
            else:  # (1 − cos A)·(cos, sin)(O − T)
                shift = _wrap_rad(math.atan2(-(r[1, 0] + r[0, 1]), r[1, 1] - r[0, 0]) - (o - t)) / 2
                o, t = o + shift, t - shift
    return wrap_deg(math.degrees(o)), math.degrees(a), wrap_deg(math.degrees(t))


# ------------------------------------------------------------------ ABB RAPID: quaternion


def quaternion_to_matrix(q1: float, q2: float, q3: float, q4: float) -> np.ndarray:
    """Rotation of the RAPID quaternion [q1, q2, q3, q4] = [w, x, y, z] (normalised first;
    ValueError for a zero or non-finite one: the reader decides how far from unit it accepts)."""
    q = np.array([q1, q2, q3, q4], dtype=float)
    norm = float(np.linalg.norm(q))
    if not (math.isfinite(norm) and norm > 0.0):
        raise ValueError(f"a quaternion needs finite components, not all zero: {[q1, q2, q3, q4]}")
    w, x, y, z = q / norm
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
    ])


def matrix_to_quaternion(rotation: np.ndarray) -> tuple[float, float, float, float]:
    """RAPID quaternion (q1, q2, q3, q4) = (w, x, y, z) of a rotation, unit, with q1 >= 0
    (at q1 = 0, a half turn, the first non-zero of q2..q4 is positive)."""
    from scipy.spatial.transform import Rotation

    q = Rotation.from_matrix(np.asarray(rotation, dtype=float)).as_quat(canonical=True, scalar_first=True)
    return tuple(float(v) + 0.0 for v in q)  # type: ignore[return-value]


# ------------------------------------------------------------------ z-y'-x'' (KRL A-B-C, Fanuc W-P-R)


def _zyx_to_matrix(z_deg: float, y_deg: float, x_deg: float) -> np.ndarray:
    return rot_z(math.radians(z_deg)) @ rot_y(math.radians(y_deg)) @ rot_x(math.radians(x_deg))


def _matrix_to_zyx(rotation: np.ndarray) -> tuple[float, float, float]:
    """(z, y, x) angles in degrees of R = Rz(z)·Ry(y)·Rx(x): y in [-90, 90], z and x in
    (-180, 180]. The coupled pair comes from the well-conditioned block:
    (1 + sin y)·(sin, cos)(z − x) and (1 − sin y)·(sin, cos)(z + x); x = 0 at y = ±90."""
    r = np.asarray(rotation, dtype=float)
    cos_y = math.hypot(r[0, 0], r[1, 0])
    y = math.atan2(-r[2, 0], cos_y)
    if y >= 0:  # z − x
        coupled = math.atan2(r[1, 2] - r[0, 1], r[0, 2] + r[1, 1])
    else:  # z + x
        coupled = math.atan2(-(r[1, 2] + r[0, 1]), r[1, 1] - r[0, 2])
    if cos_y < GIMBAL_SIN:
        z, x = coupled, 0.0
    else:
        z = math.atan2(r[1, 0], r[0, 0])
        x = z - coupled if y >= 0 else coupled - z
    return wrap_deg(math.degrees(z)), math.degrees(y), wrap_deg(math.degrees(x))


def abc_to_matrix(a_deg: float, b_deg: float, c_deg: float) -> np.ndarray:
    """Rz(A)·Ry(B)·Rx(C) for KUKA A-B-C in degrees."""
    return _zyx_to_matrix(a_deg, b_deg, c_deg)


def matrix_to_abc(rotation: np.ndarray) -> tuple[float, float, float]:
    """KUKA A-B-C (deg) of a rotation: B in [-90, 90], A and C in (-180, 180]; C = 0 at B = ±90."""
    return _matrix_to_zyx(rotation)


def wpr_to_matrix(w_deg: float, p_deg: float, r_deg: float) -> np.ndarray:
    """Rz(R)·Ry(P)·Rx(W) for Fanuc W-P-R in degrees (fixed axes x, then y, then z)."""
    return _zyx_to_matrix(r_deg, p_deg, w_deg)


def matrix_to_wpr(rotation: np.ndarray) -> tuple[float, float, float]:
    """Fanuc W-P-R (deg) of a rotation: P in [-90, 90], W and R in (-180, 180]; W = 0 at P = ±90."""
    r, p, w = _matrix_to_zyx(rotation)
    return w, p, r


# ------------------------------------------------------------------ Universal Robots: rotation vector


def rotvec_to_matrix(rx: float, ry: float, rz: float) -> np.ndarray:
    """Rotation of the UR rotation vector (axis · angle, rad)."""
    v = np.array([rx, ry, rz], dtype=float)
    if not np.isfinite(v).all():
        raise ValueError(f"a rotation vector needs finite components: {[rx, ry, rz]}")
    return exp_rotation(v)


def matrix_to_rotvec(rotation: np.ndarray) -> tuple[float, float, float]:
    """UR rotation vector (rad) of a rotation: angle in [0, π] (at π either axis sign is the
    same rotation; the one scipy returns is kept)."""
    return tuple(float(v) + 0.0 for v in log_rotation(rotation))  # type: ignore[return-value]
