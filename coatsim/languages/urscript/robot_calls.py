"""The robot's URScript functions: motions, the TCP, outputs and inputs, waits, the robot's state.

- ``movel(pose, a=1.2, v=0.25, t=0, r=0)`` and ``movep(pose, a=1.2, v=0.25, r=0)``: straight
  moves at ``v`` m/s (``t`` > 0: the time the move takes); ``movec(pose_via, pose_to, a=1.2,
  v=0.25, r=0, mode=0)``: the arc from the current pose through the via's position to
  ``pose_to``, the orientation interpolated to pose_to's (mode 0) or kept fixed to the arc's
  tangent, turning with the path (mode 1); ``movej(q, a=1.4, v=1.05, t=0, r=0)``: a joint move to
  joint values q (rad; needs the cell) or to a pose; its ``v`` (rad/s) is taken as a cap on the
  TCP speed of ``v · JOINT_MM_PER_RAD`` mm/s. Blending as :mod:`.blend` describes; the
  accelerations ``a`` are the controller's to keep, the twin keeps the cell's limits. A target
  given as joint values (movel, movec) needs the cell.
- ``set_tcp(pose)`` sets the TCP; ``set_digital_out(n, b)`` / ``set_standard_digital_out`` switch
  output n (the gun when n is its output; from the next motion, instructions run in order),
  ``set_configurable_digital_out``, ``set_tool_digital_out`` other outputs; ``get_*digital_in(n)``
  read the inputs given (else False, with a warning); ``sleep(t)`` stops the robot and rests,
  ``stopl``/``stopj`` stop it. ``get_actual_tcp_pose``, ``get_target_tcp_pose``,
  ``get_actual_joint_positions``, ``get_inverse_kin``, ``get_forward_kin``, ``get_tcp_offset``
  give the robot's state as the twin knows it.
- Speed and force control (``speedl``, ``servoj``, ``force_mode`` …) cannot be simulated: an
  ExecutionError. Set-up calls without motion (payload, gravity, tool voltage, analog domains,
  messages) pass silently; any other function is noted once and gives nothing.
"""

from __future__ import annotations

import math
from typing import Callable, Optional

import numpy as np

from coatsim.core.errors import ExecutionError, InputError
from coatsim.geometry.space.pose import Pose, exp_rotation
from coatsim.geometry.space.primitives import DegenerateArc, arc_through
from coatsim.languages.urscript.blend import M_TO_MM, blend_settings
from coatsim.languages.urscript.values import FramedPose, PoseJoints, PoseValue
from coatsim.path.arcs import via_on_turn
from coatsim.path.language import ReadOptions
from coatsim.path.toolpath_builder import ToolPathBuilder

JOINT_MM_PER_RAD = 1000.0
_SIGNATURES = {
    "movel": (("pose", None), ("a", 1.2), ("v", 0.25), ("t", 0.0), ("r", 0.0)),
    "movep": (("pose", None), ("a", 1.2), ("v", 0.25), ("r", 0.0)),
    "movej": (("q", None), ("a", 1.4), ("v", 1.05), ("t", 0.0), ("r", 0.0)),
    "movec": (("pose_via", None), ("pose_to", None), ("a", 1.2), ("v", 0.25), ("r", 0.0), ("mode", 0)),
}
_REFUSED = ("speedl", "speedj", "servoj", "servoc", "force_mode", "movepath", "path_offset_enable", "conveyor_pulse")
_SILENT = ("set_payload", "set_gravity", "set_safety", "set_standard_analog", "set_tool_analog", "set_analog",
           "set_tool_voltage", "set_input_actions", "set_target_payload", "set_tool_communication",
           "set_tool_output_mode", "set_tool_digital_output_mode", "set_configurable_digital_input_action",
           "set_standard_digital_input_action", "set_tool_digital_input_action", "set_gp_", "textmsg", "sync",
           "rtde_set_watchdog", "set_runstate", "step_count", "position_deviation_warning", "end_force_mode",
           "zero_ftsensor", "set_flag", "set_tool_gravity")
_OUTPUTS = {"set_digital_out": "", "set_standard_digital_out": "", "set_configurable_digital_out": "configurable ",
            "set_tool_digital_out": "tool "}


class RobotCalls:
    """The robot's side of a run: the ToolPath builder, the TCP, the outputs."""

    def __init__(self, source: str, options: ReadOptions, line: Callable[[], int],
                 program: Callable[[], str] = lambda: "") -> None:
        self.source, self.options, self.line = source, options, line
        start = None
        if options.kinematics is not None:
            kin = options.kinematics
            start = lambda: (kin.forward(kin.home(1)), kin.home(1))  # noqa: E731
        self.builder = ToolPathBuilder(lambda number: f"{source}:{number}", start,
                                       lambda: (source, program(), self.frame))
        self.frame = Pose.identity()  # the user frame of the last motion's target (a feature's pose)
        self.outputs: dict[str, bool] = {}
        self.switched: list[str] = []  # the outputs switched, as messages name them
        self.unknown_reads = 0  # reads of an input nobody gives (a loop that waits on one is taken as met)

    def error(self, message: str) -> InputError:
        return self.builder.error(self.line(), message)

    # --- dispatch -----------------------------------------------------------------------
    @staticmethod
    def harmless(name: str) -> bool:
        """Whether a call changes no motion, output or wait (a message, a set-up value): an unknown
        in its arguments skips nothing."""
        return name == "popup" or name.startswith(_SILENT)

    def call(self, name: str, args: tuple, kwargs: tuple):
        if name in _SIGNATURES:
            return self.motion(name, self.bind(name, args, kwargs))
        if name in _OUTPUTS:
            return self.set_output(name, args)
        if name in ("get_digital_in", "get_standard_digital_in", "get_configurable_digital_in", "get_tool_digital_in"):
            return self.read_input(name, args)
        if name in ("get_digital_out", "get_standard_digital_out"):
            return self.outputs.get(f"{self._number(args)}", False)
        if name == "set_tcp":
            self.builder.set_tool(self._pose(self._one(name, args)), self.line())
            return None
        if name == "sleep":
            self.builder.dwell(self._seconds(self._one(name, args)), self.line())
            return None
        if name in ("stopl", "stopj"):
            self.builder.stop()
            return None
        if name in ("get_actual_tcp_pose", "get_target_tcp_pose"):
            return PoseValue.of(self.builder.here(name + "()", self.line()))
        if name in ("get_actual_joint_positions", "get_target_joint_positions"):
            return list(self._joints_now(name))
        if name == "get_inverse_kin":
            return PoseJoints(self._as_pose_value(args[0] if args else None))
        if name == "get_forward_kin":
            joints = args[0] if args else dict(kwargs).get("q", self._joints_now(name))
            return PoseValue.of(self._forward(joints))
        if name == "get_tcp_offset":
            tool = self.builder.tool
            return PoseValue.of(Pose.identity() if tool is None else Pose(tool.rotation, tool.offset_mm))
        if name in _REFUSED:
            raise ExecutionError(f"{self.source}:{self.line()}: {name} (speed or force control) is not simulated; "
                                 "the twin cannot run this program")
        if name == "popup":
            self.builder.warn("popup", f"{self.source}:{self.line()}: popup() (the operator answers) is not simulated")
            return None
        if not name.startswith(_SILENT):
            self.builder.warn(f"fn:{name}", f"{self.source}:{self.line()}: {name}() is not simulated; it gives nothing")
        return None

    def bind(self, name: str, args: tuple, kwargs: tuple) -> dict:
        signature = _SIGNATURES[name]
        if len(args) > len(signature):
            raise self.error(f"{name}() takes at most {len(signature)} arguments")
        values = {key: default for key, default in signature}
        values.update({key: value for (key, _), value in zip(signature, args)})
        for key, value in kwargs:
            if key not in values:
                raise self.error(f"{name}() has no parameter {key!r}")
            values[key] = value
        missing = [key for key, value in values.items() if value is None]
        if missing:
            raise self.error(f"{name}() needs {', '.join(missing)}")
        return values

    # --- values -------------------------------------------------------------------------
    def _one(self, name: str, args: tuple):
        if len(args) != 1:
            raise self.error(f"{name}() takes one argument")
        return args[0]

    def _number(self, args: tuple) -> int:
        if not args or isinstance(args[0], bool) or not isinstance(args[0], (int, float)) or args[0] != int(args[0]):
            raise self.error("an output or input is numbered by a whole number")
        return int(args[0])

    def _seconds(self, value) -> float:
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not value >= 0 or math.isinf(value):
            raise self.error("sleep() takes a time >= 0 s")
        return float(value)

    def _as_pose_value(self, value) -> PoseValue:
        if not isinstance(value, PoseValue):
            raise self.error(f"expected a pose p[x, y, z, rx, ry, rz], got {type(value).__name__}")
        return value

    def _pose(self, value) -> Pose:
        try:
            return self._as_pose_value(value).pose()
        except ValueError as exc:
            raise self.error(f"the pose is not valid: {exc}") from None

    def _joints(self, value) -> Optional[np.ndarray]:
        if isinstance(value, list) and len(value) == 6 and all(isinstance(v, (int, float)) and not isinstance(v, bool)
                                                               for v in value):
            joints = np.array(value, dtype=float)
            if not np.isfinite(joints).all():
                raise self.error("joint values must be finite")
            return joints
        return None

    def _joints_now(self, what: str) -> np.ndarray:
        joints = self.builder.current_joints
        if joints is None:
            raise self.error(f"{what}() needs the arm's joint values, which the twin knows only after a move to "
                             "joint values")
        return joints

    def _forward(self, joints) -> Pose:
        q = self._joints(list(joints) if isinstance(joints, (list, tuple, np.ndarray)) else joints)
        if q is None:
            raise self.error("expected six joint values (rad)")
        kin = self.options.kinematics
        if kin is None:
            raise self.error("a target given as joint values needs the cell (its kinematics)")
        return kin.forward(q, self.builder.tool)

    def _target(self, value) -> tuple[Pose, Optional[np.ndarray]]:
        """A motion's target: a pose, the joint solution of one, or joint values."""
        if isinstance(value, PoseJoints):
            return self._pose(value.target), None
        joints = self._joints(value)
        if joints is not None:
            return self._forward(joints), joints
        return self._pose(value), None

    def _speed(self, name: str, values: dict, target: Pose) -> float:
        v, t = float(values["v"]), float(values.get("t", 0.0))
        if t > 0.0:
            here = self.builder.current
            length = 0.0 if here is None else float(np.linalg.norm(target.translation_mm - here.translation_mm))
            return length / t if length > 0.0 else v * (JOINT_MM_PER_RAD if name == "movej" else M_TO_MM)
        if not v > 0.0 or math.isinf(v):
            raise self.error(f"{name}(): v must be > 0")
        return v * (JOINT_MM_PER_RAD if name == "movej" else M_TO_MM)

    # --- motions and signals ------------------------------------------------------------
    def motion(self, name: str, values: dict) -> None:
        for key in ("a", "v", "r", "t"):
            if key in values and (isinstance(values[key], bool) or not isinstance(values[key], (int, float))
                                  or not math.isfinite(values[key]) or values[key] < 0):
                raise self.error(f"{name}(): {key} must be a number >= 0")
        line = self.line()
        self.frame = self._frame(values["pose_to" if name == "movec" else "pose" if name != "movej" else "q"])
        if name == "movec":
            self._movec(values, line)
            return
        target, joints = self._target(values["pose" if name != "movej" else "q"])
        settings = blend_settings(self._speed(name, values, target), float(values["r"]))
        if name == "movej":
            self.builder.joint(target, settings, line, joints)
        else:
            self.builder.linear(target, settings, line)

    def _frame(self, target) -> Pose:
        """The user frame a target is given in: its feature's pose (base otherwise)."""
        return self._pose(target.feature) if isinstance(target, FramedPose) else Pose.identity()

    def _movec(self, values: dict, line: int) -> None:
        via, _ = self._target(values["pose_via"])
        end, _ = self._target(values["pose_to"])
        mode = values["mode"]
        if mode not in (0, 1):
            raise self.error("movec(): mode is 0 (orientation to pose_to) or 1 (fixed to the path)")
        start = self.builder.here("movec()", line)
        try:
            arc = arc_through(start.translation_mm, via.translation_mm, end.translation_mm)
        except DegenerateArc as exc:
            raise self.error(f"movec(): the start, via and end define no arc: {exc}") from None
        if mode == 1:  # the tool turns with the tangent, by the arc's turn
            end = Pose(exp_rotation(arc.normal * arc.sweep) @ start.rotation, end.translation_mm)
        settings = blend_settings(self._speed("movec", values, end), float(values["r"]))
        self.builder.circular(via_on_turn(start, via, end), end, settings, line)  # the via's orientation not used

    def set_output(self, name: str, args: tuple) -> None:
        kind = _OUTPUTS[name]
        if len(args) != 2:
            raise self.error("an output is set with (n, True or False)")
        number, state = self._number(args), args[1]
        if not isinstance(state, (bool, int, float)):
            raise self.error("an output is set to True or False")
        self.outputs[f"{kind}{number}"] = bool(state)
        self.switched.append(f"{kind}output {number}")
        gun = not kind and number == self.options.gun_signal
        self.builder.switched(self.line(), f"{name}({number}, {bool(state)})", None if kind else number,
                              bool(state) if gun else None)
        if gun:
            self.builder.switch_gun(bool(state))

    def read_input(self, name: str, args: tuple) -> bool:
        number = self._number(args)
        if name in ("get_digital_in", "get_standard_digital_in") and number in self.options.inputs:
            return bool(self.options.inputs[number])
        self.unknown_reads += 1
        self.builder.warn(f"in:{name}{number}", f"{self.source}:{self.line()}: {name}({number}) is not given; taken "
                          "as False (give its state in the inputs)")
        return False
