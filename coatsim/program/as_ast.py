"""Typed syntax tree of the Kawasaki AS subset coatsim reads.

A parsed file is an :class:`AsFile`: its ``.PROGRAM`` blocks (:class:`AsProgram`, statements in
order, each carrying its source line) and its data sections (``.TRANS``, ``.JOINTS``,
``.REALS``). Numbers in statements are literals or references to ``.REALS`` variables;
poses are expressions over ``.TRANS`` names, ``TRANS(...)`` literals and ``SHIFT``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Mapping, Optional, Union


@dataclass(frozen=True)
class RealRef:
    """A real variable used as a number; ``negate`` for a leading minus."""

    name: str
    negate: bool = False


Num = Union[float, RealRef]


@dataclass(frozen=True)
class PoseName:
    """A transformation variable (``.TRANS`` name or POINT target)."""

    name: str


@dataclass(frozen=True)
class JointName:
    """A joint variable ``#name``."""

    name: str


@dataclass(frozen=True)
class TransLiteral:
    """``TRANS(x, y, z, o, a, t)`` (mm, deg)."""

    values: tuple[Num, ...]


@dataclass(frozen=True)
class JointLiteral:
    """``#[j1, ..., jn]`` (deg)."""

    values: tuple[Num, ...]


@dataclass(frozen=True)
class NullPose:
    """``NULL``: the identity transformation."""


@dataclass(frozen=True)
class Shift:
    """``SHIFT(base BY dx, dy, dz)``: ``base`` translated along the base axes."""

    base: "PoseExpr"
    delta: tuple[Num, Num, Num]


@dataclass(frozen=True)
class Compose:
    """``left + right``: ``right`` expressed in ``left``'s frame."""

    left: "PoseExpr"
    right: "PoseExpr"


PoseExpr = Union[PoseName, JointName, TransLiteral, JointLiteral, NullPose, Shift, Compose]


@dataclass(frozen=True)
class Stmt:
    """Base of all statements: ``line`` is the 1-based source line."""

    line: int


@dataclass(frozen=True)
class Move(Stmt):
    """JMOVE / LMOVE / C1MOVE / C2MOVE ``target`` [, clamp]."""

    op: str
    target: PoseExpr
    clamp: Optional[Num] = None


@dataclass(frozen=True)
class Appro(Stmt):
    """JAPPRO / LAPPRO ``target``, ``distance``: ``distance`` mm back along its tool z."""

    op: str
    target: PoseExpr
    distance: Num


@dataclass(frozen=True)
class Depart(Stmt):
    """JDEPART / LDEPART ``distance``: back along the current tool z."""

    op: str
    distance: Num


@dataclass(frozen=True)
class Draw(Stmt):
    """DRAW (base axes) / TDRAW (tool axes) dx, dy, dz [, do, da, dt]."""

    op: str
    deltas: tuple[Num, ...]


@dataclass(frozen=True)
class Home(Stmt):
    """HOME [n]."""

    number: Optional[int]


@dataclass(frozen=True)
class Delay(Stmt):
    """DELAY t: the robot holds still for t s."""

    seconds: Num


@dataclass(frozen=True)
class Speed(Stmt):
    """SPEED value [unit] [ALWAYS]; unit is "%", "MM/S", "MM/MIN" or "S"."""

    value: Num
    unit: str
    always: bool


@dataclass(frozen=True)
class Accuracy(Stmt):
    """ACCURACY d [ALWAYS] [FINE]."""

    value: Num
    always: bool
    fine: bool


@dataclass(frozen=True)
class Accel(Stmt):
    """ACCEL / DECEL percent [ALWAYS]."""

    op: str
    value: Num
    always: bool


@dataclass(frozen=True)
class Cp(Stmt):
    """CP ON / CP OFF."""

    on: bool


@dataclass(frozen=True)
class Break(Stmt):
    """BREAK: wait until the current motion has finished."""


@dataclass(frozen=True)
class Signal(Stmt):
    """SIGNAL n [, m ...]: outputs on (n > 0) or off (n < 0)."""

    outputs: tuple[int, ...]


@dataclass(frozen=True)
class Twait(Stmt):
    """TWAIT t: the program waits t s (the robot may still move)."""

    seconds: Num


@dataclass(frozen=True)
class Tool(Stmt):
    """TOOL pose: the TCP relative to the flange."""

    pose: PoseExpr


@dataclass(frozen=True)
class Base(Stmt):
    """BASE pose: the frame poses are given in, relative to the robot base."""

    pose: PoseExpr


@dataclass(frozen=True)
class Point(Stmt):
    """POINT name = pose."""

    name: str
    pose: PoseExpr


Statement = Union[Move, Appro, Depart, Draw, Home, Delay, Speed, Accuracy, Accel, Cp, Break,
                  Signal, Twait, Tool, Base, Point]


@dataclass(frozen=True)
class TransDef:
    """A ``.TRANS`` line: x, y, z (mm), o, a, t (deg), then external axes if any."""

    name: str
    values: tuple[float, float, float, float, float, float]
    extra: tuple[float, ...]
    line: int


@dataclass(frozen=True)
class JointDef:
    """A ``.JOINTS`` line (deg, mm for linear axes)."""

    name: str
    values: tuple[float, ...]
    line: int


@dataclass(frozen=True)
class RealDef:
    """A ``.REALS`` line ``name = value``."""

    name: str
    value: float
    line: int


@dataclass(frozen=True)
class AsProgram:
    """One ``.PROGRAM`` block; ``metadata`` from its ``; coatsim: key=value`` comments."""

    name: str
    line: int
    statements: tuple[Statement, ...]
    metadata: tuple[tuple[str, str], ...]


@dataclass(frozen=True)
class AsFile:
    """A parsed AS file; ``skipped`` lists (section, line) of dot-sections not read."""

    source: str
    programs: tuple[AsProgram, ...]
    trans: Mapping[str, TransDef]
    joints: Mapping[str, JointDef]
    reals: Mapping[str, RealDef]
    skipped: tuple[tuple[str, int], ...]
    n_lines: int
