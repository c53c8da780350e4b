"""The one pose type of coatsim: an immutable rigid transform (rotation matrix, translation in mm).

``Pose`` is a thin frozen wrapper rather than ``mink.lie.SE3`` itself: coatsim's poses are
born as rotation matrices (frames, surface normals, O-A-T angles) and must give the same
matrix back bit for bit (an AS program written from a pose is compared by bytes), while SE3
stores a quaternion (a round trip through it moves the matrix by ~1e-16); SE3 also applies
to one vector at a time, where coatsim transforms whole paths. ``to_mink``/``from_mink``
convert at the IK boundary. Units: mm and radians.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from mink.lie import SE3

ORTHONORMAL_TOL = 1e-9  # |RᵀR − I| and |det R − 1| above this: not a rotation


class InvalidPose(ValueError):
    """Not a rigid transformation: a non-finite translation or a matrix that is not a rotation."""


def _frozen(array: np.ndarray) -> np.ndarray:
    out = np.array(array, dtype=float)  # a copy: the caller's array stays theirs
    out.flags.writeable = False
    return out


def check_rotation(rotation: np.ndarray) -> np.ndarray:
    """``rotation`` as a (3, 3) float array; ValueError unless it is a proper rotation."""
    r = np.asarray(rotation, dtype=float)
    if r.shape != (3, 3) or not np.isfinite(r).all():
        raise InvalidPose(f"a rotation is a finite 3x3 matrix, got shape {r.shape}")
    if np.abs(r.T @ r - np.eye(3)).max() > ORTHONORMAL_TOL or abs(np.linalg.det(r) - 1.0) > ORTHONORMAL_TOL:
        raise InvalidPose("the matrix is not a rotation (orthonormal with determinant +1)")
    return r


def skew(v: np.ndarray) -> np.ndarray:
    """Cross-product matrices of vectors (..., 3) -> (..., 3, 3)."""
    v = np.asarray(v, dtype=float)
    z = np.zeros(v.shape[:-1])
    return np.stack((np.stack((z, -v[..., 2], v[..., 1]), -1),
                     np.stack((v[..., 2], z, -v[..., 0]), -1),
                     np.stack((-v[..., 1], v[..., 0], z), -1)), -2)


def exp_rotation(rotvec: np.ndarray) -> np.ndarray:
    """Rotation matrices (..., 3, 3) of rotation vectors (..., 3) (axis · angle, rad; Rodrigues)."""
    v = np.asarray(rotvec, dtype=float)
    angle = np.linalg.norm(v, axis=-1)[..., None, None]
    k = skew(v)
    with np.errstate(divide="ignore", invalid="ignore"):
        a = np.where(angle > 1e-8, np.sin(angle) / angle, 1.0 - angle**2 / 6.0)
        b = np.where(angle > 1e-8, (1.0 - np.cos(angle)) / angle**2, 0.5 - angle**2 / 24.0)
    return np.eye(3) + a * k + b * (k @ k)


def log_rotation(rotation: np.ndarray) -> np.ndarray:
    """Rotation vector (3,) of a rotation matrix, angle in [0, π] (scipy's robust conversion)."""
    from scipy.spatial.transform import Rotation

    return Rotation.from_matrix(np.asarray(rotation, dtype=float)).as_rotvec()


def rotation_angle(r1: np.ndarray, r2: np.ndarray) -> float:
    """Angle (rad, in [0, π]) of the relative rotation r1ᵀ r2, accurate near 0 and near π."""
    rel = np.asarray(r1, dtype=float).T @ np.asarray(r2, dtype=float)
    cos_angle = (float(np.trace(rel)) - 1.0) / 2.0
    sin_angle = float(np.linalg.norm(rel - rel.T)) / (2.0 * math.sqrt(2.0))
    return math.atan2(sin_angle, cos_angle)


def slerp(r0: np.ndarray, r1: np.ndarray, u: np.ndarray | float) -> np.ndarray:
    """Rotations (n, 3, 3) at fractions ``u`` along the shortest rotation from ``r0`` to ``r1``:
    r0 · exp(u · log(r0ᵀ r1)), as a controller interpolates orientation between two poses
    (constant angular rate about one fixed axis). At exactly 180° the axis scipy picks is used."""
    u = np.atleast_1d(np.asarray(u, dtype=float))
    step = log_rotation(np.asarray(r0, float).T @ np.asarray(r1, float))
    return np.asarray(r0, float) @ exp_rotation(u[:, None] * step)


@dataclass(frozen=True, eq=False)
class Pose:
    """x ↦ rotation @ x + translation_mm: a frame's pose in its parent frame (mm).

    Compose with ``@`` (``a @ b`` applies ``b`` first), invert with ``inverse()``; points
    move with ``apply``, directions with ``apply_vectors``. The arrays are read-only copies.
    """

    rotation: np.ndarray
    translation_mm: np.ndarray

    def __post_init__(self) -> None:
        t = np.asarray(self.translation_mm, dtype=float)
        if t.shape != (3,) or not np.isfinite(t).all():
            raise InvalidPose(f"a translation is 3 finite numbers (mm), got {t}")
        object.__setattr__(self, "rotation", _frozen(check_rotation(self.rotation)))
        object.__setattr__(self, "translation_mm", _frozen(t))

    @classmethod
    def identity(cls) -> Pose:
        return cls(np.eye(3), np.zeros(3))

    @classmethod
    def from_translation(cls, translation_mm: np.ndarray) -> Pose:
        return cls(np.eye(3), translation_mm)

    @classmethod
    def from_matrix4(cls, matrix: np.ndarray) -> Pose:
        """From a 4x4 homogeneous matrix (last row 0, 0, 0, 1)."""
        m = np.asarray(matrix, dtype=float)
        if m.shape != (4, 4) or not np.allclose(m[3], (0.0, 0.0, 0.0, 1.0), rtol=0.0, atol=ORTHONORMAL_TOL):
            raise ValueError("a homogeneous transform is a 4x4 matrix with last row 0, 0, 0, 1")
        return cls(m[:3, :3], m[:3, 3])

    def as_matrix4(self) -> np.ndarray:
        m = np.eye(4)
        m[:3, :3], m[:3, 3] = self.rotation, self.translation_mm
        return m

    @classmethod
    def from_mink(cls, se3: SE3) -> Pose:
        """From ``mink.lie.SE3`` (its translation taken as mm)."""
        return cls(se3.rotation().as_matrix(), se3.translation())

    def to_mink(self) -> SE3:
        """As ``mink.lie.SE3`` (translation unchanged: convert mm to m at the robot boundary)."""
        from mink.lie import SE3, SO3

        return SE3.from_rotation_and_translation(SO3.from_matrix(np.array(self.rotation)), np.array(self.translation_mm))

    def __matmul__(self, other: Pose) -> Pose:
        return Pose(self.rotation @ other.rotation, self.rotation @ other.translation_mm + self.translation_mm)

    def inverse(self) -> Pose:
        rt = self.rotation.T
        return Pose(rt, -(rt @ self.translation_mm))

    def apply(self, points: np.ndarray) -> np.ndarray:
        """Points (3,) or (n, 3) in this frame's parent frame."""
        p = np.asarray(points, dtype=float)
        return p @ self.rotation.T + self.translation_mm

    def apply_vectors(self, vectors: np.ndarray) -> np.ndarray:
        """Directions (3,) or (n, 3) rotated only."""
        return np.asarray(vectors, dtype=float) @ self.rotation.T

    def interpolate(self, other: Pose, u: float) -> Pose:
        """The pose a fraction ``u`` of the way to ``other``: translation linear, orientation
        by slerp (as a controller moves between two taught poses)."""
        t = (1.0 - u) * self.translation_mm + u * other.translation_mm
        return Pose(slerp(self.rotation, other.rotation, u)[0], t)

    def angle_to(self, other: Pose) -> float:
        """Angle (rad) between the two orientations."""
        return rotation_angle(self.rotation, other.rotation)

    def is_close(self, other: Pose, tol_mm: float = 1e-9, tol_rad: float = 1e-9) -> bool:
        return (float(np.abs(self.translation_mm - other.translation_mm).max()) <= tol_mm
                and self.angle_to(other) <= tol_rad)
