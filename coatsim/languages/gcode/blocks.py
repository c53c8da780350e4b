"""G-code text -> blocks of words, as RS274/NGC reads a line.

A line is a block: an optional block-delete ``/``, an optional ``N`` line number, words (a letter
and a value), parameter settings ``#n=value`` / ``#<name>=value``, and comments ``( ... )`` or
``;`` to the end of the line. Letters are case-insensitive, spaces and tabs between characters
are ignored (``G1X10 y 2`` is ``G1 X10 Y2``). A value is a number (``10``, ``-.5``, ``3.``), a
parameter ``#5221`` / ``#<name>`` or an expression in brackets with LinuxCNC's operators and
functions. ``%`` lines delimit the program; an ``O`` number alone is the program number (of a
subprogram after the main one); O-word and macro flow statements are read as :mod:`.flow`
says. Values are parsed here and evaluated when the block runs
(parameters change as the program runs).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, replace
from typing import Optional, Union

from coatsim.core.errors import InputError
from coatsim.languages.gcode.flow import Flow, parse_flow

# An expression: ("num", v) | ("par", index_expr | name) | ("neg", e) | ("bin", op, a, b) | ("fn", name, a[, b])
Expr = tuple
_CONTROL = re.compile(r"[\x00-\x08\x0a-\x1f\x7f]")  # a tab is text; a line holds no other control character
_NUMBER = re.compile(r"[0-9]+\.?[0-9]*|\.[0-9]+")
_FUNCTIONS = ("ABS", "ACOS", "ASIN", "ATAN", "COS", "EXISTS", "EXP", "FIX", "FUP", "LN", "ROUND", "SIN", "SQRT",
              "TAN")
# binary operators by precedence, loosest first (RS274/NGC: logic < comparison < +- < */MOD < **)
_LEVELS = (("AND", "OR", "XOR"), ("EQ", "NE", "GT", "GE", "LT", "LE"), ("+", "-"), ("*", "/", "MOD"), ("**",))

@dataclass(frozen=True)
class Block:
    """One line: its words in order (letter, value expression), its parameter settings (target
    number expression or name, value), its comments, the program number an ``O`` line gives."""

    line: int
    words: tuple[tuple[str, Expr], ...]
    settings: tuple[tuple[Union[Expr, str], Expr], ...]
    comments: tuple[str, ...]
    program_number: Optional[int] = None
    flow: Optional[Flow] = None


class _Reader:
    """Reads one line's code (comments removed, spaces dropped, upper case)."""

    def __init__(self, code: str, where: str) -> None:
        self.s, self.i, self.where = code, 0, where

    def error(self, message: str) -> InputError:
        return InputError(f"{self.where}: {message}")

    def peek(self, text: str) -> bool:
        return self.s.startswith(text, self.i)

    def take(self, text: str) -> bool:
        if self.peek(text):
            self.i += len(text)
            return True
        return False

    def expect(self, text: str) -> None:
        if not self.take(text):
            raise self.error(f"expected {text!r} at column {self.i + 1}")

    def value(self) -> Expr:
        """A word's value: a signed number, a parameter or a bracketed expression."""
        if self.take("-"):
            return ("neg", self.value())
        if self.take("+"):
            return self.value()
        if self.take("["):
            inner = self.expression()
            self.expect("]")
            return inner
        if self.peek("#"):
            return self.parameter()
        for name in _FUNCTIONS:
            if self.peek(name + "["):
                return self.function(name)
        match = _NUMBER.match(self.s, self.i)
        if match is None:
            raise self.error(f"expected a number at column {self.i + 1}")
        self.i = match.end()
        return ("num", float(match.group()))

    def parameter(self) -> Expr:
        self.expect("#")
        if self.take("<"):
            end = self.s.find(">", self.i)
            if end < 0:
                raise self.error("a named parameter #<name> lacks its '>'")
            name, self.i = self.s[self.i:end], end + 1
            if not name:
                raise self.error("a named parameter needs a name")
            return ("par", name)
        return ("par", self.value())

    def function(self, name: str) -> Expr:
        self.i += len(name)
        self.expect("[")
        if name == "EXISTS":
            arg = self.parameter()
            self.expect("]")
            return ("fn", name, arg)
        arg = self.expression()
        self.expect("]")
        if name == "ATAN":  # ATAN[y]/[x]
            self.expect("/[")
            second = self.expression()
            self.expect("]")
            return ("fn", name, arg, second)
        return ("fn", name, arg)

    def expression(self, level: int = 0) -> Expr:
        if level == len(_LEVELS):
            return self.value()
        left = self.expression(level + 1)
        while True:
            op = next((op for op in _LEVELS[level] if self.peek(op) and not (op == "*" and self.peek("**"))), None)
            if op is None:
                return left
            self.i += len(op)
            left = ("bin", op, left, self.expression(level + 1))


def _split_comments(text: str, where: str) -> tuple[str, list[str]]:
    """The code of a line (comments removed) and its comments."""
    code, comments, i = [], [], 0
    while i < len(text):
        ch = text[i]
        if ch == "(":
            end = text.find(")", i)
            if end < 0:
                raise InputError(f"{where}: a comment '(' is not closed on its line")
            comments.append(text[i + 1:end])
            i = end + 1
        elif ch == ";":
            comments.append(text[i + 1:])
            break
        else:
            code.append(ch)
            i += 1
    return "".join(code), comments


def parse_block(text: str, line: int, where: str) -> Optional[Block]:
    """The block of one line (None for an empty line or a ``%``)."""
    if _CONTROL.search(text):
        raise InputError(f"{where}: a control character in the line; G-code is plain text")
    code, comments = _split_comments(text, where)
    code = re.sub(r"[ \t]+", "", code).upper()
    if code.startswith("/"):
        code = code[1:]  # block delete: run (the switch is off, as a control starts)
    if code in ("", "%"):
        return Block(line, (), (), tuple(comments)) if comments else None
    number = re.match(r"N[0-9]+", code)
    flow_code = code[number.end():] if number else code
    flow, rest = parse_flow(flow_code, _Reader(flow_code, where))
    if flow is not None:
        label = (("N", ("num", float(number.group()[1:]))),) if number else ()
        block = _words(rest, line, where, comments) if rest else Block(line, (), (), tuple(comments))
        return replace(block, words=label + block.words, flow=flow)
    reader = _Reader(code, where)
    if reader.peek("O"):
        return _program_number(reader, line, tuple(comments))
    return _words(code, line, where, comments)


def _words(code: str, line: int, where: str, comments: list[str]) -> Block:
    """The block of a line's words and parameter settings."""
    reader = _Reader(code, where)
    words: list[tuple[str, Expr]] = []
    settings: list[tuple[Union[Expr, str], Expr]] = []
    while reader.i < len(code):
        ch = code[reader.i]
        if ch == "#":
            target = reader.parameter()[1]
            reader.expect("=")
            settings.append((target, reader.expression()))  # a Fanuc macro writes #1=#2+1 unbracketed
        elif "A" <= ch <= "Z":
            reader.i += 1
            words.append((ch, reader.value()))
        else:
            raise reader.error(f"unexpected {ch!r} at column {reader.i + 1}; a word is a letter and a number")
    return Block(line, tuple(words), tuple(settings), tuple(comments))


def _program_number(reader: _Reader, line: int, comments: tuple[str, ...]) -> Block:
    reader.expect("O")
    match = re.match(r"(<[^>]*>|[0-9]+)(.*)\Z", reader.s[reader.i:])
    rest = match.group(2) if match else ""
    if match is None or rest:
        raise reader.error("an O word is a program number (O1234) or an O-word statement (o100 sub, call, while, "
                           "if, repeat ...)")
    if not match.group(1).isdigit():
        raise reader.error("an O number names the program: O followed by digits")
    return Block(line, (), (), comments, program_number=int(match.group(1)))


def parse_blocks(text: str, source: str) -> tuple[Block, ...]:
    """Every block of a program text (lines counted from 1)."""
    blocks = []
    for number, raw in enumerate(text.splitlines(), start=1):
        block = parse_block(raw, number, f"{source}:{number}")
        if block is not None:
            blocks.append(block)
    return tuple(blocks)
