"""Kawasaki AS reader: file text -> :class:`~coatsim.languages.kawasaki_as.ast.AsFile`.

Reads every ``.PROGRAM`` / ``.END`` block (several per file), ``.TRANS``, ``.JOINTS``,
``.REALS`` and ``.STRINGS``; keeps every other section as raw lines: a section whose header
line holds nothing else runs to its ``.END`` (``.AUXDATA``, ``.SYSDATA``, ``.ROBOTDATA1``,
``.INTER_PANEL_*``, ``.SIG_COMMENT``, unknown ones), one with text on its header line
(``.NETCONF 192.168.0.2,...``, ``.LANGUAGE ENGLISH``) ends there unless an ``.END`` follows
its content. ``.*`` lines are comments; leading blanks before ``.END`` are allowed. Every
defect is an :class:`AsSyntaxError` naming line, column and what was expected.
"""

from __future__ import annotations

import re
from typing import Optional

from coatsim.languages.kawasaki_as import ast
from coatsim.languages.kawasaki_as.blocks import BlockBuilder
from coatsim.languages.kawasaki_as.expressions import Cursor
from coatsim.languages.kawasaki_as.lexer import MAX_LITERAL, tokenize
from coatsim.core.fileio import decode_text as decode
from coatsim.languages.kawasaki_as.source import AsSyntaxError, split_lines, syntax_error
from coatsim.languages.kawasaki_as.statements import parse_line

_DIRECTIVE = re.compile(r"\.([A-Za-z_][A-Za-z0-9_]*)")
_PROGRAM_NAME = re.compile(r"[ \t]+([A-Za-z][A-Za-z0-9_.]*)")
_METADATA = re.compile(r"[ \t]*(?:\d+[ \t]+)?;[ \t]*coatsim:[ \t]*([A-Za-z0-9_.]+)[ \t]*=(.*)$")
_DATA = ("TRANS", "JOINTS", "REALS", "STRINGS")
_SIMPLE_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_.]*(\[\d+(,\d+)?\])?\Z")


def _without_array_brackets(tokens: list) -> list:
    """The tokens of a parameter list without the ``[]`` / ``[,]`` that mark a parameter
    receiving a whole array (``.PROGRAM trace(.&rel[,], .n)``); any other bracket is kept (and
    rejected as a parameter)."""
    out, i = [], 0
    while i < len(tokens):
        tok = tokens[i]
        if tok.kind == "op" and tok.text == "[" and out and out[-1].kind == "name":
            j = i + 1
            while j < len(tokens) and tokens[j].kind == "op" and tokens[j].text == ",":
                j += 1
            if j < len(tokens) and tokens[j].kind == "op" and tokens[j].text == "]":
                i = j + 1
                continue
        out.append(tok)
        i += 1
    return out


def _is_end(stripped: str) -> bool:
    return stripped[:4].upper() == ".END" and (len(stripped) == 4 or stripped[4] in " \t;")


def key(name: str) -> str:
    """How a variable is looked up: lower case, array indices without blanks."""
    return name.lower().replace(" ", "")


class _Reader:
    """Line-by-line state machine over the sections of a file."""

    def __init__(self, source: str) -> None:
        self.source = source
        self.programs: list[ast.Program] = []
        self.names: dict[str, int] = {}
        self.data: dict[str, dict] = {kind: {} for kind in _DATA}
        self.sections: list[ast.RawSection] = []
        self.section: Optional[str] = None  # PROGRAM, a data section, or RAW
        self.raw_name, self.raw_open_ended, self.raw_lines = "", False, []
        self.section_line = 0
        self.header: tuple[str, tuple[ast.Param, ...]] = ("", ())
        self.blocks: Optional[BlockBuilder] = None
        self.metadata: list[tuple[str, str]] = []

    def error(self, line: int, col: int, message: str) -> AsSyntaxError:
        return syntax_error(self.source, line, col, message)

    def feed(self, line: int, text: str) -> None:
        stripped = text.lstrip(" \t")
        col = len(text) - len(stripped) + 1
        if self.section == "RAW":
            if _is_end(stripped):
                self._close_raw()
                return
            if not (self.raw_open_ended and _DIRECTIVE.match(stripped)):
                self.raw_lines.append(text)
                return
            self._close_raw()
        if _is_end(stripped):
            self._end(line, col, stripped)
        elif self.section == "PROGRAM":
            self._program_line(line, text, stripped, col)
        elif self.section is not None:
            self._data_line(line, text)
        elif stripped.startswith(".*"):
            return
        elif stripped.startswith("."):
            self._directive(line, stripped, col)
        elif stripped and not stripped.startswith(";"):
            raise self.error(line, col, "statement outside a section; expected a dot-section such as '.PROGRAM name()'")

    def _close_raw(self) -> None:
        self.sections.append(ast.RawSection(self.raw_name, self.section_line, tuple(self.raw_lines)))
        self.section, self.raw_lines = None, []

    def _end(self, line: int, col: int, stripped: str) -> None:
        if self.section is None:
            raise self.error(line, col, "'.END' without an open section")
        if tokenize(stripped[4:], self.source, line):
            raise self.error(line, col + 4, "unexpected text after '.END'; expected end of line")
        if self.section == "PROGRAM":
            name, params = self.header
            body = self.blocks.finish(line)
            self.programs.append(ast.Program(name, params, self.section_line, body, tuple(self.metadata),
                                             self.source, line))
        self.section = None

    def _directive(self, line: int, stripped: str, col: int) -> None:
        m = _DIRECTIVE.match(stripped)
        if m is None:
            raise self.error(line, col, "expected a section name such as '.PROGRAM', '.TRANS' or '.END'")
        word = m.group(1).upper()
        self.section_line = line
        rest = stripped[m.end():]
        if word == "PROGRAM":
            self._program_header(line, col + m.end(), rest)
        elif word in _DATA:
            if tokenize(rest, self.source, line):
                raise self.error(line, col + m.end(), f"unexpected text after '.{word}'; expected end of line")
            self.section = word
        else:
            self.section, self.raw_name, self.raw_lines = "RAW", word, []
            self.raw_open_ended = bool(rest.split(";", 1)[0].strip())

    def _program_header(self, line: int, col: int, rest: str) -> None:
        m = _PROGRAM_NAME.match(rest)
        if m is None:
            raise self.error(line, col + 1, "expected a program name after '.PROGRAM', as in '.PROGRAM name()'")
        name = m.group(1)
        after = rest[m.end():]
        if after[:1] not in ("", " ", "\t", "(", "@", "#", ";"):
            raise self.error(line, col + m.end(), f"program name '{name}' is followed by {after[:1]!r}; "
                             "a name has letters, digits, '.' and '_' only")
        if name.lower() in self.names:
            raise self.error(line, 1, f"program '{name}' is defined twice (first at line {self.names[name.lower()]})")
        self.names[name.lower()] = line
        params: tuple[ast.Param, ...] = ()
        if after.lstrip(" \t").startswith("("):
            params = self._params(line, col + m.end() + len(after) - len(after.lstrip(" \t")), after.lstrip(" \t"))
        self.section, self.header = "PROGRAM", (name, params)
        self.blocks, self.metadata = BlockBuilder(self.source, name), []

    def _params(self, line: int, col: int, text: str) -> tuple[ast.Param, ...]:
        close = text.find(")")
        if close < 0:
            raise self.error(line, col, "expected ')' to close the parameter list")
        tokens = _without_array_brackets(tokenize(" " * (col - 1) + text[1:close], self.source, line))
        params, expect_name = [], True
        for tok in tokens:
            if expect_name:
                if tok.kind != "name":
                    raise self.error(line, tok.col, f"expected a parameter name, found {tok.show()}")
                by_ref = tok.text.startswith("&") or tok.text.startswith(".&")
                bare = tok.text.lstrip(".&")
                params.append(ast.Param("." + bare, by_ref))
            elif tok.text != ",":
                raise self.error(line, tok.col, f"expected ',' between parameters, found {tok.show()}")
            expect_name = not expect_name
        if tokens and expect_name:
            raise self.error(line, col + close, "expected a parameter name after ','")
        return tuple(params)

    def _program_line(self, line: int, text: str, stripped: str, col: int) -> None:
        if stripped[:8].upper() == ".PROGRAM":
            raise self.error(line, col, f"'.PROGRAM' inside program '{self.header[0]}' (line {self.section_line}); "
                             "expected '.END' first")
        if stripped.startswith(".*"):
            return
        meta = _METADATA.match(text)
        if meta is not None:
            self.metadata.append((meta.group(1), meta.group(2).strip()))
            return
        tokens = tokenize(text, self.source, line)
        if tokens:
            for item in parse_line(tokens, self.source, line, text):
                self.blocks.add(item)

    # --- data sections -------------------------------------------------------------------
    def _data_line(self, line: int, text: str) -> None:
        if self.section == "TRANS" and ";" not in text and self._fast_trans(text, line):
            return
        tokens = tokenize(text, self.source, line)
        if not tokens:
            return
        c = Cursor(tokens, self.source, line, len(text))
        {"TRANS": self._trans, "JOINTS": self._joint, "REALS": self._real, "STRINGS": self._string}[self.section](c, line)

    def _name(self, c: Cursor, what: str, prefix: str = "") -> tuple[str, int]:
        tok = c.peek()
        if tok is None or tok.kind != "name" or not tok.text.startswith(prefix) or tok.text[len(prefix):][:1] in ("", "$", "#", ".", "&"):
            raise c.error(f"expected {what}" + (f" starting with '{prefix}'" if prefix else "") + f", found {c.found(tok)}", tok)
        col = tok.col
        name = c.variable(c.take())
        if any(not isinstance(i, ast.Num) or i.value != int(i.value) or i.value < 0 for i in name.index):
            raise c.error(f"expected a whole-number array index in {name.name}[...]", tok)
        text = name.name + (f"[{','.join(str(int(i.value)) for i in name.index)}]" if name.index else "")
        return text, col

    def _numbers(self, c: Cursor, what: str, most: int, name: str) -> list[float]:
        values = []
        while not c.at_end():
            if values and c.is_op(","):
                c.take()
            if len(values) == most:
                raise c.error(f"too many numbers for {name}; expected at most {most}", c.peek())
            sign = -1.0 if c.is_op("-") else 1.0
            if c.is_op("-", "+"):
                c.take()
            tok = c.take()
            if tok is None or tok.kind != "num":
                raise c.error(f"expected {what}, found {c.found(tok)}", tok)
            values.append(sign * float(tok.value))
        return values

    def _store(self, kind: str, name: str, value, line: int, col: int, what: str) -> None:
        table = self.data[kind]
        k = key(name)
        if k in table:
            raise self.error(line, col, f"{what} '{name}' is defined twice (first at line {table[k].line})")
        table[k] = value

    def _fast_trans(self, text: str, line: int) -> bool:
        """The common ``name x y z o a t`` line without the tokenizer; False to take the slow path."""
        parts = text.replace(",", " ").split()
        if not 7 <= len(parts) <= 1 + ast.MAX_AXES or not _SIMPLE_NAME.match(parts[0]) or "_" in text.split(None, 1)[1]:
            return False
        try:
            values = [float(v) for v in parts[1:]]
        except ValueError:
            return False
        if not all(abs(v) <= MAX_LITERAL for v in values):  # (also rejects nan)
            return False
        name = parts[0]
        col = len(text) - len(text.lstrip(" \t")) + 1
        self._store("TRANS", name, ast.TransDef(name, tuple(values[:6]), tuple(values[6:]), line), line, col, "pose")
        return True

    def _trans(self, c: Cursor, line: int) -> None:
        name, col = self._name(c, "a pose name")
        values = self._numbers(c, "a number (x y z mm, o a t deg)", ast.MAX_AXES, f"pose '{name}'")
        if len(values) < 6:
            raise c.error(f"pose '{name}' has {len(values)} numbers; expected 6 (x y z o a t) and external axes")
        self._store("TRANS", name, ast.TransDef(name, tuple(values[:6]), tuple(values[6:]), line), line, col, "pose")

    def _joint(self, c: Cursor, line: int) -> None:
        name, col = self._name(c, "a joint pose name", "#")
        values = self._numbers(c, "a joint value", ast.MAX_AXES, f"joint pose '{name}'")
        if not values:
            raise c.error(f"joint pose '{name}' has no values")
        self._store("JOINTS", name, ast.JointDef(name, tuple(values), line), line, col, "joint pose")

    def _real(self, c: Cursor, line: int) -> None:
        name, col = self._name(c, "a real variable name")
        c.op("=", f"after '{name}'")
        values = self._numbers(c, "a number", 1, f"'{name}'")
        if not values:
            raise c.error(f"expected a number after '{name} ='")
        self._store("REALS", name, ast.RealDef(name, values[0], line), line, col, "real variable")

    def _string(self, c: Cursor, line: int) -> None:
        name, col = self._name(c, "a string variable name", "$")
        c.op("=", f"after '{name}'")
        tok = c.take()
        if tok is None or tok.kind != "str":
            raise c.error(f"expected a string in quotes after '{name} =', found {c.found(tok)}", tok)
        c.end(f"string '{name}'")
        self._store("STRINGS", name, ast.StringDef(name, str(tok.value), line), line, col, "string variable")

    def finish(self, n_lines: int) -> ast.AsFile:
        if self.section == "RAW" and self.raw_open_ended:
            self._close_raw()
        if self.section is not None:
            what = f"'.PROGRAM {self.header[0]}'" if self.section == "PROGRAM" else \
                f"'.{self.raw_name if self.section == 'RAW' else self.section}'"
            raise self.error(n_lines, 1, f"end of file inside {what} opened at line {self.section_line}; expected '.END'")
        d = self.data
        return ast.AsFile(self.source, tuple(self.programs), d["TRANS"], d["JOINTS"], d["REALS"], d["STRINGS"],
                          tuple(self.sections), n_lines)


def parse_as(text: str, source: str = "<program>") -> ast.AsFile:
    """Parse AS program text; raises AsSyntaxError (an InputError) naming line and column."""
    reader = _Reader(source)
    lines = split_lines(text)
    for number, line in enumerate(lines, start=1):
        reader.feed(number, line)
    return reader.finish(max(1, len(lines)))


def parse_as_bytes(data: bytes, source: str = "<program>") -> ast.AsFile:
    """Parse the bytes of an AS file (UTF-8 with or without BOM, or a Windows code page)."""
    return parse_as(decode(data), source)
