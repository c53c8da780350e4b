"""URScript values and the functions on them that need no robot: poses, math, lists.

A pose ``p[x, y, z, rx, ry, rz]`` is metres and a rotation vector (radians, axis · angle) in the
frame it is given in; :class:`PoseValue` holds it and converts to coatsim's :class:`Pose` (mm).
Pose functions follow the URScript manual: ``pose_trans(a, b)`` is the frame product a·b,
``pose_inv``, ``pose_add(a, b)`` adds the positions and multiplies the rotations (R_a·R_b),
``pose_sub(to, from)`` subtracts the positions and gives R_fromᵀ·R_to (so that
``pose_add(from, pose_sub(to, from))`` is ``to``), ``interpolate_pose`` is linear in position and spherical in rotation;
``rpy2rotvec`` / ``rotvec2rpy`` use roll-pitch-yaw about the fixed x, y, z axes.
"""

from __future__ import annotations

import math
from typing import Callable, Sequence

import numpy as np

from coatsim.geometry.space.pose import InvalidPose, Pose
from coatsim.geometry.space.rotations import matrix_to_rotvec, matrix_to_wpr, rotvec_to_matrix, wpr_to_matrix

M_TO_MM = 1000.0


class PoseValue(tuple):
    """A URScript pose: six floats, metres and a rotation vector (rad)."""

    def __new__(cls, values: Sequence[float]) -> "PoseValue":
        items = tuple(float(v) for v in values)
        if len(items) != 6:
            raise ValueError(f"a pose has 6 values, not {len(items)}")
        return super().__new__(cls, items)

    def pose(self) -> Pose:
        """As coatsim's Pose (mm); ValueError unless finite."""
        if not all(math.isfinite(v) for v in self):
            raise ValueError("a pose's values must be finite")
        try:
            return Pose(rotvec_to_matrix(*self[3:]), np.array(self[:3]) * M_TO_MM)
        except InvalidPose as exc:
            raise ValueError(str(exc)) from None

    @classmethod
    def of(cls, pose: Pose) -> "PoseValue":
        return cls(tuple(pose.translation_mm / M_TO_MM) + matrix_to_rotvec(pose.rotation))

    def __repr__(self) -> str:
        return "p[" + ", ".join(f"{v:g}" for v in self) + "]"


class FramedPose(PoseValue):
    """A pose made as ``pose_trans(feature, p)`` with ``feature`` a pose variable (a Polyscope
    feature, a plane, the workpiece frame): the user frame ``p`` is given in, which the reading
    reports for each move so that a converted program keeps it."""

    feature: PoseValue

    def __new__(cls, values: Sequence[float], feature: PoseValue) -> "FramedPose":
        made = super().__new__(cls, values)
        made.feature = feature
        return made


class PoseJoints(tuple):
    """The joint solution of a pose (``get_inverse_kin(p)``): a movej goes to the pose."""

    def __new__(cls, pose: PoseValue) -> "PoseJoints":
        return super().__new__(cls, (pose,))

    @property
    def target(self) -> PoseValue:
        return self[0]


def _poses(*values) -> list[Pose]:
    out = []
    for v in values:
        if not isinstance(v, PoseValue):
            raise TypeError("expects poses p[…]")
        out.append(v.pose())
    return out


def pose_trans(a, b) -> PoseValue:
    pa, pb = _poses(a, b)
    return PoseValue.of(pa @ pb)


def pose_inv(a) -> PoseValue:
    return PoseValue.of(_poses(a)[0].inverse())


def pose_add(a, b) -> PoseValue:
    pa, pb = _poses(a, b)
    return PoseValue.of(Pose(pa.rotation @ pb.rotation, pa.translation_mm + pb.translation_mm))


def pose_sub(a, b) -> PoseValue:
    pa, pb = _poses(a, b)
    return PoseValue.of(Pose(pb.rotation.T @ pa.rotation, pa.translation_mm - pb.translation_mm))


def interpolate_pose(a, b, alpha) -> PoseValue:
    pa, pb = _poses(a, b)
    return PoseValue.of(pa.interpolate(pb, float(alpha)))


def point_dist(a, b) -> float:
    pa, pb = _poses(a, b)
    return float(np.linalg.norm(pa.translation_mm - pb.translation_mm)) / M_TO_MM


def rpy2rotvec(rpy) -> list:
    r, p, y = (math.degrees(float(v)) for v in rpy)
    return list(matrix_to_rotvec(wpr_to_matrix(r, p, y)))


def rotvec2rpy(v) -> list:
    return [math.radians(a) for a in matrix_to_wpr(rotvec_to_matrix(*(float(x) for x in v)))]


def norm(value) -> float:
    if isinstance(value, (list, tuple)):
        return float(np.linalg.norm([float(v) for v in value]))
    return abs(float(value))


def _to_str(value) -> str:
    if isinstance(value, bool):
        return "True" if value else "False"
    return str(value)


def _length(value) -> int:
    if not isinstance(value, (list, str, tuple)):
        raise TypeError("length() takes a list or a string")
    return len(value)


#: Functions of values alone, by name.
PURE: dict[str, Callable] = {
    "sin": math.sin, "cos": math.cos, "tan": math.tan, "asin": math.asin, "acos": math.acos, "atan": math.atan,
    "atan2": math.atan2, "sqrt": math.sqrt, "pow": math.pow, "log": lambda b, f: math.log(f, b), "floor": math.floor,
    "ceil": math.ceil, "d2r": math.radians, "r2d": math.degrees, "norm": norm, "to_num": float, "to_str": _to_str,
    "length": _length, "pose_trans": pose_trans, "pose_inv": pose_inv, "pose_add": pose_add, "pose_sub": pose_sub,
    "interpolate_pose": interpolate_pose, "point_dist": point_dist, "rpy2rotvec": rpy2rotvec,
    "rotvec2rpy": rotvec2rpy, "is_within_safety_limits": lambda *a: True,
}
