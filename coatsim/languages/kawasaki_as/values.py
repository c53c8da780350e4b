"""Run-time values of the AS interpreter: transformations (poses) and joint values.

A transformation is a rigid frame (rotation (3, 3), translation (3,) mm) written as x, y, z,
O-A-T; a joint value holds the joint angles in degrees as the program writes them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from coatsim.path.oat import matrix_to_oat, oat_to_matrix
from coatsim.path.toolpath import Pose


@dataclass(frozen=True, eq=False)
class Frame:
    """Rigid transformation: rotation ``r`` (3, 3), translation ``p`` (3,) mm."""

    r: np.ndarray
    p: np.ndarray

    @classmethod
    def from_xyzoat(cls, x: float, y: float, z: float, o: float, a: float, t: float) -> Frame:
        return cls(oat_to_matrix(o, a, t), np.array([x, y, z], dtype=float))

    @classmethod
    def from_pose(cls, pose: Pose) -> Frame:
        return cls(np.asarray(pose.rotation, dtype=float), np.asarray(pose.position, dtype=float))

    def __mul__(self, other: Frame) -> Frame:
        return Frame(self.r @ other.r, self.p + self.r @ other.p)

    def inverse(self) -> Frame:
        rt = self.r.T
        return Frame(rt, -(rt @ self.p))

    def xyzoat(self) -> tuple[float, float, float, float, float, float]:
        o, a, t = matrix_to_oat(self.r)
        return (float(self.p[0]), float(self.p[1]), float(self.p[2]), o, a, t)

    def pose(self) -> Pose:
        return Pose(self.p.copy(), self.r.copy())

    def is_finite(self) -> bool:
        return math.isfinite(float(self.p.sum()) + float(self.r.sum()))


IDENTITY = Frame(np.eye(3), np.zeros(3))


def rotation_about(axis: int, degrees: float) -> Frame:
    """RX / RY / RZ: a pure rotation about the x (0), y (1) or z (2) axis."""
    c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))
    i, j = [(1, 2), (2, 0), (0, 1)][axis]
    r = np.eye(3)
    r[i, i], r[i, j], r[j, i], r[j, j] = c, -s, s, c
    return Frame(r, np.zeros(3))


def frame_from_points(p1: np.ndarray, p2: np.ndarray, p3: np.ndarray, origin: np.ndarray) -> Frame | None:
    """FRAME(p1, p2, p3, p4): x along p1 -> p2, y towards p3 in the plane of the three, z = x by y,
    origin at p4; None when the points do not span a plane."""
    x = p2 - p1
    nx = float(np.linalg.norm(x))
    if nx < 1e-9:
        return None
    x = x / nx
    y = (p3 - p1) - float((p3 - p1) @ x) * x
    ny = float(np.linalg.norm(y))
    if ny < 1e-9:
        return None
    y = y / ny
    return Frame(np.column_stack((x, y, np.cross(x, y))), np.asarray(origin, dtype=float))
