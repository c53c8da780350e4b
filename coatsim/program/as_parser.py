"""Kawasaki AS reader: program text -> :class:`~coatsim.program.as_ast.AsFile`.

Reads ``.PROGRAM`` / ``.END`` blocks, ``.TRANS``, ``.JOINTS`` and ``.REALS``; skips any other
dot-section up to its ``.END`` (``.STRINGS``, controller backup sections) and ``.*`` header
lines. Statements may carry a numeric or ``name:`` label and a ``;`` comment. Every defect is an
:class:`AsSyntaxError` naming line, column and what was expected; no other exception escapes.
"""

from __future__ import annotations

import re
from typing import Callable, Optional

from coatsim.program import as_ast as ast
from coatsim.program.as_lexer import AsSyntaxError, Cursor, syntax_error, tokenize
from coatsim.program.as_statements import parse_statement

_PROGRAM_HEADER = re.compile(r"\.PROGRAM[ \t]+(\.?[A-Za-z_][A-Za-z0-9_.]*)[ \t]*(\([^)]*\))?", re.IGNORECASE)
_DIRECTIVE = re.compile(r"\.([A-Za-z_][A-Za-z0-9_]*)")
_METADATA = re.compile(r"[ \t]*(?:\d+[ \t]+)?;[ \t]*coatsim:[ \t]*([A-Za-z0-9_.]+)[ \t]*=(.*)$")
_DATA_SECTIONS = ("TRANS", "JOINTS", "REALS")


def _is_end(stripped: str) -> bool:
    return stripped[:4].upper() == ".END" and (len(stripped) == 4 or stripped[4] in " \t;")


class _Reader:
    """Line-by-line state machine over the dot-sections of a file."""

    def __init__(self, source: str) -> None:
        self.source = source
        self.programs: list[ast.AsProgram] = []
        self.trans: dict[str, ast.TransDef] = {}
        self.joints: dict[str, ast.JointDef] = {}
        self.reals: dict[str, ast.RealDef] = {}
        self.skipped: list[tuple[str, int]] = []
        self.section: Optional[str] = None
        self.section_line = 0
        self.program_name = ""
        self.statements: list[ast.Statement] = []
        self.metadata: list[tuple[str, str]] = []
        self.defined: dict[str, int] = {}

    def error(self, line: int, col: int, message: str) -> AsSyntaxError:
        return syntax_error(self.source, line, col, message)

    def feed(self, line: int, text: str) -> None:
        stripped = text.lstrip(" \t")
        col = len(text) - len(stripped) + 1
        if self.section is not None and self.section not in ("PROGRAM", *_DATA_SECTIONS):
            if _is_end(stripped):
                self.section = None
            return
        if _is_end(stripped):
            self._end(line, col, stripped)
        elif self.section == "PROGRAM":
            self._program_line(line, text, stripped, col)
        elif self.section is not None:
            self._data_line(line, text)
        elif stripped.startswith("."):
            self._directive(line, text, stripped, col)
        elif stripped and not stripped.startswith(";"):
            raise self.error(line, col, "statement outside a section; expected a dot-section such as '.PROGRAM name()'")

    def _end(self, line: int, col: int, stripped: str) -> None:
        if self.section is None:
            raise self.error(line, col, "'.END' without an open section")
        if tokenize(stripped[4:], self.source, line):
            raise self.error(line, col + 4, "unexpected text after '.END'; expected end of line")
        if self.section == "PROGRAM":
            self.programs.append(ast.AsProgram(self.program_name, self.section_line, tuple(self.statements), tuple(self.metadata)))
        self.section = None

    def _directive(self, line: int, text: str, stripped: str, col: int) -> None:
        if stripped.startswith(".*"):
            return
        m = _DIRECTIVE.match(stripped)
        if m is None:
            raise self.error(line, col, "expected a dot-section name such as '.PROGRAM', '.TRANS' or '.END'")
        word = m.group(1).upper()
        self.section, self.section_line = word, line
        if word == "PROGRAM":
            header = _PROGRAM_HEADER.match(stripped)
            if header is None:
                raise self.error(line, col + m.end() + 1, "expected a program name after '.PROGRAM', as in '.PROGRAM name()'")
            name = header.group(1)
            if name.lower() in self.defined:
                raise self.error(line, col, f"program '{name}' is defined twice (first at line {self.defined[name.lower()]})")
            self.defined[name.lower()] = line
            self.program_name, self.statements, self.metadata = name, [], []
        elif word in _DATA_SECTIONS:
            rest = stripped[m.end():]
            if tokenize(rest, self.source, line):
                raise self.error(line, col + m.end(), f"unexpected text after '.{word}'; expected end of line")
        else:
            self.skipped.append((word, line))

    def _program_line(self, line: int, text: str, stripped: str, col: int) -> None:
        if stripped[:8].upper() == ".PROGRAM":
            raise self.error(line, col, f"'.PROGRAM' inside program '{self.program_name}' (line {self.section_line}); expected '.END' first")
        meta = _METADATA.match(text)
        if meta is not None:
            self.metadata.append((meta.group(1), meta.group(2).strip()))
            return
        tokens = tokenize(text, self.source, line)
        if tokens:
            statement = parse_statement(tokens, self.source, line, len(text))
            if statement is not None:
                self.statements.append(statement)

    def _data_line(self, line: int, text: str) -> None:
        tokens = tokenize(text, self.source, line)
        if not tokens:
            return
        cur = Cursor(tokens, self.source, line, len(text))
        parse: Callable[[Cursor, int], None] = {
            "TRANS": self._trans, "JOINTS": self._joint, "REALS": self._real,
        }[self.section or ""]
        parse(cur, line)

    def _unique(self, table: dict, name: str, line: int, col: int, kind: str) -> None:
        if name in table:
            raise self.error(line, col, f"{kind} '{name}' is defined twice (first at line {table[name].line})")

    def _trans(self, cur: Cursor, line: int) -> None:
        col = cur.peek().col
        name = cur.name("a pose name")
        values = []
        while cur.peek() is not None:
            if len(values) == 7:
                raise cur.error(f"too many numbers for pose '{name}'; expected x y z o a t and at most one external axis", cur.peek())
            values.append(cur.number("a number (x y z mm, o a t deg)"))
        if len(values) < 6:
            raise cur.error(f"pose '{name}' has {len(values)} numbers; expected 6 (x y z o a t) or 7")
        self._unique(self.trans, name, line, col, "pose")
        self.trans[name] = ast.TransDef(name, tuple(values[:6]), tuple(values[6:]), line)

    def _joint(self, cur: Cursor, line: int) -> None:
        col = cur.peek().col
        name = cur.name("a joint pose name", joint=True)
        values = []
        while cur.peek() is not None:
            if len(values) == 9:
                raise cur.error(f"too many numbers for joint pose '{name}'; expected 6 to 9 joint values", cur.peek())
            values.append(cur.number("a joint value"))
        if len(values) < 6:
            raise cur.error(f"joint pose '{name}' has {len(values)} values; expected 6 to 9")
        self._unique(self.joints, name, line, col, "joint pose")
        self.joints[name] = ast.JointDef(name, tuple(values), line)

    def _real(self, cur: Cursor, line: int) -> None:
        col = cur.peek().col
        name = cur.name("a real variable name")
        eq = cur.take()
        if eq is None or eq.text != "=":
            raise cur.error(f"expected '=' after '{name}', found {eq.show() if eq else 'end of line'}", eq)
        value = cur.number("a number")
        if cur.peek() is not None:
            raise cur.error(f"unexpected {cur.peek().show()} after the value of '{name}'; expected end of line", cur.peek())
        self._unique(self.reals, name, line, col, "real variable")
        self.reals[name] = ast.RealDef(name, value, line)

    def finish(self, n_lines: int) -> ast.AsFile:
        if self.section is not None:
            what = f"'.PROGRAM {self.program_name}'" if self.section == "PROGRAM" else f"'.{self.section}'"
            raise self.error(n_lines, 1, f"end of file inside {what} opened at line {self.section_line}; expected '.END'")
        return ast.AsFile(self.source, tuple(self.programs), self.trans, self.joints, self.reals,
                          tuple(self.skipped), n_lines)


def split_lines(text: str) -> list[str]:
    """Lines of ``text`` for any of the \\n, \\r\\n and \\r conventions."""
    lines = text.replace("\r\n", "\n").replace("\r", "\n").split("\n")
    if lines and lines[-1] == "":
        lines.pop()
    return lines


def parse_as(text: str, source: str = "<program>") -> ast.AsFile:
    """Parse AS program text; raises AsSyntaxError (an InputError) naming line and column."""
    reader = _Reader(source)
    lines = split_lines(text)
    for number, line in enumerate(lines, start=1):
        reader.feed(number, line)
    return reader.finish(max(1, len(lines)))


def parse_as_bytes(data: bytes, source: str = "<program>") -> ast.AsFile:
    """Parse AS program bytes; non-ASCII bytes are accepted in comments only."""
    return parse_as(data.decode("latin-1"), source)
