"""The controller model of the interpreter: motion settings, forward processing, dwells.

What it implements (Kawasaki AS semantics as far as public sources go, see the robot-language
reference; the parts marked there as unconfirmed are modelled as stated here):

- ``SPEED``, ``ACCURACY`` without ALWAYS apply to the next motion only; with ALWAYS they become
  the default. Speed units: MM/S, MM/MIN, CM/S, CM/MIN, S (time for the motion), % of
  ``full_speed_mm_s`` (monitor speed 100 %). Before any SPEED the speed is 10 %, before any
  ACCURACY the accuracy 1 mm, CP is ON.
- ``stop_at_end`` is true when the motion ran with CP OFF or ACCURACY ... FINE, when a BREAK,
  DELAY, STABLE or a TWAIT longer than the motion follows it before the next motion, and for
  the last motion of the program.
- Gun signal (forward processing): the program runs ahead while a motion executes, so a gun
  switch written after motion k with no BREAK in between switches the gun as motion k starts;
  after a BREAK it switches when motion k has ended, i.e. as motion k+1 starts. The rule is
  the same under CP ON and CP OFF, for lines and arcs (C2MOVE), and a switch never makes the
  robot stop. Under CP ON, "motion k starts" where the tool enters the accuracy zone of the
  point before it (the robot stage switches at the start of the corner blend). A move's
  ``spray`` is the gun state from its start to its end; several switches between two motions
  act as the last one. The writer relies on this to spray a closed contour exactly once
  around, switching on the fly at the seam.
- Dwells: DELAY t / STABLE t are motion steps: the robot stops, then stands still t s (a gun
  switch written right after one switches as it starts). TWAIT t counts from the start of the
  motion in progress: the robot rests t minus the motion's nominal time (length / speed) at its
  end if that is positive (after a BREAK the full t), and a gun switch after it happens when
  the rest is over.
- ``TOOL`` (at any point) sets the controller's TCP in the flange frame for the motions after
  it (``MotionSettings.tool``; the robot stage puts the flange where that TCP reaches the
  programmed poses). A TOOL after motion ends that motion at rest (like BREAK) and re-expresses
  the current pose with the new TCP, the flange staying put (when the previous TOOL is known).
  The TOOL in force at the end is ``ToolPath.tool``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Optional, Union

import numpy as np

from coatsim.core.errors import ExecutionError, InputError
from coatsim.geometry.space.primitives import DegenerateArc, arc_through
from coatsim.languages.kawasaki_as.unknowns import NotSimulated
from coatsim.path.process import ProcessInfo
from coatsim.geometry.space.pose import Pose
from coatsim.path.toolpath import CircularMove, Dwell, JointMove, LinearMove, MotionSettings, Move, ToolFrame, ToolPath

# What SPEED 100 (percent) means in mm/s; the controller's true maximum is robot-specific.
FULL_SPEED_MM_S = 1000.0
DEFAULT_SPEED = (10.0, "%")
DEFAULT_ACCURACY_MM = 1.0
MAX_MOTIONS = 200_000  # motions one run may issue (a runaway loop of moves stops here)
_UNIT_FACTOR = {"MM/S": 1.0, "MM/MIN": 1.0 / 60.0, "CM/S": 10.0, "CM/MIN": 10.0 / 60.0}


@dataclass
class _Pending:
    """A motion issued but not yet final (its stop and spray may still change)."""

    kind: str
    start: Optional[Pose]
    end: Pose
    via: Optional[Pose]
    speed: tuple[float, str]
    accuracy: float
    cp: bool
    stop: bool
    spray: bool
    line: int
    joints: Optional[np.ndarray]
    first_line: int  # the C1MOVE's line for an arc, else ``line``
    tool: Optional[ToolFrame]


@dataclass
class _PendingDwell:
    after: int
    seconds: float
    spray: bool
    line: int


class Controller:
    """Motions, settings and the gun as the controller's program pointer meets them.

    ``where(line)`` names a line of the program running ("file.as:12") in error messages.
    """

    def __init__(self, full_speed_mm_s: float, where: Callable[[int], str],
                 start: Optional[Callable[[], tuple[Pose, np.ndarray]]] = None) -> None:
        self.full_speed, self.where, self.start = full_speed_mm_s, where, start
        self.tool: Optional[ToolFrame] = None
        self.speed_always: tuple[float, str] = DEFAULT_SPEED
        self.speed_once: Optional[tuple[float, str]] = None
        self.acc_always, self.acc_once = DEFAULT_ACCURACY_MM, None
        self.fine_always, self.fine_once = False, False
        self.cp = True
        self.current: Optional[Pose] = None
        self.current_joints: Optional[np.ndarray] = None
        self.gun_on = False
        self.moves: list[_Pending] = []
        self.dwells: list[_PendingDwell] = []
        self.last_motion: Optional[Union[_Pending, _PendingDwell]] = None
        self.at_rest = True  # a BREAK (or a rest) since the last motion: switches wait for it
        self.c1: Optional[tuple[Pose, int]] = None

    def error(self, line: int, message: str) -> InputError:
        return InputError(f"{self.where(line)}: {message}")

    def failure(self, line: int, message: str) -> ExecutionError:
        return ExecutionError(f"{self.where(line)}: {message}")

    # --- motions ------------------------------------------------------------------------
    def need_current(self, op: str, line: int) -> Pose:
        """Where the tool is: the last target, or before any motion the start (home) pose."""
        if self.current is None and not self.moves and self.start is not None:
            self.current, self.current_joints = self.start()
        if self.current is None:
            raise self.error(line, f"{op} needs a known start pose; begin the program with JMOVE or JAPPRO")
        return self.current

    def _check_no_arc(self, line: int) -> None:
        if self.c1 is not None:
            raise self.error(self.c1[1], f"C1MOVE must be followed by C2MOVE before the next motion (line {line})")

    def issue(self, kind: str, end: Pose, line: int, via: Optional[Pose] = None,
              joints: Optional[np.ndarray] = None, first_line: Optional[int] = None) -> None:
        if len(self.moves) >= MAX_MOTIONS:
            raise self.failure(line, f"the program issues more than {MAX_MOTIONS} motions; coatsim stops it")
        x, y, z = (float(v) for v in end.translation_mm)
        if not max(abs(x), abs(y), abs(z)) <= 1e9:  # (NaN fails too)
            raise self.failure(line, "the target pose is out of range (|x| <= 1e9 mm)")
        fine = self.fine_once or self.fine_always
        move = _Pending(kind, self.current, end, via, self.speed_once or self.speed_always,
                        self.acc_always if self.acc_once is None else self.acc_once,
                        self.cp, (not self.cp) or fine, self.gun_on, line, joints,
                        line if first_line is None else first_line, self.tool)
        self.moves.append(move)
        self.speed_once, self.acc_once, self.fine_once = None, None, False
        self.current = end
        self.current_joints = joints
        self.last_motion, self.at_rest = move, False

    def joint(self, end: Pose, line: int, joints: Optional[np.ndarray] = None) -> None:
        self._check_no_arc(line)
        self.issue("joint", end, line, joints=joints)

    def linear(self, op: str, end: Pose, line: int) -> None:
        self._check_no_arc(line)
        self.need_current(op, line)
        self.issue("line", end, line)

    def arc_via(self, via: Pose, line: int) -> None:
        self._check_no_arc(line)
        self.need_current("C1MOVE", line)
        self.c1 = (via, line)

    def arc_end(self, end: Pose, line: int) -> None:
        if self.c1 is None:
            raise self.error(line, "C2MOVE without a C1MOVE before it; an arc is C1MOVE via then C2MOVE end")
        via, via_line = self.c1
        self.c1 = None
        try:
            arc_through(self.current.translation_mm, via.translation_mm, end.translation_mm)
        except DegenerateArc as exc:
            raise self.error(line, f"arc from the current pose through the C1MOVE pose (line {via_line}) to here "
                             f"is undefined: {exc}") from None
        self.issue("arc", end, line, via=via, first_line=via_line)

    def finish(self, line: int) -> None:
        if self.c1 is not None:
            raise self.error(self.c1[1], "C1MOVE at the end of the program; expected C2MOVE with the arc end")

    # --- rests --------------------------------------------------------------------------
    def stop_previous(self) -> None:
        if self.moves:
            self.moves[-1].stop = True
        self.at_rest = True

    def brk(self, line: int) -> None:
        self._check_no_arc(line)
        self.stop_previous()

    def delay(self, seconds: float, line: int) -> None:
        """DELAY / STABLE: a motion step standing still."""
        self._check_no_arc(line)
        self.stop_previous()
        dwell = _PendingDwell(len(self.moves) - 1, seconds, self.gun_on, line)
        self.dwells.append(dwell)
        self.last_motion, self.at_rest = dwell, False

    def twait(self, seconds: float, line: int) -> None:
        """TWAIT: the program (not the robot) waits; the robot rests if the wait outlasts the motion."""
        last = self.last_motion
        if last is not None and not self.at_rest:
            seconds -= self.nominal_time(last) if isinstance(last, _Pending) else last.seconds
        if seconds <= 0.0 or last is None:
            return  # over before the motion ends, or before any motion (the robot stands at home)
        self.stop_previous()
        self.dwells.append(_PendingDwell(len(self.moves) - 1, seconds, self.gun_on, line))

    # --- settings -----------------------------------------------------------------------
    def speed(self, value: float, unit: str, always: bool, line: int) -> None:
        if not value > 0.0:
            raise self.error(line, "SPEED must be > 0")
        if unit.startswith("DEG"):
            raise NotSimulated(f"SPEED in {unit} (a rotation speed) is not simulated; give MM/S")
        if always:
            self.speed_always = (value, unit)
        else:
            self.speed_once = (value, unit)

    def accuracy(self, value: float, always: bool, fine: bool, line: int) -> None:
        if value < 0.0:
            raise self.error(line, "ACCURACY must be >= 0 mm")
        if always:
            self.acc_always, self.fine_always = value, fine
        else:
            self.acc_once, self.fine_once = value, fine

    def tool_frame(self) -> Optional[Pose]:
        """The TCP the program's last TOOL set (None before any)."""
        return None if self.tool is None else Pose(self.tool.rotation, self.tool.offset_mm)

    def set_tool(self, frame: Pose, line: int) -> None:
        self._check_no_arc(line)
        if self.moves:
            self.stop_previous()
        if self.current is not None and self.tool is not None:
            # the flange stays where it is; the pose now names the new TCP
            flange = self.current @ Pose(self.tool.rotation, self.tool.offset_mm).inverse()
            self.current = flange @ frame
        self.tool = ToolFrame(np.array(frame.rotation), np.array(frame.translation_mm), line)

    def switch_gun(self, on: bool) -> None:
        """The gun output changes as the program pointer reaches the switch (forward processing)."""
        self.gun_on = on
        if self.last_motion is not None and not self.at_rest:
            self.last_motion.spray = on

    # --- result -------------------------------------------------------------------------
    def speed_mm_s(self, m: _Pending) -> float:
        value, unit = m.speed
        if unit in _UNIT_FACTOR:
            return value * _UNIT_FACTOR[unit]
        if unit == "%":
            return value / 100.0 * self.full_speed
        length = self.length(m)
        return length / value if length > 0.0 else self.full_speed

    def length(self, m: _Pending) -> float:
        start = m.start.translation_mm if m.start is not None else m.end.translation_mm
        if m.kind == "arc":
            c = arc_through(start, m.via.translation_mm, m.end.translation_mm)
            return c.radius * c.sweep
        return float(np.linalg.norm(m.end.translation_mm - start))

    def nominal_time(self, m: _Pending) -> float:
        if m.speed[1] == "S":
            return m.speed[0]
        return self.length(m) / self.speed_mm_s(m)

    def toolpath(self, name: str, process: ProcessInfo, warnings: tuple[str, ...]) -> ToolPath:
        if self.moves:
            self.moves[-1].stop = True
        moves: list[Move] = []
        for m in self.moves:
            settings = MotionSettings(self.speed_mm_s(m), m.accuracy, m.cp, m.stop, m.tool)
            if m.kind == "joint":
                moves.append(JointMove(m.start, m.end, settings, m.spray, m.line, joints_rad=m.joints))
            elif m.kind == "line":
                moves.append(LinearMove(m.start, m.end, settings, m.spray, m.line))
            else:
                moves.append(CircularMove(m.start, m.via, m.end, settings, m.spray, m.line))
        dwells = tuple(Dwell(d.after, d.seconds, d.spray, d.line) for d in self.dwells)
        return ToolPath(name, tuple(moves), process, dwells, warnings, self.tool)
