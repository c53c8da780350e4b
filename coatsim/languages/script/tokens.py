"""Tokens of a statement language, configured per language: its comment start, how names may
begin (KRL's ``$`` and ``#``), its operators. Newlines are tokens (KRL ends a statement at a
line end; RAPID at ``;`` and skips them)."""

from __future__ import annotations

import re
from dataclasses import dataclass

from coatsim.core.errors import InputError

NUM, STR, NAME, OP, NEWLINE, END = "num", "str", "name", "op", "newline", "end"


@dataclass(frozen=True)
class Token:
    kind: str
    text: str
    line: int


@dataclass(frozen=True)
class Syntax:
    """A language's lexical rules: ``comment`` the character starting a comment to the line end,
    ``name_start`` the characters a name may start with besides letters and '_', ``operators``
    its multi- and single-character operators (longest first), ``strings`` its string quotes."""

    comment: str
    name_start: str
    operators: tuple[str, ...]
    strings: str = '"'

    def pattern(self) -> re.Pattern:
        ops = "|".join(re.escape(o) for o in sorted(self.operators, key=len, reverse=True))
        start = re.escape(self.name_start)
        return re.compile(
            rf"(?P<ws>[ \t\f\v\x00]+)|(?P<nl>\r\n|\r|\n)|(?P<comment>{re.escape(self.comment)}[^\r\n]*)"
            rf"|(?P<num>(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)"
            rf"|(?P<name>[A-Za-z_{start}][A-Za-z0-9_{start}]*)"
            rf'|(?P<str>"[^"\r\n]*")|(?P<op>{ops})')


def tokenize(text: str, syntax: Syntax, source: str) -> list[Token]:
    """The tokens of ``text``; InputError naming ``source``:line at a character the language
    does not have."""
    pattern = syntax.pattern()
    out: list[Token] = []
    line, pos = 1, 0
    while pos < len(text):
        m = pattern.match(text, pos)
        if m is None:
            ch = text[pos]
            shown = repr(ch) if ch.isprintable() else f"U+{ord(ch):04X}"
            raise InputError(f"{source}:{line}: unexpected character {shown}")
        kind = m.lastgroup
        value = m.group()
        if kind == "nl":
            out.append(Token(NEWLINE, "\n", line))
            line += 1
        elif kind == "num":
            out.append(Token(NUM, value, line))
        elif kind == "name":
            out.append(Token(NAME, value, line))
        elif kind == "str":
            out.append(Token(STR, value[1:-1], line))
        elif kind == "op":
            out.append(Token(OP, value, line))
        pos = m.end()
    out.append(Token(NEWLINE, "\n", line))
    out.append(Token(END, "", line))
    return out
