"""Statements of Kawasaki AS as real programs use them (blocks nested); ``Statement`` is their union."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional, Union

from coatsim.languages.kawasaki_as.ast_expr import Expr, Name


@dataclass(frozen=True)
class Stmt:
    """Base of all statements: ``line`` is the 1-based source line."""

    line: int


@dataclass(frozen=True)
class Label(Stmt):
    """A step label (``10``) or a named label (``re_connect:``)."""

    name: str


@dataclass(frozen=True)
class Assign(Stmt):
    """``x = expr`` (a real) or ``$s = expr`` (a string)."""

    target: Name
    value: Expr


@dataclass(frozen=True)
class PointAssign(Stmt):
    """``POINT p = expr`` (pose), ``POINT #j = expr`` (joints); ``component`` for
    ``POINT/X p = q`` (X, Y, Z, O, A, T or OAT: only that part of q is copied); ``reference``
    the joint value that picks the arm's configuration in ``POINT #j = p, #ref``."""

    target: Name
    value: Expr
    component: Optional[str] = None
    reference: Optional[Expr] = None


@dataclass(frozen=True)
class Decompose(Stmt):
    """``DECOMPOSE arr[i] = pose``: x y z o a t (or the joint values) into arr[i], arr[i+1], ..."""

    target: Name
    value: Expr


@dataclass(frozen=True)
class Here(Stmt):
    """``HERE p`` / ``HERE #j``: store where the robot is."""

    target: Name


@dataclass(frozen=True)
class Move(Stmt):
    """JMOVE, LMOVE, C1MOVE, C2MOVE, HMOVE ``target`` [, clamp]; XMOVE ``target`` TILL ``till``."""

    op: str
    target: Expr
    clamp: Optional[Expr] = None
    till: Optional[Expr] = None


@dataclass(frozen=True)
class Appro(Stmt):
    """JAPPRO / LAPPRO ``target``, ``distance``: ``distance`` mm back along its tool z."""

    op: str
    target: Expr
    distance: Expr


@dataclass(frozen=True)
class Depart(Stmt):
    """JDEPART / LDEPART ``distance``: back along the current tool z."""

    op: str
    distance: Expr


@dataclass(frozen=True)
class Draw(Stmt):
    """DRAW (base axes) / TDRAW (tool axes) dx, dy, dz [, rx, ry, rz [, speed]]; empty parts None."""

    op: str
    deltas: tuple[Optional[Expr], ...]


@dataclass(frozen=True)
class Home(Stmt):
    """HOME [n] (HOME2 is n = 2)."""

    number: Optional[Expr]


@dataclass(frozen=True)
class Delay(Stmt):
    """DELAY t / STABLE t: a motion step in which the robot stands still t s."""

    op: str
    seconds: Expr


@dataclass(frozen=True)
class Speed(Stmt):
    """SPEED value [unit] [ALWAYS]; unit is "%", "MM/S", "MM/MIN", "CM/S", "CM/MIN", "S",
    "DEG/S" or "DEG/MIN"."""

    value: Expr
    unit: str
    always: bool


@dataclass(frozen=True)
class Accuracy(Stmt):
    """ACCURACY d [ALWAYS] [FINE]."""

    value: Expr
    always: bool
    fine: bool


@dataclass(frozen=True)
class Accel(Stmt):
    """ACCEL / DECEL percent [ALWAYS]."""

    op: str
    value: Expr
    always: bool


@dataclass(frozen=True)
class Switch(Stmt):
    """A system switch set ON or OFF: ``CP ON``, ``QTOOL OFF``, ``ABS.SPEED ON``, ``SWITCH X ON``."""

    name: str
    on: bool


@dataclass(frozen=True)
class Break(Stmt):
    """BREAK: wait until the current motion has finished."""


@dataclass(frozen=True)
class Brake(Stmt):
    """BRAKE: stop the motion in progress at once."""


@dataclass(frozen=True)
class Tool(Stmt):
    """TOOL pose: the TCP relative to the flange."""

    pose: Expr


@dataclass(frozen=True)
class Base(Stmt):
    """BASE pose: the frame poses are given in, relative to the robot base."""

    pose: Expr


@dataclass(frozen=True)
class Signal(Stmt):
    """SIGNAL n [, m ...]: outputs on (n > 0) or off (n < 0)."""

    outputs: tuple[Expr, ...]


@dataclass(frozen=True)
class Pulse(Stmt):
    """PULSE n [, t] (on for t s) / DLYSIG n, t (set n after t s)."""

    op: str
    signal: Expr
    seconds: Optional[Expr]


@dataclass(frozen=True)
class Bits(Stmt):
    """BITS start, count = value: ``count`` outputs from ``start`` set to the bits of value."""

    start: Expr
    count: Expr
    value: Expr


@dataclass(frozen=True)
class Swait(Stmt):
    """SWAIT n [, m ...]: wait until every signal is in the state its sign gives."""

    signals: tuple[Expr, ...]


@dataclass(frozen=True)
class Wait(Stmt):
    """WAIT condition."""

    condition: Expr


@dataclass(frozen=True)
class Twait(Stmt):
    """TWAIT t: the program waits t s (the robot may still be moving)."""

    seconds: Expr


@dataclass(frozen=True)
class Output(Stmt):
    """TYPE / PRINT / PROMPT: ``items`` are expressions and formats (``/D``, ``/F8.3``);
    PROMPT's ``target`` receives the operator's answer."""

    op: str
    items: tuple[Expr, ...]
    target: Optional[Name] = None


@dataclass(frozen=True)
class CallProgram(Stmt):
    """CALL name[(args)]; SCALL takes the program name from a string expression."""

    program: Union[str, Expr]
    args: tuple[Expr, ...]


@dataclass(frozen=True)
class Goto(Stmt):
    """GOTO label, or ``IF condition GOTO label`` when ``condition`` is given."""

    label: str
    condition: Optional[Expr] = None


@dataclass(frozen=True)
class Return(Stmt):
    """RETURN: back to the calling program."""


@dataclass(frozen=True)
class Stop(Stmt):
    """STOP / HALT: the program ends (PAUSE: it pauses and may go on)."""

    op: str


@dataclass(frozen=True)
class Exit(Stmt):
    """EXIT: leave the innermost loop."""


@dataclass(frozen=True)
class If(Stmt):
    """IF c THEN ... [ELSEIF c THEN ...] [ELSE ...] END: ``branches`` in order, ``orelse`` last."""

    branches: tuple[tuple[Expr, tuple["Statement", ...]], ...]
    orelse: tuple["Statement", ...]
    end_line: int


@dataclass(frozen=True)
class While(Stmt):
    """WHILE c DO ... END."""

    condition: Expr
    body: tuple["Statement", ...]
    end_line: int


@dataclass(frozen=True)
class DoUntil(Stmt):
    """DO ... UNTIL c."""

    body: tuple["Statement", ...]
    condition: Expr
    end_line: int


@dataclass(frozen=True)
class For(Stmt):
    """FOR v = a TO b [STEP s] ... END."""

    var: Name
    start: Expr
    stop: Expr
    step: Optional[Expr]
    body: tuple["Statement", ...]
    end_line: int


@dataclass(frozen=True)
class Case(Stmt):
    """CASE x OF (SCASE $x OF): VALUE a, b: ... ANY: ... END."""

    subject: Expr
    branches: tuple[tuple[tuple[Expr, ...], tuple["Statement", ...], int], ...]
    default: Optional[tuple["Statement", ...]]
    string: bool
    end_line: int


@dataclass(frozen=True)
class Command(Stmt):
    """Any other AS instruction (tasks, monitor commands, network and serial I/O, grippers,
    display, configuration), with its arguments as expressions where they parse as such
    (``args``) and as written (``text``)."""

    name: str
    args: tuple[Expr, ...]
    text: str


@dataclass(frozen=True)
class BlockStep(Stmt):
    """A teach-pendant block step (``LINEAR 125. ACCU1 ... #[...]``), kept as written."""

    kind: str
    text: str


Statement = Union[Label, Assign, PointAssign, Decompose, Here, Move, Appro, Depart, Draw, Home, Delay, Speed,
                  Accuracy, Accel, Switch, Break, Brake, Tool, Base, Signal, Pulse, Bits, Swait, Wait, Twait,
                  Output, CallProgram, Goto, Return, Stop, Exit, If, While, DoUntil, For, Case, Command, BlockStep]
