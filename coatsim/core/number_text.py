"""Numbers in text tables as people write them, read exactly or refused.

A table is lines of fields: separated by semicolons, tabs, commas or spaces; ``#`` starts a
comment. Understood, each with a note the command prints once: a decimal comma (``1,5;2,5``,
``1,5<TAB>2,5`` or ``1,5 2,5``: a comma inside a field that a semicolon, a tab or a space
separates from the next), a Unicode minus or plus sign (U+2212 and the other dashes a word
processor puts for ``-``, fullwidth forms), a no-break or thin space between digit groups
(``1 000,5``), digits of other scripts. Anything else that is not a plain decimal number
(``1_000``, ``0x10``, ``1.2.3``, ``2mm``, a superscript) is refused with its line and field; a
file may not mix decimal commas and decimal points. The first line is a header only when none of
its fields is a number in any of these forms.
"""

from __future__ import annotations

import math
import re
import unicodedata
from dataclasses import dataclass, field

from coatsim.core.errors import InputError, shown

_MINUS = "\u2212\u2012\u2013\u2014\ufe63\uff0d\u2010\u2011"
_PLUS = "\uff0b\ufe62"
_GROUP_SPACE = "\u00a0\u202f\u2007\u2009"
_NUMBER = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?")
_COMMA_NUMBER = re.compile(r"[+-]?(?:\d+,\d*|,\d+)(?:[eE][+-]?\d+)?")
_GROUPED = re.compile(rf"(?<=\d)[{_GROUP_SPACE}](?=\d{{3}}(?:\D|$))")
_WORDS = {"nan", "+nan", "-nan", "inf", "+inf", "-inf", "infinity", "+infinity", "-infinity"}


@dataclass
class Rows:
    """Numeric rows of a table (each a list of floats) with their line numbers, the header's
    fields (empty when there is none) and notes on forms that were understood."""

    values: list[list[float]] = field(default_factory=list)
    lines: list[int] = field(default_factory=list)
    header: list[str] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)


def _normalised(line: str, notes: dict[str, str], number: int) -> str:
    """The line with Unicode signs, digit-group spaces and non-ASCII digits made ASCII."""
    if line.isascii():
        return line
    out = []
    grouped = _GROUPED.sub("", line)
    if grouped != line:
        notes.setdefault("group", f"line {number}: read a no-break or thin space between digits as a thousands "
                                  "separator")
    for ch in grouped:
        if ch in _MINUS:
            notes.setdefault("minus", f"line {number}: read U+{ord(ch):04X} ({unicodedata.name(ch, '?').lower()}) as a "
                                      "minus sign")
            out.append("-")
        elif ch in _PLUS:
            out.append("+")
        elif ch in _GROUP_SPACE:
            out.append(" ")
        elif not ch.isascii() and unicodedata.category(ch) == "Nd":
            notes.setdefault("digits", f"line {number}: read digits of another script ({unicodedata.name(ch, '?').lower()})")
            out.append(str(unicodedata.digit(ch)))
        else:
            out.append(ch)
    return "".join(out)


def _fields(line: str) -> tuple[list[str], bool]:
    """The fields of a normalised line and whether its commas are decimal marks."""
    if ";" in line:
        return _unquoted(line.split(";")), True
    if "\t" in line:
        return _unquoted(line.split("\t")), "," in line
    tokens = line.split()
    if "," not in line:
        return _unquoted(tokens), False
    if len(tokens) >= 2 and all(_COMMA_NUMBER.fullmatch(t) or _NUMBER.fullmatch(t) for t in tokens) \
            and not any("." in t for t in tokens):
        return tokens, True
    return _unquoted(line.split(",")), False


def _unquoted(parts: list[str]) -> list[str]:
    """Fields without surrounding blanks and double quotes; empty fields at the end of the line
    (a trailing separator) dropped."""
    fields = [p.strip() for p in parts]
    fields = [f[1:-1].strip() if len(f) >= 2 and f[0] == f[-1] == '"' else f for f in fields]
    while fields and not fields[-1]:
        fields.pop()
    return fields


def number(field: str, decimal_comma: bool) -> float | None:
    """A field's value, or None when it is not a plain decimal number."""
    text = field.replace(",", ".", 1) if decimal_comma and _COMMA_NUMBER.fullmatch(field) else field
    if _NUMBER.fullmatch(text) or text.lower() in _WORDS:
        return float(text)
    return None


def read_rows(text: str, source: str, expected: str) -> Rows:
    """The rows of a numeric table; InputError ``source:line: field k ...`` for a field that is
    not a number (``expected`` says what the columns hold, e.g. "x,y or x,y,z columns")."""
    rows = Rows()
    notes: dict[str, str] = {}
    marks: dict[str, int] = {}  # decimal mark -> first line using it
    for number_, raw in enumerate(text.splitlines(), start=1):
        line = _normalised(raw.split("#", 1)[0], notes, number_).strip()
        if not line:
            continue
        fields, comma = _fields(line)
        values = [number(f, comma) for f in fields]
        if not rows.values and not rows.header and all(v is None for v in values) and any(fields):
            rows.header = fields  # a header: no field is a number in any form
            continue
        bad = next((k for k, v in enumerate(values) if v is None), None)
        if bad is not None:
            raise InputError(f"{source}:{number_}: field {bad + 1} is not a number: {shown(fields[bad], names=True)} "
                             f"(expected {expected})")
        if not all(math.isfinite(v) for v in values):  # type: ignore[arg-type]
            raise InputError(f"{source}:{number_}: value is not finite (NaN or inf)")
        for f in fields:
            mark = "," if comma and "," in f else "." if "." in f else None
            if mark is not None:
                marks.setdefault(mark, number_)
        if len(marks) > 1:
            raise InputError(f"{source}:{number_}: decimal commas (line {marks[',']}) and decimal points (line "
                             f"{marks['.']}) in one file; write every number the same way")
        rows.values.append(values)  # type: ignore[arg-type]
        rows.lines.append(number_)
    if "," in marks:
        notes["comma"] = f"line {marks[',']}: read ',' as the decimal mark"
    rows.notes = [f"{source}: {note}" for note in notes.values()]
    return rows
