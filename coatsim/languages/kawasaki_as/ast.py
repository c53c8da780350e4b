"""Typed syntax tree of Kawasaki AS as real programs use it.

A parsed file is an :class:`AsFile`: its ``.PROGRAM`` blocks (:class:`Program`, a body of
statements, blocks nested), its data sections (``.TRANS``, ``.JOINTS``, ``.REALS``,
``.STRINGS``) and every other section kept as raw lines (:class:`RawSection`: controller
backups hold ``.AUXDATA``, ``.SYSDATA``, ``.ROBOTDATA1``, ``.NETCONF``, ``.SIG_COMMENT``, ...).

Expressions are untyped trees; the interpreter evaluates them in the context a statement
gives (a real, a string, a pose or a joint value). Names keep their prefixes: ``.x`` is local,
``$s`` a string, ``#j`` a joint value.
"""

from __future__ import annotations

# the expressions, the statements and the file structure live in their own modules; ``ast.X``
# names them all
from coatsim.languages.kawasaki_as.ast_expr import (  # noqa: F401
    Binary,
    Call,
    Chain,
    Expr,
    Format,
    JointLiteral,
    Name,
    Num,
    Ref,
    Shift,
    Str,
    Unary,
)
from coatsim.languages.kawasaki_as.ast_files import (  # noqa: F401
    AsFile,
    JointDef,
    Param,
    Program,
    RawSection,
    RealDef,
    StringDef,
    TransDef,
)
from coatsim.languages.kawasaki_as.ast_statements import (  # noqa: F401
    Accel,
    Accuracy,
    Appro,
    Assign,
    Base,
    Bits,
    BlockStep,
    Brake,
    Break,
    CallProgram,
    Case,
    Command,
    Decompose,
    Delay,
    Depart,
    DoUntil,
    Draw,
    Exit,
    For,
    Goto,
    Here,
    Home,
    If,
    Label,
    Move,
    Output,
    PointAssign,
    Pulse,
    Return,
    Signal,
    Speed,
    Statement,
    Stop,
    Swait,
    Switch,
    Tool,
    Twait,
    Wait,
    While,
)

MAX_AXES = 18  # values a pose or joint value may hold: six arm axes, then external axes (rails, positioners)
