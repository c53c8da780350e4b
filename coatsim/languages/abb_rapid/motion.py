"""RAPID motion instructions -> ToolPath moves, with the controller settings of each.

``MoveL``/``MoveC``/``MoveJ``/``MoveAbsJ`` (and the ``...DO`` forms, which set an output in the
middle of the corner path): the target in the work object (``\\WObj``, default ``wobj0``) with
the tool (``tooldata``), the TCP speed of the ``speeddata`` (``\\V`` overrides it, ``\\T`` gives the
move's time; ``VelSet`` scales and caps it), and the zone: ``fine`` (or ``\\Inpos``) a stop point,
otherwise a fly-by point whose corner the twin rounds within the zone's ``pzone_tcp`` (``\\Z``
overrides it) — the zone is also cut to half the distance to the neighbouring points, by the
twin's blend as by the controller (ABB, RAPID Instructions, Functions and Data types: zonedata).
Outputs set between moves switch as the next move starts: after a stop point at rest, after a
fly-by point in its corner zone (ABB, Technical reference manual — RAPID overview, "Program
execution" of logical instructions in corner paths ⚠ the exact point in the zone is the
twin's assumption).
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Any, Optional

import numpy as np

from coatsim.geometry.space.pose import Pose
from coatsim.languages.abb_rapid import data as d
from coatsim.languages.script import nodes as n
from coatsim.path.arcs import via_on_turn
from coatsim.path.toolpath import CircularMove, JointMove, LinearMove, MotionSettings, ToolFrame

# Instruction -> (positional parameters, the index of its target, of its circle point or None)
MOVES = {
    "movel": (("ToPoint", "Speed", "Zone", "Tool"), 0, None),
    "movej": (("ToPoint", "Speed", "Zone", "Tool"), 0, None),
    "movec": (("CirPoint", "ToPoint", "Speed", "Zone", "Tool"), 1, 0),
    "moveabsj": (("ToJointPos", "Speed", "Zone", "Tool"), 0, None),
    "moveldo": (("ToPoint", "Speed", "Zone", "Tool", "Signal", "Value"), 0, None),
    "movejdo": (("ToPoint", "Speed", "Zone", "Tool", "Signal", "Value"), 0, None),
    "movecdo": (("CirPoint", "ToPoint", "Speed", "Zone", "Tool", "Signal", "Value"), 1, 0),
    "triggl": (("ToPoint", "Speed", "Trigg1", "Zone", "Tool"), 0, None),
    "triggj": (("ToPoint", "Speed", "Trigg1", "Zone", "Tool"), 0, None),
    "triggc": (("CirPoint", "ToPoint", "Speed", "Trigg1", "Zone", "Tool"), 1, 0),
}


class Motions:
    """The motion state of a run: where the TCP is, with which tool and work object; the
    interpreter provides ``eval``, ``error``, ``failure``, ``warn``, ``add_move`` and ``options``."""

    def init_motion(self) -> None:
        self.tcp: Optional[Pose] = None
        self.tool_record = d.PREDEFINED["tool0"][1]
        self.wobj_record = d.PREDEFINED["wobj0"][1]
        self.velset = (100.0, math.inf)  # VelSet override %, max TCP speed mm/s

    def _frame(self, wobj: d.Record) -> Pose:
        if wobj.fields["robhold"]:
            raise self.failure("a work object held by the robot (stationary tool) is not simulated")
        if wobj.fields["ufmec"]:
            self.warn("ufmec", f"work object moved by {wobj.fields['ufmec']!r}: coatsim keeps it where it is")
        return d.pose_of(wobj.fields["uframe"], self.error) @ d.pose_of(wobj.fields["oframe"], self.error)

    def _tool(self, tool: d.Record, line: int) -> ToolFrame:
        if not tool.fields["robhold"]:
            raise self.failure("a stationary tool (robhold FALSE) is not simulated")
        pose = d.pose_of(tool.fields["tframe"], self.error)
        return ToolFrame(pose.rotation, pose.translation_mm, line)

    def motion(self, call, name: str) -> None:
        params, target_at, via_at = MOVES[name]
        positional = [a.value for a in call.args if a.name is None]
        named = {a.name.lower(): a for a in call.args if a.name is not None}
        if len(positional) != len(params):
            raise self.error(f"{call.name} takes {len(params)} arguments ({', '.join(params)}), got {len(positional)}")
        by = dict(zip(params, positional))
        tool_rec = d.coerce("tooldata", self.eval(by["Tool"]), self.error)
        wobj_rec = d.coerce("wobjdata", self.eval(named["wobj"].value), self.error) if "wobj" in named \
            else d.PREDEFINED["wobj0"][1]
        speed = d.coerce("speeddata", self.eval(by["Speed"]), self.error)
        zone = d.coerce("zonedata", self.eval(by["Zone"]), self.error)
        tool = self._tool(tool_rec, call.line)
        frame = self._frame(wobj_rec)
        v = speed.fields["v_tcp"]
        if "v" in named and named["v"].value is not None:
            v = self._num(self.eval(named["v"].value))
        stop = bool(zone.fields["finep"]) or "inpos" in named
        accuracy = 0.0 if stop else zone.fields["pzone_tcp"]
        if "z" in named and named["z"].value is not None and not stop:
            accuracy = self._num(self.eval(named["z"].value))
        if "trigg1" in by:
            self.warn("trigg", f"{call.name}: its trigger events (TriggIO, TriggEquip) are not simulated; the outputs "
                               "they set do not switch in the twin")
        if name == "moveabsj":
            end, joints = self._joint_target(by["ToJointPos"], tool)
            self.tool_record, self.wobj_record = tool_rec, wobj_rec
            settings = self._settings(v, accuracy, stop, tool, None, named)
            self.add_move(JointMove(self.tcp, end, settings, self.spraying, call.line, joints_rad=joints), call, frame)
            self.tcp = end
        else:
            end = frame @ self._pose(by[params[target_at]])
            via = frame @ self._pose(by[params[via_at]]) if via_at is not None else None
            settings = self._settings(v, accuracy, stop, tool, (via, end), named)
            self.tool_record, self.wobj_record = tool_rec, wobj_rec
            if name in ("movej", "movejdo", "triggj"):
                move = JointMove(self.tcp, end, settings, self.spraying, call.line)
            else:
                start = self.tcp if self.tcp is not None else self._home_start(call.name, tool)
                move = (CircularMove(start, via_on_turn(start, via, end), end, settings, self.spraying, call.line)
                        if via is not None
                        else LinearMove(start, end, settings, self.spraying, call.line))
            self.add_move(move, call, frame)
            self.tcp = end
        if name.endswith("do"):  # the output switches in the middle of the corner path
            self.set_output(by["Signal"], self._num(self.eval(by["Value"])) != 0, call, f"{call.name}")

    def _settings(self, v: float, accuracy: float, stop: bool, tool: ToolFrame, ends, named) -> MotionSettings:
        override, cap = self.velset
        speed = min(v * override / 100.0, cap)
        if "t" in named and named["t"].value is not None and ends is not None and self.tcp is not None:
            seconds = self._num(self.eval(named["t"].value))
            if seconds <= 0:
                raise self.error(f"\\T:={seconds:g}: the time of a move must be > 0 s")
            speed = max(float(np.linalg.norm(ends[1].translation_mm - self.tcp.translation_mm)), 1e-6) / seconds
        if not (math.isfinite(speed) and speed > 0):
            raise self.error(f"TCP speed {speed:g} mm/s: must be > 0")
        return MotionSettings(speed, max(float(accuracy), 0.0), not stop, stop, tool)

    def _pose(self, e: n.Expr) -> Pose:
        if isinstance(e, n.Name) and e.name == "*":
            raise self.error("a position written as * (stored in the instruction) has no coordinates in the file: "
                             "give it a robtarget")
        return d.pose_of(d.coerce("robtarget", self.eval(e), self.error), self.error)

    def _home_start(self, word: str, tool: ToolFrame) -> Pose:
        """Where a linear or circular first motion starts: the cell's home, where the twin's arm
        stands when the program starts (a robot's is wherever it stands; without the cell it is
        unknown)."""
        kin = self.options.kinematics
        if kin is None:
            raise self.failure(f"{word} is the first motion: the robot's position before it is unknown; start with "
                               "MoveJ or MoveAbsJ")
        self.warn("first-motion", f"{word} is the first motion: it starts from the cell's home, where the twin's arm "
                  "stands when the program starts")
        return kin.forward(kin.home(1), tool)

    def _joint_target(self, e: n.Expr, tool: ToolFrame) -> tuple[Pose, np.ndarray]:
        target = d.coerce("jointtarget", self.eval(e), self.error)
        axes = target.fields["robax"].fields
        joints = np.radians([axes[f"rax_{k}"] for k in range(1, 7)])
        if self.options.kinematics is None:
            raise self.error("MoveAbsJ needs the cell's kinematics to know where the tool goes")
        return self.options.kinematics.forward(joints, tool), joints

    def stop_previous(self) -> None:
        """The robot comes to rest at the end of the last move (a wait, a stop, a read of its
        position): it has no next point to fly by to."""
        if self.moves and not self.moves[-1].settings.stop_at_end:
            last = self.moves[-1]
            self.moves[-1] = replace(last, settings=replace(last.settings, stop_at_end=True))

    def current_target(self, named: dict) -> d.Record:
        """CRobT / CPos: the TCP where the program last sent it, in ``\\Tool`` and ``\\WObj``
        (default: the ones of the last motion)."""
        if self.tcp is None:
            raise self.failure("CRobT before any motion: the robot's position is unknown")
        if self.moves and not self.moves[-1].settings.stop_at_end:
            self.warn("crobt", "CRobT after a fly-by point reads a position the robot is passing; coatsim takes the "
                               "point itself (use a stop point, fine, before it)")
        tool = d.coerce("tooldata", self.eval(named["tool"]), self.error) if named.get("tool") else self.tool_record
        wobj = d.coerce("wobjdata", self.eval(named["wobj"]), self.error) if named.get("wobj") else self.wobj_record
        flange = self.tcp @ Pose(*self._tool_pose(self.tool_record)).inverse()
        tcp = flange @ Pose(*self._tool_pose(tool))
        return d.make_robtarget(self._frame(wobj).inverse() @ tcp)

    def _tool_pose(self, tool: d.Record) -> tuple[np.ndarray, np.ndarray]:
        pose = d.pose_of(tool.fields["tframe"], self.error)
        return pose.rotation, pose.translation_mm

    def current_joints(self) -> Any:
        raise self.failure("CJointT reads the robot's joint angles, which the program does not give; the twin "
                           "does not simulate it")
