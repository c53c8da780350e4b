"""Tokens and expressions of Fanuc TP instructions.

Names are case-insensitive (held upper case); ``R[n:comment]`` style comments after a colon inside
brackets are dropped. An expression is a number, ``ON``/``OFF``, a register ``R[i]`` (``i`` itself
an expression: ``R[R[1]]``), an argument ``AR[i]``, a position register element ``PR[i,j]``, a
signal (``DI[i]``, ``DO[i]``, ``RI``, ``RO``, ``F``, ``UI``, ``UO``, ``SI``, ``SO``, ``GI``, ``GO``,
``AI``, ``AO``), a system variable ``$NAME``, a call of a function of mixed logic (``SQRT(x)``…),
combined with ``+ - * / MOD DIV``, comparisons ``= <> < > <= >=``, ``AND OR`` and ``!`` (not),
with parentheses.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Optional

from coatsim.core.errors import InputError

_TOKEN = re.compile(r"""\s*(?:
    (?P<num>(?:\d+\.?\d*|\.\d+)(?:E[-+]?\d+)?)
  | (?P<str>'[^']*'|"[^"]*")
  | (?P<name>\$?[A-Z_][A-Z0-9_.$]*)
  | (?P<op><>|<=|>=|[-+*/=<>()\[\],:!%])
  )""", re.X)
SIGNALS = ("DI", "DO", "RI", "RO", "F", "UI", "UO", "SI", "SO", "GI", "GO", "AI", "AO", "WI", "WO", "M")
FUNCTIONS = ("SQRT", "SIN", "COS", "TAN", "ASIN", "ACOS", "ATAN", "ATAN2", "LN", "EXP", "ABS", "TRUNC", "ROUND")
_COMPARE = ("=", "<>", "<", ">", "<=", ">=")

# Expression nodes: ("num", v) | ("reg", kind, index[, element]) | ("sys", name) | ("not", e) | ("neg", e)
# | ("bin", op, a, b) | ("fn", name, args)
Expr = tuple


@dataclass(frozen=True)
class Token:
    kind: str  # num, str, name, op
    text: str


def tokenize(text: str, where: str) -> list[Token]:
    """Tokens of an instruction (upper case outside strings)."""
    out, i, upper = [], 0, text.upper()
    while i < len(text):
        match = _TOKEN.match(upper, i)
        if match is None or match.end() == i:
            if not upper[i:].strip():
                break
            raise InputError(f"{where}: unexpected {text[i:].strip()[:1]!r} in {text.strip()[:40]!r}")
        kind = match.lastgroup
        value = match.group(kind)
        if kind == "str":
            value = text[match.start(kind):match.end(kind)]
        out.append(Token(kind, value))
        i = match.end()
    return out


class Tokens:
    """A cursor over an instruction's tokens with the expression grammar."""

    def __init__(self, tokens: list[Token], where: str) -> None:
        self.t, self.i, self.where = tokens, 0, where

    def error(self, message: str) -> InputError:
        return InputError(f"{self.where}: {message}")

    def peek(self, offset: int = 0) -> Optional[Token]:
        k = self.i + offset
        return self.t[k] if k < len(self.t) else None

    def at(self, *texts: str) -> bool:
        tok = self.peek()
        return tok is not None and tok.text in texts

    def take(self, *texts: str) -> Optional[Token]:
        if self.at(*texts):
            self.i += 1
            return self.t[self.i - 1]
        return None

    def expect(self, text: str) -> Token:
        tok = self.take(text)
        if tok is None:
            found = self.peek()
            raise self.error(f"expected {text!r}, found {found.text if found else 'the end of the instruction'!r}")
        return tok

    def name(self) -> str:
        tok = self.peek()
        if tok is None or tok.kind != "name":
            raise self.error(f"expected a name, found {tok.text if tok else 'the end of the instruction'!r}")
        self.i += 1
        return tok.text

    def done(self) -> bool:
        return self.i >= len(self.t)

    def rest(self) -> str:
        return " ".join(tok.text for tok in self.t[self.i:])

    def close_bracket(self) -> None:
        """``]`` after an index, skipping a ``:comment``."""
        if self.take(":"):
            while not self.at("]"):
                if self.done():
                    raise self.error("a bracket is not closed")
                self.i += 1
        self.expect("]")

    def index(self) -> Expr:
        """``[i]`` (the opening bracket taken here)."""
        self.expect("[")
        value = self.expression()
        self.close_bracket()
        return value

    def register(self, kind: str) -> Expr:
        """``R[i]``, ``PR[i]``, ``PR[i,j]``, ``DO[i]`` … after its name."""
        self.expect("[")
        first = self.expression()
        if kind == "PR" and self.take(","):
            second = self.expression()
            self.close_bracket()
            return ("reg", kind, first, second)
        self.close_bracket()
        return ("reg", kind, first)

    # expression grammar, loosest first: OR, AND, comparison, + -, * / MOD DIV, unary, atom
    def expression(self) -> Expr:
        left = self._and()
        while self.take("OR"):
            left = ("bin", "OR", left, self._and())
        return left

    def _and(self) -> Expr:
        left = self._compare()
        while self.take("AND"):
            left = ("bin", "AND", left, self._compare())
        return left

    def _compare(self) -> Expr:
        left = self._sum()
        op = self.take(*_COMPARE)
        return ("bin", op.text, left, self._sum()) if op else left

    def _sum(self) -> Expr:
        left = self._product()
        while self.at("+", "-"):
            op = self.take("+", "-").text
            left = ("bin", op, left, self._product())
        return left

    def _product(self) -> Expr:
        left = self._unary()
        while self.at("*", "/", "MOD", "DIV"):
            op = self.take("*", "/", "MOD", "DIV").text
            left = ("bin", op, left, self._unary())
        return left

    def _unary(self) -> Expr:
        if self.take("-"):
            return ("neg", self._unary())
        if self.take("+"):
            return self._unary()
        if self.take("!"):
            return ("not", self._unary())
        return self._atom()

    def _atom(self) -> Expr:
        tok = self.peek()
        if tok is None:
            raise self.error("an expression is missing")
        if tok.kind == "num":
            self.i += 1
            return ("num", float(tok.text))
        if self.take("("):
            inner = self.expression()
            self.expect(")")
            return inner
        if tok.kind != "name":
            raise self.error(f"unexpected {tok.text!r} in an expression")
        self.i += 1
        word = tok.text
        if word in ("ON", "TRUE"):
            return ("num", 1.0)
        if word in ("OFF", "FALSE"):
            return ("num", 0.0)
        if word.startswith("$"):
            return ("sys", word)
        if word in ("R", "AR", "PR", *SIGNALS) and self.at("["):
            return self.register(word)
        if word in FUNCTIONS and self.at("("):
            self.expect("(")
            args = [self.expression()]
            while self.take(","):
                args.append(self.expression())
            self.expect(")")
            return ("fn", word, tuple(args))
        raise self.error(f"{word!r} is not a value this reader knows")
