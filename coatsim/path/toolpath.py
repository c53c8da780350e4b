"""ToolPath: what a robot program asks the tool to do, in Cartesian terms.

This is the contract between the programs stage (the interpreter produces it from parsed AS
text) and the robot stage (which executes it). Poses are coatsim's one pose type
(:class:`~coatsim.geometry.space.pose.Pose`) in the robot base frame, mm; a rotation's columns
are the tool x, y, z axes (z = spray axis).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Optional, Protocol, Union

import numpy as np

from coatsim.geometry.space.pose import Pose
from coatsim.path.process import ProcessInfo


@dataclass(frozen=True, eq=False)
class ToolFrame:
    """A TOOL in force: the controller's TCP in the flange frame, ``rotation`` (3, 3) and
    ``offset_mm`` (3,), set by the TOOL statement on source ``line``."""

    rotation: np.ndarray
    offset_mm: np.ndarray
    line: int


@dataclass(frozen=True)
class MotionSettings:
    """Controller settings in force for one motion.

    ``stop_at_end``: the controller brings the tool to rest at the end of this motion
    (CP OFF, ACCURACY ... FINE, or a BREAK before the next step); otherwise it blends into
    the next motion within ``accuracy_mm``. ``tool``: the TOOL the controller computes this
    motion's poses with; None when the program sets none (the controller's own, which the
    twin takes to be the cell's gun).
    """

    speed_mm_s: float
    accuracy_mm: float
    cp: bool
    stop_at_end: bool
    tool: ToolFrame | None = None


@dataclass(frozen=True, eq=False)
class JointMove:
    """JMOVE / JAPPRO / HOME: joint-interpolated move to ``target`` (path not Cartesian).

    ``start`` is None for the first move of a program: the robot starts wherever it is.
    ``joints_rad`` (6,) is the configuration to reach when the program gives one (a joint
    value, HOME); ``target`` is then its forward kinematics. Otherwise the robot stage solves
    the inverse kinematics of ``target``.
    """

    start: Pose | None
    target: Pose
    settings: MotionSettings
    spray: bool
    line: int
    kind: str = field(default="joint", init=False)
    joints_rad: Optional[np.ndarray] = None


@dataclass(frozen=True, eq=False)
class LinearMove:
    """LMOVE / LAPPRO / LDEPART: straight TCP line from ``start`` to ``end``."""

    start: Pose
    end: Pose
    settings: MotionSettings
    spray: bool
    line: int
    kind: str = field(default="line", init=False)


@dataclass(frozen=True, eq=False)
class CircularMove:
    """C1MOVE via + C2MOVE end: the circle arc through ``start``, ``via`` and ``end``.

    ``line`` is the source line of the C2MOVE.
    """

    start: Pose
    via: Pose
    end: Pose
    settings: MotionSettings
    spray: bool
    line: int
    kind: str = field(default="arc", init=False)


Move = Union[JointMove, LinearMove, CircularMove]


@dataclass(frozen=True)
class Dwell:
    """The tool rests ``seconds`` at the end of move ``after`` (-1: before the first move),
    the gun on when ``spray``: TWAIT, DELAY and STABLE (the coat sees a thick spot)."""

    after: int
    seconds: float
    spray: bool
    line: int


class Kinematics(Protocol):
    """What the interpreter needs to know of the cell: forward kinematics of a joint
    configuration (rad) to the controller's TCP (base frame, mm) under a TOOL (None: the
    controller's own, the cell's gun), and the home configurations."""

    def forward(self, joints_rad: np.ndarray, tool: Optional[ToolFrame] = None) -> Pose:
        ...

    def home(self, number: int) -> Optional[np.ndarray]:
        """HOME n (1 = the start configuration of every program); None where the cell has no
        keyframe ``home<n>`` (a home pose taught on the pendant)."""
        ...


@dataclass(frozen=True, eq=False)
class ToolPath:
    """The moves of a program in execution order.

    ``spray`` on a move is true when the gun output is on for the whole move: signals switch
    at move boundaries, as a move starts (see the interpreter for the forward-processing rule).
    ``process`` is the program's record of how coatsim made it (lead-in and lead-out, sprayed
    contours, speed limits), decoded by the language's reader, so downstream stages can tell the
    curve proper from the run-in and run-out without the in-memory polysegment; empty for a
    program written by anyone else. ``dwells`` are the rests between moves in program order;
    ``warnings`` what the interpreter did not simulate, one line each; ``tool`` the TOOL in
    force when the program ends (None: the controller's own).
    """

    name: str
    moves: tuple[Move, ...]
    process: ProcessInfo = ProcessInfo()
    dwells: tuple[Dwell, ...] = ()
    warnings: tuple[str, ...] = ()
    tool: ToolFrame | None = None

    @property
    def spray_moves(self) -> tuple[Move, ...]:
        return tuple(m for m in self.moves if m.spray)
