"""Nest the statements of a program into blocks: IF/ELSEIF/ELSE/END, WHILE/END, DO/UNTIL,
FOR/END and CASE/VALUE/ANY/END. Every unmatched or misplaced marker is a syntax error naming
its line and the block it belongs to."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Optional

from coatsim.languages.kawasaki_as import ast
from coatsim.languages.kawasaki_as.source import AsSyntaxError, syntax_error
from coatsim.languages.kawasaki_as.statements_flow import Item, Marker, Open

MAX_NESTING = 64


@dataclass
class _Frame:
    """A block being read: its opener and the statement lists of its parts."""

    opener: Open
    parts: list[tuple[Optional[tuple], int, list]] = field(default_factory=list)  # (head, line, body)

    @property
    def body(self) -> list:
        return self.parts[-1][2]


class BlockBuilder:
    """Feed items line by line; :meth:`finish` returns the nested body."""

    def __init__(self, source: str, program: str) -> None:
        self.source, self.program = source, program
        self.top: list[ast.Statement] = []
        self.stack: list[_Frame] = []

    def error(self, line: int, message: str) -> AsSyntaxError:
        return syntax_error(self.source, line, 1, message)

    @property
    def body(self) -> list:
        return self.stack[-1].body if self.stack else self.top

    def add(self, item: Item) -> None:
        if isinstance(item, Open):
            if len(self.stack) >= MAX_NESTING:
                raise self.error(item.line, f"blocks nested more than {MAX_NESTING} deep")
            frame = _Frame(item)
            frame.parts.append((item.data, item.line, []))
            self.stack.append(frame)
            if item.kind == "CASE":
                frame.parts[-1] = (None, item.line, [])  # statements before the first VALUE
        elif isinstance(item, Marker):
            self.marker(item)
        else:
            self.body.append(item)

    def marker(self, m: Marker) -> None:
        frame = self.stack[-1] if self.stack else None
        kind = frame.opener.kind if frame else None
        if m.kind in ("ELSE", "ELSEIF"):
            if kind != "IF" or frame.parts[-1][0] == ("ELSE",):
                raise self.error(m.line, f"{m.kind} without an open IF ... THEN" + self._inside(frame))
            frame.parts.append((("ELSE",) if m.kind == "ELSE" else m.data, m.line, []))
        elif m.kind in ("VALUE", "ANY"):
            if kind != "CASE":
                raise self.error(m.line, f"{'VALUE' if m.kind == 'VALUE' else 'ANY'} outside a CASE ... OF block"
                                 + self._inside(frame))
            if frame.parts[-1][0] == ("ANY",):
                raise self.error(m.line, f"{m.kind} after ANY in the CASE block of line {frame.opener.line}")
            string = frame.opener.data[1]
            if m.kind == "VALUE" and m.data[1] != string:
                want = "SVALUE" if string else "VALUE"
                raise self.error(m.line, f"expected {want} in the {'SCASE' if string else 'CASE'} block of line "
                                 f"{frame.opener.line}")
            frame.parts.append((("ANY",) if m.kind == "ANY" else m.data, m.line, []))
        elif m.kind == "UNTIL":
            if kind != "DO":
                raise self.error(m.line, "UNTIL without an open DO" + self._inside(frame))
            self.close(m.line, m.data)
        else:  # END
            if frame is None:
                raise self.error(m.line, "END without an open block (IF, WHILE, FOR, CASE)")
            if kind == "DO":
                raise self.error(m.line, f"the DO block of line {frame.opener.line} ends with UNTIL condition, not END")
            self.close(m.line, ())

    def _inside(self, frame: Optional[_Frame]) -> str:
        return f" (inside the {frame.opener.kind} block of line {frame.opener.line})" if frame else ""

    def close(self, line: int, data: tuple) -> None:
        frame = self.stack.pop()
        o = frame.opener
        if o.kind == "IF":
            branches, orelse = [], ()
            for head, _, body in frame.parts:
                if head == ("ELSE",):
                    orelse = tuple(body)
                else:
                    branches.append((head[0], tuple(body)))
            node = ast.If(o.line, tuple(branches), orelse, line)
        elif o.kind == "WHILE":
            node = ast.While(o.line, o.data[0], tuple(frame.parts[0][2]), line)
        elif o.kind == "DO":
            node = ast.DoUntil(o.line, tuple(frame.parts[0][2]), data[0], line)
        elif o.kind == "FOR":
            var, start, stop, step = o.data
            node = ast.For(o.line, var, start, stop, step, tuple(frame.parts[0][2]), line)
        else:
            lead = frame.parts[0][2]
            if any(not isinstance(s, ast.Label) for s in lead):
                first = next(s for s in lead if not isinstance(s, ast.Label))
                raise self.error(first.line, f"statement before the first VALUE of the CASE block of line {o.line}")
            branches, default = [], None
            for head, at, body in frame.parts[1:]:
                if head == ("ANY",):
                    default = tuple(body)
                else:
                    branches.append((head[0], tuple(body), at))
            node = ast.Case(o.line, o.data[0], tuple(branches), default, o.data[1], line)
        self.body.append(node)

    def finish(self, end_line: int) -> tuple[ast.Statement, ...]:
        if self.stack:
            o = self.stack[-1].opener
            closer = "UNTIL condition" if o.kind == "DO" else "END"
            raise self.error(end_line, f"the {o.kind} block of line {o.line} in program '{self.program}' is not "
                             f"closed; expected {closer} before .END")
        return tuple(self.top)
