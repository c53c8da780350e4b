"""Tokens of one AS source line.

``;`` starts a comment outside strings. Names may contain letters, digits, '_' and '.', and a
local variable starts with '.'. Any character that cannot start a token is a syntax error
naming its line and column.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from typing import Optional

from coatsim.errors import InputError

# Largest magnitude a number may have: 1e9 mm or degrees is beyond any cell.
MAX_ABS_NUMBER = 1e9

_TOKEN = re.compile(
    r"""
    (?P<ws>[ \t]+)
    |(?P<num>(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)
    |(?P<name>\.?[A-Za-z_][A-Za-z0-9_.]*)
    |(?P<str>"[^"]*")
    |(?P<punct>[()\[\],=+\-*/#$:%<>@])
    """,
    re.VERBOSE,
)


class AsSyntaxError(InputError):
    """An AS program text does not parse; the message is ``source:line:col: ...``."""


def syntax_error(source: str, line: int, col: int, message: str) -> AsSyntaxError:
    return AsSyntaxError(f"{source}:{line}:{col}: {message}")


@dataclass(frozen=True)
class Token:
    """``kind`` is "num", "name", "str" or "punct"; ``col`` is 1-based."""

    kind: str
    text: str
    col: int

    @property
    def upper(self) -> str:
        return self.text.upper()

    def show(self) -> str:
        return repr(self.text)


def tokenize(text: str, source: str, line: int) -> list[Token]:
    """Tokens of ``text`` up to a comment; raises AsSyntaxError on a stray character."""
    tokens: list[Token] = []
    pos = 0
    while pos < len(text):
        if text[pos] == ";":
            break
        m = _TOKEN.match(text, pos)
        if m is None:
            if text[pos] == '"':
                raise syntax_error(source, line, pos + 1, "string is not closed; expected '\"' before the end of the line")
            raise syntax_error(source, line, pos + 1, f"unexpected character {text[pos]!r}")
        kind = m.lastgroup or ""
        if kind == "num":
            value = float(m.group())
            if not (math.isfinite(value) and abs(value) <= MAX_ABS_NUMBER):
                raise syntax_error(source, line, pos + 1, f"number {m.group()} is out of range (|x| <= {MAX_ABS_NUMBER:g})")
        if kind != "ws":
            tokens.append(Token(kind, m.group(), pos + 1))
        pos = m.end()
    return tokens


class Cursor:
    """Token cursor over the tokens of one line; errors name the line and column."""

    def __init__(self, tokens: list[Token], source: str, line: int, width: int) -> None:
        self.tokens, self.source, self.line, self.width, self.pos = tokens, source, line, width, 0

    def error(self, message: str, token: Optional[Token] = None) -> AsSyntaxError:
        col = token.col if token is not None else self.width + 1
        return syntax_error(self.source, self.line, col, message)

    def peek(self) -> Optional[Token]:
        return self.tokens[self.pos] if self.pos < len(self.tokens) else None

    def take(self) -> Optional[Token]:
        tok = self.peek()
        self.pos += tok is not None
        return tok

    def number(self, what: str) -> float:
        tok = self.take()
        sign = 1.0
        if tok is not None and tok.kind == "punct" and tok.text in "+-":
            sign = -1.0 if tok.text == "-" else 1.0
            tok = self.take()
        if tok is None or tok.kind != "num":
            raise self.error(f"expected {what}, found {tok.show() if tok else 'end of line'}", tok)
        return sign * float(tok.text)

    def index(self) -> str:
        tok = self.take()
        if tok is None or tok.kind != "num" or not tok.text.isdigit():
            raise self.error(f"expected an array index (a whole number), found {tok.show() if tok else 'end of line'}", tok)
        return str(int(tok.text))

    def name(self, what: str, joint: bool = False) -> str:
        """A variable name with an optional [i] or [i, j] index."""
        tok = self.take()
        prefix = ""
        if joint:
            if tok is None or tok.text != "#":
                raise self.error(f"expected {what} starting with '#', found {tok.show() if tok else 'end of line'}", tok)
            prefix, tok = "#", self.take()
        if tok is None or tok.kind != "name":
            raise self.error(f"expected {what}, found {tok.show() if tok else 'end of line'}", tok)
        text = prefix + tok.text
        nxt = self.peek()
        if nxt is not None and nxt.text == "[":
            self.take()
            indices = [self.index()]
            while self.peek() is not None and self.peek().text == ",":
                self.take()
                indices.append(self.index())
            close = self.take()
            if close is None or close.text != "]":
                raise self.error(f"expected ']' after the array index, found {close.show() if close else 'end of line'}", close)
            text += "[" + ",".join(indices) + "]"
        return text
