"""Tokens of one AS source line.

``;`` starts a comment outside strings. Names hold letters, digits, ``_`` and ``.``; a prefix
marks the kind: ``.`` a local variable, ``$`` a string, ``#`` a joint value, ``&`` (or ``.&``)
a by-reference argument. Numbers are decimal (``125.``, ``.5``, ``1e3``) or ``^H``/``^B``
hexadecimal and binary. Keywords are case-insensitive. Any character that cannot start a token
is a syntax error naming its line and column.
"""

from __future__ import annotations

import math
import re

from coatsim.languages.kawasaki_as.source import AsSyntaxError, syntax_error

# Largest magnitude of a numeric literal (a 32-bit mask fits; a coordinate of 1e15 mm does not
# fit any cell, and the interpreter checks poses on its own).
MAX_LITERAL = 1e15

_TOKEN = re.compile(
    r"""
    (?P<ws>[ \t\f\v]+)
    |(?P<hex>\^[Hh][0-9A-Fa-f]+|\^[Bb][01]+)
    |(?P<num>(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)
    |(?P<name>(?:\.&|&|\.)?[$\#]?[A-Za-z_][A-Za-z0-9_.]*)
    |(?P<str>"[^"]*")
    |(?P<op>==|<>|<=|>=|=<|=>|[-+*/^()\[\],=<>:\#%@])
    """,
    re.VERBOSE,
)
# Relational operators AS also accepts the other way round.
_SPELLED = {"=<": "<=", "=>": ">="}
_SCAN = re.compile(_TOKEN.pattern + r"|(?P<comment>;.*)|(?P<bad>.)", re.VERBOSE | re.DOTALL)


class Token:
    """``kind`` is "num", "str", "name" or "op"; ``col`` is 1-based; ``value`` the number or
    the string's text; ``upper`` the upper-case text (keywords compare with it)."""

    __slots__ = ("kind", "text", "col", "value", "upper")

    def __init__(self, kind: str, text: str, col: int, value: float | str | None = None) -> None:
        self.kind, self.text, self.col, self.value = kind, text, col, value
        self.upper = text.upper()

    def show(self) -> str:
        return repr(self.text)

    def __repr__(self) -> str:
        return f"Token({self.kind}, {self.text!r}, {self.col})"


def tokenize(text: str, source: str, line: int) -> list[Token]:
    """Tokens of ``text`` up to a comment; raises AsSyntaxError on a stray character."""
    tokens: list[Token] = []
    append = tokens.append
    for m in _SCAN.finditer(text):
        kind = m.lastgroup
        if kind == "ws":
            continue
        pos = m.start()
        if kind == "name":
            append(Token(kind, m.group(), pos + 1))
        elif kind == "op":
            append(Token(kind, _SPELLED.get(m.group(), m.group()), pos + 1))
        elif kind == "num" or kind == "hex":
            word = m.group()
            append(Token("num", word, pos + 1, _number(word, source, line, pos)))
        elif kind == "str":
            word = m.group()
            append(Token("str", word, pos + 1, word[1:-1]))
        elif kind == "comment":
            break
        else:
            raise _stray(text, pos, source, line)
    return tokens


def _number(word: str, source: str, line: int, pos: int) -> float:
    if word.startswith("^"):
        value = float(int(word[2:], 16 if word[1] in "Hh" else 2))
    else:
        value = float(word)
    if not (math.isfinite(value) and abs(value) <= MAX_LITERAL):
        raise syntax_error(source, line, pos + 1, f"number {word} is out of range (|x| <= {MAX_LITERAL:g})")
    return value


def _stray(text: str, pos: int, source: str, line: int) -> AsSyntaxError:
    ch = text[pos]
    if ch == '"':
        return syntax_error(source, line, pos + 1, "string is not closed; expected '\"' before the end of the line")
    if ch == "^":
        return syntax_error(source, line, pos + 1, "expected ^H (hexadecimal) or ^B (binary) digits after '^'")
    if ch == "&":
        return syntax_error(source, line, pos + 1, "expected a variable name after '&'")
    if not ch.isascii() or not ch.isprintable():
        return syntax_error(source, line, pos + 1, f"unexpected character {ch!r}; only comments and strings may hold it")
    return syntax_error(source, line, pos + 1, f"unexpected character {ch!r}")
