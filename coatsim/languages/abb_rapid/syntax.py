"""RAPID's lexical rules, its expression grammar and its statements (the syntax tree).

RAPID is case-insensitive; ``!`` starts a comment; statements end with ``;``; arrays are indexed
with ``{}``, aggregates written with ``[]``; optional arguments are ``\\Name:=value`` or the switch
``\\Name`` (ABB, Technical reference manual — RAPID overview, "Basic elements"; RAPID Instructions,
Functions and Data types).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Optional

from coatsim.languages.script.nodes import Arg, Expr
from coatsim.languages.script.parse import Grammar
from coatsim.languages.script.tokens import Syntax

SYNTAX = Syntax(comment="!", name_start="", operators=(":=", "<>", "<=", ">=", "+", "-", "*", "/", "=", "<", ">",
                                                       "(", ")", "[", "]", "{", "}", ",", ";", ":", ".", "\\", "|",
                                                       "%", "?"))
GRAMMAR = Grammar(binary={"OR": 1, "XOR": 1, "AND": 2, "=": 4, "<>": 4, "<": 4, ">": 4, "<=": 4, ">=": 4,
                          "+": 5, "-": 5, "*": 6, "/": 6, "DIV": 6, "MOD": 6},
                  unary={"NOT": 3, "-": 7, "+": 7}, index_open="{", index_close="}", aggregate_open="[")


@dataclass(frozen=True)
class DataDecl:
    """``[LOCAL|TASK] VAR|PERS|CONST type name{dims} := value;``"""

    storage: str
    type: str
    name: str
    dims: tuple[Expr, ...]
    value: Optional[Expr]
    line: int
    source: str


@dataclass(frozen=True)
class Param:
    """A routine parameter: ``mode`` (IN, VAR, PERS, INOUT), optional (``\\``), its alternatives."""

    name: str
    type: str
    mode: str = "IN"
    optional: bool = False


@dataclass(frozen=True)
class Assign:
    target: Expr
    value: Expr
    line: int


@dataclass(frozen=True)
class ProcCall:
    """An instruction or a procedure call: ``MoveL p10, v500, z10, tool0\\WObj:=wobj1;``;
    ``late`` a late-bound call ``%name% ...`` (its name an expression)."""

    name: str
    args: tuple[Arg, ...]
    line: int
    end_line: int
    late: Optional[Expr] = None


@dataclass(frozen=True)
class If:
    branches: tuple[tuple[Expr, tuple], ...]
    orelse: tuple
    line: int
    end_line: int


@dataclass(frozen=True)
class For:
    var: str
    start: Expr
    stop: Expr
    step: Optional[Expr]
    body: tuple
    line: int
    end_line: int


@dataclass(frozen=True)
class While:
    cond: Expr
    body: tuple
    line: int
    end_line: int


@dataclass(frozen=True)
class Test:
    value: Expr
    cases: tuple[tuple[tuple[Expr, ...], tuple], ...]
    default: Optional[tuple]
    line: int
    end_line: int


@dataclass(frozen=True)
class Goto:
    label: str
    line: int


@dataclass(frozen=True)
class Label:
    name: str
    line: int


@dataclass(frozen=True)
class Return:
    value: Optional[Expr]
    line: int


@dataclass(frozen=True)
class Connect:
    """``CONNECT intno WITH trap;`` (interrupts are noted, not run)."""

    interrupt: Expr
    trap: str
    line: int


@dataclass(frozen=True)
class Routine:
    """A PROC, FUNC or TRAP: its parameters, data declared in it, statements (an ERROR or UNDO
    handler is kept apart and not run)."""

    kind: str
    name: str
    type: str
    params: tuple[Param, ...]
    data: tuple[DataDecl, ...]
    body: tuple
    line: int
    end_line: int
    source: str
    handlers: tuple[str, ...] = ()


@dataclass(frozen=True)
class Module:
    name: str
    attributes: tuple[str, ...]
    data: tuple[DataDecl, ...]
    routines: tuple[Routine, ...]
    line: int
    source: str
    records: tuple[str, ...] = field(default_factory=tuple)
