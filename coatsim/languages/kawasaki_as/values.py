"""Run-time values of the AS interpreter: transformations and joint values.

A transformation is coatsim's pose type (a rigid frame: rotation, translation mm), written as x,
y, z, O-A-T; a joint value holds the joint angles in degrees as the program writes them. A
computation that leaves the finite rotations (an infinite coordinate) raises
:class:`~coatsim.geometry.space.pose.InvalidPose`, which the interpreter reports at its line.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from coatsim.core.numeric import TINY
from coatsim.geometry.space.pose import Pose


IDENTITY = Pose.identity()


@dataclass(frozen=True, eq=False)
class PoseJoints:
    """A joint value known by the pose it reaches (``POINT #j = p [, #ref]``): ``frame`` in the
    robot base frame, ``reference`` the joint value (deg) the program gave to pick the arm's
    configuration. A JMOVE to it moves to the pose (the cell's inverse kinematics picks the
    configuration); its joint angles are unknown to the interpreter."""

    frame: Pose
    reference: tuple[float, ...] | None


def rotation_about(axis: int, degrees: float) -> Pose:
    """RX / RY / RZ: a pure rotation about the x (0), y (1) or z (2) axis."""
    c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))
    i, j = [(1, 2), (2, 0), (0, 1)][axis]
    r = np.eye(3)
    r[i, i], r[i, j], r[j, i], r[j, j] = c, -s, s, c
    return Pose(r, np.zeros(3))


def average(a: Pose, b: Pose) -> Pose:
    """AVE_TRANS(a, b): the mean of the positions and the rotation halfway from a's to b's."""
    from scipy.spatial.transform import Rotation, Slerp

    half = Slerp([0.0, 1.0], Rotation.from_matrix(np.stack([a.rotation, b.rotation])))([0.5]).as_matrix()[0]
    return Pose(half, (a.translation_mm + b.translation_mm) / 2.0)


def frame_from_points(p1: np.ndarray, p2: np.ndarray, p3: np.ndarray, origin: np.ndarray) -> Pose | None:
    """FRAME(p1, p2, p3, p4): x along p1 -> p2, y towards p3 in the plane of the three, z = x by y,
    origin at p4; None when the points do not span a plane."""
    x = p2 - p1
    nx = float(np.linalg.norm(x))
    if nx < TINY:
        return None
    x = x / nx
    y = (p3 - p1) - float((p3 - p1) @ x) * x
    ny = float(np.linalg.norm(y))
    if ny < TINY:
        return None
    y = y / ny
    return Pose(np.column_stack((x, y, np.cross(x, y))), np.asarray(origin, dtype=float))
