"""Expression nodes of the statement languages (RAPID, KRL): what their parsers build and their
interpreters evaluate. ``line`` is the source line."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional, Union


@dataclass(frozen=True)
class Num:
    """A number; ``integer`` when written without a point or exponent (KRL types it INT)."""

    value: float
    line: int
    integer: bool = False


@dataclass(frozen=True)
class Str:
    value: str
    line: int


@dataclass(frozen=True)
class Name:
    """A name (``p10``, ``$VEL``, ``#BASE``) as written."""

    name: str
    line: int


@dataclass(frozen=True)
class Field:
    """``base.field``."""

    base: "Expr"
    field: str
    line: int


@dataclass(frozen=True)
class Index:
    """``base{i, j}`` (RAPID) or ``base[i, j]`` (KRL)."""

    base: "Expr"
    index: tuple["Expr", ...]
    line: int


@dataclass(frozen=True)
class Arg:
    """An argument of a call: positional (``name`` None), named optional (RAPID ``\\WObj:=w``,
    ``value`` None for a switch ``\\Off``)."""

    value: Optional["Expr"]
    name: Optional[str] = None


@dataclass(frozen=True)
class Call:
    name: str
    args: tuple[Arg, ...]
    line: int


@dataclass(frozen=True)
class Unary:
    op: str
    operand: "Expr"
    line: int


@dataclass(frozen=True)
class Binary:
    op: str
    left: "Expr"
    right: "Expr"
    line: int


@dataclass(frozen=True)
class Aggregate:
    """``[a, b, [c]]`` (RAPID) or ``{X 1, Y 2}`` / ``{E6POS: X 1}`` (KRL: ``fields`` names each
    item, ``type`` the optional type prefix)."""

    items: tuple["Expr", ...]
    line: int
    fields: tuple[str, ...] = ()
    type: str = ""


Expr = Union[Num, Str, Name, Field, Index, Call, Unary, Binary, Aggregate]
