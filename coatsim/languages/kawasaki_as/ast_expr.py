"""AS expressions as untyped trees: numbers, strings, variables (prefixes kept: ``.x`` local,
``$s`` string, ``#j`` joint), operators, built-in calls, SHIFT, joint literals and formats;
the interpreter evaluates them in the context a statement gives."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional, Union


@dataclass(frozen=True)
class Num:
    value: float


@dataclass(frozen=True)
class Str:
    value: str


@dataclass(frozen=True)
class Name:
    """A variable, ``index`` holding the expressions of ``name[i, j]``; ``whole`` for an entire
    array written with empty indices (``a[]``, ``a[,]``), as a CALL argument passes one."""

    name: str
    index: tuple["Expr", ...] = ()
    whole: bool = False

    @property
    def base(self) -> str:
        """The name without the local prefix: what tells its kind ('$', '#')."""
        return self.name[1:] if self.name.startswith(".") else self.name

    @property
    def is_local(self) -> bool:
        return self.name.startswith(".")

    @property
    def kind(self) -> str:
        """'string', 'joint' or 'value' (a real or a pose; the context decides)."""
        first = self.base[:1]
        return "string" if first == "$" else "joint" if first == "#" else "value"


@dataclass(frozen=True)
class Ref:
    """``&x`` / ``.&x``: a variable passed by reference (CALL and $DECODE arguments)."""

    target: Name


@dataclass(frozen=True)
class Unary:
    op: str  # "-", "+", "NOT"
    operand: "Expr"


@dataclass(frozen=True)
class Binary:
    op: str  # + - * / ^ MOD == <> < > <= >= AND OR XOR BAND BOR BXOR
    left: "Expr"
    right: "Expr"


@dataclass(frozen=True)
class Chain:
    """Three or more operands joined by left-associative operators of one precedence
    (``a + b - c``, ``x * y / z``): kept flat, so that a long sum is no deep tree."""

    first: "Expr"
    rest: tuple[tuple[str, "Expr"], ...]


@dataclass(frozen=True)
class Call:
    """A built-in function (upper-case ``name``, prefix kept: ``$MID``, ``#HERE``); an
    argument is None where it is left empty (``TRANS(,,50)``)."""

    name: str
    args: tuple[Optional["Expr"], ...]


@dataclass(frozen=True)
class Shift:
    """``SHIFT(base BY dx, dy, dz)``; empty offsets are None (zero)."""

    base: "Expr"
    delta: tuple[Optional["Expr"], Optional["Expr"], Optional["Expr"]]


@dataclass(frozen=True)
class JointLiteral:
    """``#[j1, ..., jn]`` (deg); empty components are None."""

    values: tuple[Optional["Expr"], ...]


@dataclass(frozen=True)
class Format:
    """A format item of ``$ENCODE`` / ``TYPE``: ``/D``, ``/F8.3``, ``/E``, ``/G``, ``/X2`` ..."""

    spec: str


Expr = Union[Num, Str, Name, Ref, Unary, Binary, Chain, Call, Shift, JointLiteral, Format]
