"""What a program asks of the robot while it runs: forward kinematics, HOME, joint values as
poses, HERE and #HERE. A part of the interpreter (``Interpreter`` derives from it), kept apart
because it is the one place the interpreter needs the cell's kinematics."""

from __future__ import annotations

import numpy as np

from coatsim.core.errors import CoatsimError
from coatsim.geometry.space.pose import Pose
from coatsim.languages.kawasaki_as import ast
from coatsim.languages.kawasaki_as.values import PoseJoints
from coatsim.path.toolpath import Kinematics


class RobotQueries:
    """Robot-state queries of a running program. The interpreter provides ``kinematics``,
    ``controller``, ``base``, ``line`` and its ``where``/``error``/``failure``/``warn``."""

    def need_kinematics(self, what: str) -> Kinematics:
        if self.kinematics is None:
            raise self.failure(f"{what} needs the cell's kinematics; run it with a cell model")
        return self.kinematics

    def fk(self, q: np.ndarray, what: str):
        """Forward kinematics of ``q`` (rad): the TCP pose in the robot base frame."""
        kin = self.need_kinematics(what)
        try:
            return kin.forward(q, self.controller.tool)
        except CoatsimError as exc:
            raise exc.prefixed(self.where()) from None

    def home_joints(self, number: int) -> np.ndarray:
        """HOME n's joints (rad): the cell's keyframe, else the joint value ``#home<n>`` given from
        outside (a home pose taught on the pendant is kept by the controller: an unknown)."""
        q = self.need_kinematics("HOME").home(number)
        if q is None:
            return self.joints_rad(self.eval.joints(ast.Name(f"#home{number}")))
        return np.asarray(q, dtype=float)

    def home_pose(self):
        """The pose and joints every program starts from: the cell's home."""
        q = self.home_joints(1)
        return self.fk(q, "the start pose"), q

    def joints_rad(self, values: tuple[float, ...]) -> np.ndarray:
        if len(values) < 6:
            raise self.error(f"a joint value for this six-axis arm needs 6 values, found {len(values)}")
        if len(values) > 6:
            self.warn("external-axes", f"joint values beyond the 6th (external axes) are ignored ({len(values)} given)")
        return np.radians(np.array(values[:6], dtype=float))

    def joint_frame(self, values: tuple[float, ...] | PoseJoints) -> Pose:
        """A joint value as a transformation relative to BASE (forward kinematics, or the pose
        a POINT #j = p gave it)."""
        if isinstance(values, PoseJoints):
            return self.base.inverse() @ values.frame
        pose = self.fk(self.joints_rad(values), "a joint value used as a pose")
        return self.base.inverse() @ pose

    def here(self) -> Pose:
        if self.controller.current is None and self.kinematics is None:
            raise self.failure("HERE before the first motion needs the cell's kinematics (the home pose)")
        current = self.controller.need_current("HERE", self.line)
        return self.base.inverse() @ current

    def here_value(self) -> tuple[float, ...] | PoseJoints:
        """The joint value where the robot is (HERE #j, #HERE, #DEST): its angles, or after a
        Cartesian motion the pose it is at (the angles need the inverse kinematics)."""
        if self.controller.current_joints is None and self.controller.current is not None:
            return PoseJoints(self.controller.current, None)
        return self.here_joints()

    def here_joints(self) -> tuple[float, ...]:
        if self.controller.current is None and self.kinematics is not None:
            self.controller.need_current("#HERE", self.line)
        q = self.controller.current_joints
        if q is None:
            raise self.failure("the joint angles after a Cartesian motion need the inverse kinematics of the arm, "
                               "which the interpreter does not solve")
        return tuple(float(v) for v in np.degrees(q))
