"""Building a ToolPath while a language's interpreter runs a program.

The languages whose controllers switch outputs in program order share this model (Fanuc TP,
URScript, G-code; Kawasaki AS has its own forward processing): an output switched between two
motions takes effect as the second one starts; under blending that is where the tool enters the
corner before it (the robot stage switches at the start of the blend). A move's ``spray`` is the
gun state while it runs. A rest (a timed wait, a dwell) brings the motion before it to a stop;
the last motion of a program ends at rest. The interpreter decides each motion's settings in its
language's terms and may revise a motion's settings until the program ends (a blend that depends
on the next move, a stop decided by what follows). The builder also keeps what a
:class:`~coatsim.path.reading.Reading` needs: each move's source and user frame (``origin``), the
statements that switch outputs.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Callable, Optional

import numpy as np

from coatsim.core.errors import ExecutionError, InputError
from coatsim.geometry.space.pose import Pose
from coatsim.geometry.space.primitives import DegenerateArc, arc_through
from coatsim.path.process import ProcessInfo
from coatsim.path.reading import MoveSource, OutputSwitch, Reading
from coatsim.path.toolpath import CircularMove, Dwell, JointMove, LinearMove, MotionSettings, Move, ToolFrame, ToolPath

#: Motions one run may issue, and statements it may execute (a runaway loop stops there).
MAX_MOTIONS = 200_000
MAX_STEPS = 2_000_000
#: The largest coordinate a target may have (beyond any cell; NaN fails too).
MAX_COORDINATE_MM = 1e9


@dataclass
class PendingMove:
    """A motion issued; its settings may still change until the program ends."""

    kind: str
    start: Optional[Pose]
    end: Pose
    via: Optional[Pose]
    settings: MotionSettings
    spray: bool
    line: int
    joints: Optional[np.ndarray] = None

    @property
    def length_mm(self) -> float:
        """The TCP path length (the chord for a joint move)."""
        start = self.end.translation_mm if self.start is None else self.start.translation_mm
        if self.kind == "arc":
            return arc_through(start, self.via.translation_mm, self.end.translation_mm).length
        return float(np.linalg.norm(self.end.translation_mm - start))


class ToolPathBuilder:
    """Motions, rests, the gun and the TCP as a program meets them.

    ``where(line)`` names a source line in messages ("prog.ls:12"); ``start()`` gives the pose
    (and joints) the robot stands at before the first motion, when the cell is known;
    ``origin()`` the file, the program (routine) running and the user frame in force, for each
    move's source.
    """

    def __init__(self, where: Callable[[int], str],
                 start: Optional[Callable[[], tuple[Pose, Optional[np.ndarray]]]] = None,
                 origin: Optional[Callable[[], tuple[str, str, Pose]]] = None) -> None:
        self.where, self._start = where, start
        self._origin = origin or (lambda: ("", "", Pose.identity()))
        self.moves: list[PendingMove] = []
        self.move_sources: list[MoveSource] = []
        self.move_frames: list[Pose] = []
        self.switches: list[OutputSwitch] = []
        self.outputs: set[int] = set()
        self._switch_lines: set[tuple[str, int]] = set()
        self.dwells: list[Dwell] = []
        self.current: Optional[Pose] = None
        self.current_joints: Optional[np.ndarray] = None
        self.gun_on = False
        self.tool: Optional[ToolFrame] = None
        self.warnings: list[str] = []
        self._warned: set[str] = set()
        self._steps = 0

    # --- messages -----------------------------------------------------------------------
    def error(self, line: int, message: str) -> InputError:
        return InputError(f"{self.where(line)}: {message}")

    def warn(self, key: str, message: str) -> None:
        """One warning line per distinct ``key``, in the order met."""
        if key not in self._warned:
            self._warned.add(key)
            self.warnings.append(message)

    def step(self, line: int) -> None:
        """Count one executed statement; ExecutionError past MAX_STEPS (an endless loop)."""
        self._steps += 1
        if self._steps > MAX_STEPS:
            raise ExecutionError(f"{self.where(line)}: the program runs more than {MAX_STEPS} statements "
                                 "(an endless loop?); coatsim stops it")

    # --- where the tool is --------------------------------------------------------------
    def here(self, what: str, line: int) -> Pose:
        """The current TCP pose: the last target, before any motion where the robot stands."""
        if self.current is None and not self.moves and self._start is not None:
            self.current, self.current_joints = self._start()
        if self.current is None:
            raise self.error(line, f"{what} needs to know where the tool is; begin the program with a joint move "
                             "to a known pose")
        return self.current

    # --- motions ------------------------------------------------------------------------
    def _issue(self, kind: str, end: Pose, settings: MotionSettings, line: int, via: Optional[Pose] = None,
               joints: Optional[np.ndarray] = None, last_line: Optional[int] = None) -> None:
        if len(self.moves) >= MAX_MOTIONS:
            raise ExecutionError(f"{self.where(line)}: the program issues more than {MAX_MOTIONS} motions; "
                                 "coatsim stops it")
        if not float(np.abs(end.translation_mm).max()) <= MAX_COORDINATE_MM:
            raise ExecutionError(f"{self.where(line)}: the target is out of range (|x| <= {MAX_COORDINATE_MM:g} mm)")
        if not settings.speed_mm_s > 0:
            raise self.error(line, f"the speed must be > 0, got {settings.speed_mm_s:g} mm/s")
        self.moves.append(PendingMove(kind, self.current, end, via, replace(settings, tool=self.tool),
                                      self.gun_on, line, joints))
        source, program, frame = self._origin()
        self.move_sources.append(MoveSource(source, program, line, max(line, last_line or line)))
        self.move_frames.append(frame)
        self.current, self.current_joints = end, joints

    def joint(self, target: Pose, settings: MotionSettings, line: int, joints: Optional[np.ndarray] = None) -> None:
        """A joint-interpolated move (it starts and ends at rest)."""
        self._issue("joint", target, settings, line, joints=joints)

    def linear(self, end: Pose, settings: MotionSettings, line: int) -> None:
        self.here("a linear move", line)
        self._issue("line", end, settings, line)

    def circular(self, via: Pose, end: Pose, settings: MotionSettings, line: int, last_line: Optional[int] = None) -> None:
        """The arc from the current pose through ``via`` to ``end`` (a statement from ``line`` to
        ``last_line``); InputError if they define none."""
        start = self.here("a circular move", line)
        try:
            arc_through(start.translation_mm, via.translation_mm, end.translation_mm)
        except DegenerateArc as exc:
            raise self.error(line, f"the arc from the current pose through the via point to the end is undefined: {exc}") \
                from None
        self._issue("arc", end, settings, line, via=via, last_line=last_line)

    def revise(self, index: int, **changes: object) -> None:
        """Change settings of motion ``index`` (e.g. ``stop_at_end``, ``accuracy_mm``)."""
        move = self.moves[index]
        move.settings = replace(move.settings, **changes)

    # --- rests, the gun, the tool ------------------------------------------------------
    def stop(self) -> None:
        """The last motion ends at rest."""
        if self.moves:
            self.revise(len(self.moves) - 1, stop_at_end=True)

    def dwell(self, seconds: float, line: int) -> None:
        """The robot stops, then rests ``seconds`` (the gun as it is)."""
        if not seconds >= 0.0:
            raise self.error(line, f"a wait must be >= 0 s, got {seconds:g}")
        self.stop()
        if seconds > 0.0:
            self.dwells.append(Dwell(len(self.moves) - 1, seconds, self.gun_on, line))

    def switch_gun(self, on: bool) -> None:
        """The gun output as from the next motion."""
        self.gun_on = on

    def switched(self, line: int, text: str, output: Optional[int] = None, gun: Optional[bool] = None) -> None:
        """Note a statement that switches an output (``output`` its number, when it has one; ``gun``
        what it does to the gun, when it is the gun), as the language writes it; a statement run
        again (a loop) is noted once."""
        if output is not None:
            self.outputs.add(output)
        source = self._origin()[0]
        if (source, line) in self._switch_lines:
            return
        self._switch_lines.add((source, line))
        self.switches.append(OutputSwitch(source, line, text + ("" if gun is None else f" (gun {'on' if gun else 'off'})")))

    def set_tool(self, frame: Optional[Pose], line: int) -> None:
        """The TCP in the flange frame for the motions after this (None: the controller's own, the
        cell's gun). The motion before ends at rest; the current pose is re-expressed with the new
        TCP (the flange stays put) when both TCPs are known."""
        new = None if frame is None else ToolFrame(np.array(frame.rotation), np.array(frame.translation_mm), line)
        if self.moves:
            self.stop()
        if self.current is not None and self.tool is not None and new is not None:
            flange = self.current @ Pose(self.tool.rotation, self.tool.offset_mm).inverse()
            self.current = flange @ frame
        self.tool = new

    # --- the result ---------------------------------------------------------------------
    def toolpath(self, name: str, process: ProcessInfo) -> ToolPath:
        """The ToolPath of the run (the last motion ends at rest)."""
        self.stop()
        moves: list[Move] = []
        for m in self.moves:
            if m.kind == "joint":
                moves.append(JointMove(m.start, m.end, m.settings, m.spray, m.line, joints_rad=m.joints))
            elif m.kind == "line":
                moves.append(LinearMove(m.start, m.end, m.settings, m.spray, m.line))
            else:
                moves.append(CircularMove(m.start, m.via, m.end, m.settings, m.spray, m.line))
        return ToolPath(name, tuple(moves), process, tuple(self.dwells), tuple(self.warnings), self.tool)

    def reading(self, toolpath: ToolPath, sources: tuple[str, ...], program: tuple[str, int], programs: tuple[str, ...],
                ended: str, n_steps: int, n_poses: int, **more: object) -> Reading:
        """The Reading of the run that made ``toolpath``: ``program`` the main program's file and
        line; ``more`` the Reading's other fields (problems, notes, unknowns)."""
        return Reading(toolpath=toolpath, sources=sources, program=toolpath.name, program_source=program[0],
                       program_line=program[1], programs=programs, ended=ended,
                       move_sources=tuple(self.move_sources), move_frames=tuple(self.move_frames), n_steps=n_steps,
                       n_poses=n_poses, switches=tuple(self.switches), outputs=tuple(sorted(self.outputs)),
                       gun_on_at_end=self.gun_on, **more)  # type: ignore[arg-type]
