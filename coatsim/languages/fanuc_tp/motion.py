"""Fanuc TP motions: the target (``P[i]`` in its user frame and tool, ``PR[i]`` in the selected
ones, joint values through the cell's kinematics, ``INC``, ``Offset``, ``Tool_Offset``), the
speed and the termination (FINE, CNT) of each motion. The interpreter's Motions part (see
:mod:`.interpreter`, which says what the twin models)."""

from __future__ import annotations

import math
from typing import Optional

import numpy as np

from coatsim.geometry.space.pose import Pose
from coatsim.languages.fanuc_tp.blend import cnt_accuracy_mm
from coatsim.languages.fanuc_tp.positions import Position, pose_of, values_of
from coatsim.languages.fanuc_tp.statements import Motion
from coatsim.path.toolpath import MotionSettings

FULL_SPEED_MM_S = 1000.0
_UNIT_MM_S = {"mm/sec": 1.0, "cm/min": 10.0 / 60.0, "inch/min": 25.4 / 60.0}


class Motions:
    """Motions of a FanucRun; the run provides ``data``, ``builder``, ``uf``, ``ut``, ``offsets``,
    ``options``, ``position_value``, ``warn``, ``refuse`` and ``error``."""

    def motion(self, st: Motion, args: tuple) -> None:
        if st.kind == "A":
            raise self.refuse("the A motion (an arc through consecutive points)")
        if st.other_options:
            self.warn(f"option:{st.other_options.split()[0]}", f"motion option {st.other_options[:40]} is not simulated")
        targets = [self.target(kind, index, st, args) for kind, index in st.targets]
        end_pose, joints = targets[-1]
        start = self.builder.current
        speed = self.speed(st, args, start, targets)
        settings = self.termination(st, args, speed)
        if st.kind == "J":
            self.builder.joint(end_pose, settings, st.line, joints)
        elif st.kind == "L":
            self.builder.linear(end_pose, settings, st.line)
        else:
            self.builder.circular(targets[0][0], end_pose, settings, st.line, st.end_line)

    def target(self, kind: str, index_expr, st: Motion, args: tuple) -> tuple[Pose, Optional[np.ndarray]]:
        """The base-frame pose (and joint values, when the position holds them) of a motion target."""
        number = self.data.index(index_expr, args)
        if kind == "P":
            if number not in self.program.positions:
                raise self.error(f"P[{number}] is not in the program's /POS section")
            position = self.program.positions[number]
            uf, ut = self._agree("UFRAME_NUM", self.uf, position.uf), self._agree("UTOOL_NUM", self.ut, position.ut)
        else:
            value = self.data.position(number)
            position = Position(None, None, None if value.joints else value.pose(),
                                np.array(value.values) if value.joints else None, st.line)
            uf, ut = self.uf or 0, self.ut
        if position.extended:
            self.warn("extended", f"{kind}[{number}] (and any later position): extended axes and other motion groups "
                      "are not simulated")
        self.use_tool(ut)
        if position.joints_deg is not None:
            return self._forward(np.radians(position.joints_deg), kind, number)
        pose = position.pose
        frame = self.data.frame("UFRAME", uf)
        self.user_frame = frame
        for option, register in st.options:
            if option == "INC":
                here = frame.inverse() @ self.builder.here("an INC motion", st.line)
                pose = pose_of(np.array(values_of(here)) + np.array(values_of(pose)))
            elif option in self.offsets:
                condition = self.offsets[option]
                if register is None and condition is None:
                    raise self.error(f"{option} without PR[i] needs an {option} CONDITION PR[i] before it")
                offset = self.data.position(self.data.index(register, args)).pose() if register is not None \
                    else self.position_value(*condition).pose()
                pose = offset @ pose if option == "OFFSET" else pose @ offset
        return frame @ pose, None

    def _agree(self, what: str, selected: Optional[int], taught: Optional[int]) -> int:
        if selected is not None and taught is not None and selected != taught:
            raise self.error(f"the position was taught in {what.split('_')[0]} {taught} but {what}={selected} is "
                             "selected; the controller refuses the motion (frame number mismatch)")
        return selected if selected is not None else (taught or 0)

    def use_tool(self, number: Optional[int]) -> None:
        """Make UTOOL ``number`` the TCP of the motions from here (None: keep the one in use)."""
        if number is None or number == self.tool_number:
            return
        frame = self.data.frame("UTOOL", number)
        if frame is None:
            self.warn(f"utool:{number}", f"UTOOL[{number}] is not set by the program nor given; the twin takes the "
                      "cell's gun as the tool")
        self.builder.set_tool(frame, self.line)
        self.tool_number = number

    def _forward(self, joints: np.ndarray, kind: str, number: int) -> tuple[Pose, np.ndarray]:
        kin = self.options.kinematics
        if kin is None:
            raise self.error(f"{kind}[{number}] holds joint values; reading it needs the cell (its kinematics)")
        return kin.forward(joints, self.builder.tool), joints

    def speed(self, st: Motion, args: tuple, start: Optional[Pose], targets) -> float:
        if st.unit == "max":
            return FULL_SPEED_MM_S * self.override / 100.0
        if st.speed is None:
            return self.unsimulated_speed(f"speed {st.unit} (an application's setting)")
        value = self.data.evaluate(st.speed, args)
        if not value > 0.0:
            raise self.error(f"the speed must be > 0, got {value:g}")
        if st.unit == "deg/sec":
            return self.unsimulated_speed("a speed in deg/sec (a rotation speed)")
        if st.unit in ("sec", "msec"):
            seconds = value / (1000.0 if st.unit == "msec" else 1.0)
            here = start if start is not None else targets[-1][0]
            points = [here.translation_mm] + [t[0].translation_mm for t in targets]
            length = sum(float(np.linalg.norm(b - a)) for a, b in zip(points[:-1], points[1:]))
            speed = length / seconds if length > 0.0 else FULL_SPEED_MM_S
        elif st.unit == "%":
            speed = value / 100.0 * FULL_SPEED_MM_S
        else:
            speed = value * _UNIT_MM_S[st.unit]
        return speed * self.override / 100.0

    def termination(self, st: Motion, args: tuple, speed: float) -> MotionSettings:
        if st.term == "FINE":
            return MotionSettings(speed, 0.0, False, True)
        value = self.data.evaluate(st.term_value, args)
        if st.term == "CNT" and not 0.0 <= value <= 100.0:
            raise self.error(f"CNT{value:g}: from 0 to 100")
        if not value >= 0.0 or math.isinf(value):
            raise self.error(f"CR{value:g}: a corner radius >= 0 mm")
        accuracy = cnt_accuracy_mm(value, speed, self.decel) if st.term == "CNT" else value
        return MotionSettings(speed, accuracy, True, value == 0.0)
