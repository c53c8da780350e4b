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

import codecs
import math
import re
import unicodedata
import warnings
from dataclasses import dataclass, field

import numpy as np

from coatsim.core.errors import InputError, shown

_MINUS = "\u2212\u2012\u2013\u2014\ufe63\uff0d\u2010\u2011"
_PLUS = "\uff0b\ufe62"
_GROUP_SPACE = "\u00a0\u202f\u2007\u2009"
_NUMBER = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?")
_COMMA_NUMBER = re.compile(r"[+-]?(?:\d+,\d*|,\d+)(?:[eE][+-]?\d+)?")
_GROUPED = re.compile(rf"(?<=\d)[{_GROUP_SPACE}](?=\d{{3}}(?:\D|$))")
_WORDS = {"nan", "+nan", "-nan", "inf", "+inf", "-inf", "infinity", "+infinity", "-infinity"}


_BREAKS = re.compile("\r\n?|[\x0b\x0c\x1c\x1d\x1e\x85\u2028\u2029]")  # str.splitlines' line ends
_COMMENT = re.compile(r"#[^\n]*")
_CONTENT = re.compile(r"(?m)^[^\S\n]*[^#\s]")  # the first character of the first line with content
_EDGES = re.compile(r"(?m)^[ \t]+|[ \t]+$")
_OTHER_DIGIT = re.compile(r"(?![0-9])\d")
_FAST_BYTES = np.zeros(256, bool)
_FAST_BYTES[np.frombuffer(b"0123456789+-.eE,;\t \n", np.uint8)] = True
CHUNK_CHARS = 1 << 20  # text read at once: a chunk with an odd line is read line by line


@dataclass(frozen=True, eq=False)
class Rows:
    """Numeric rows of a table: every number row after row (``flat``), the count in each row
    (``widths``) and its line number (``lines``); the header's fields (empty when there is
    none) and notes on forms that were understood."""

    flat: np.ndarray
    widths: np.ndarray
    lines: np.ndarray
    header: list[str]
    notes: list[str]

    @property
    def values(self) -> list[list[float]]:
        """The rows as lists of floats (small tables; large ones use ``columns``)."""
        return [row.tolist() for row in np.split(self.flat, np.cumsum(self.widths)[:-1])] if len(self.widths) else []

    def columns(self, index: list[int]) -> np.ndarray:
        """(n, len(index)) the given columns of every row (each row has more than max(index) values)."""
        if len(self.widths) and np.all(self.widths == self.widths[0]):
            return self.flat.reshape(len(self.widths), -1)[:, index]
        starts = np.cumsum(self.widths) - self.widths
        return self.flat[starts[:, None] + np.asarray(index, dtype=np.int64)[None, :]]


@dataclass
class _Reading:
    """What read_rows has found so far."""

    source: str
    expected: str
    header: list[str] = field(default_factory=list)
    notes: dict[str, str] = field(default_factory=dict)
    marks: dict[str, int] = field(default_factory=dict)  # decimal mark -> first line using it
    parts: list[tuple[np.ndarray, np.ndarray, np.ndarray]] = field(default_factory=list)

    @property
    def has_rows(self) -> bool:
        return any(len(widths) for _, widths, _ in self.parts)


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


def table_text(data: bytes) -> str:
    """The text of a table file: UTF-8 (a byte-order mark skipped), or UTF-16 or UTF-32 when a
    byte-order mark says so (spreadsheets save "Unicode text" that way); UnicodeDecodeError
    for anything else."""
    for bom, codec in ((codecs.BOM_UTF32_LE, "utf-32"), (codecs.BOM_UTF32_BE, "utf-32"),
                       (codecs.BOM_UTF16_LE, "utf-16"), (codecs.BOM_UTF16_BE, "utf-16")):
        if data.startswith(bom):
            return data.decode(codec)
    return data.decode("utf-8-sig")


def read_rows(text: str, source: str, expected: str) -> Rows:
    """The rows of a numeric table; InputError ``source:line: field k ...`` for a field that is
    not a number (``expected`` says what the columns hold, e.g. "x,y or x,y,z columns").

    Chunks of plain rows are read by numpy at once; a chunk with anything the fast reader does
    not prove equal to the line-by-line rules (a quote, a word, a separator that changes) is read
    line by line, so both give the same numbers, notes and errors."""
    if any(ch in text for ch in "\r\x0b\x0c\x1c\x1d\x1e\x85\u2028\u2029"):
        text = _BREAKS.sub("\n", text)
    reading = _Reading(source, expected)
    pos, number_ = _header(reading, text)
    while pos <= len(text):
        end = len(text) if len(text) - pos <= CHUNK_CHARS else text.find("\n", pos + CHUNK_CHARS)
        end = len(text) if end < 0 else end
        chunk = text[pos:end]
        if not _fast_chunk(reading, chunk, number_):
            _slow_lines(reading, chunk.split("\n"), number_)
        number_ += chunk.count("\n") + 1
        pos = end + 1
    if "," in reading.marks:
        reading.notes["comma"] = f"line {reading.marks[',']}: read ',' as the decimal mark"
    parts = reading.parts or [(np.zeros(0), np.zeros(0, np.int64), np.zeros(0, np.int64))]
    return Rows(flat=np.concatenate([p[0] for p in parts]), widths=np.concatenate([p[1] for p in parts]),
                lines=np.concatenate([p[2] for p in parts]), header=reading.header,
                notes=[f"{source}: {note}" for note in reading.notes.values()])


def _header(reading: _Reading, text: str) -> tuple[int, int]:
    """Take the first line with content as the header when none of its fields is a number;
    the offset and line number where the rows start."""
    found = _CONTENT.search(text)  # blank and comment lines skipped at the speed of re
    if found is None:
        return len(text) + 1, text.count("\n") + 2
    pos = text.rfind("\n", 0, found.start()) + 1
    number_ = 1 + text.count("\n", 0, pos)
    end = text.find("\n", pos)
    end = len(text) if end < 0 else end
    raw = text[pos:end].split("#", 1)[0]
    fields, comma = _fields(_normalised(raw, {}, number_).strip())
    if any(fields) and all(number(f, comma) is None for f in fields):
        _normalised(raw, reading.notes, number_)
        reading.header = fields
        return end + 1, number_ + 1
    return pos, number_


def _slow_lines(reading: _Reading, lines: list[str], first: int) -> None:
    """Read lines one by one (the rules of the module docstring)."""
    flat: list[float] = []
    widths: list[int] = []
    numbers: list[int] = []
    marks = reading.marks
    for number_, raw in enumerate(lines, start=first):
        line = _normalised(raw.split("#", 1)[0], reading.notes, number_).strip()
        if not line:
            continue
        fields, comma = _fields(line)
        values = [number(f, comma) for f in fields]
        bad = next((k for k, v in enumerate(values) if v is None), None)
        if bad is not None:
            raise InputError(f"{reading.source}:{number_}: field {bad + 1} is not a number: "
                             f"{shown(fields[bad], names=True)} (expected {reading.expected})")
        if not all(math.isfinite(v) for v in values):  # type: ignore[arg-type]
            raise InputError(f"{reading.source}:{number_}: value is not finite (NaN or inf)")
        for f in fields:
            mark = "," if comma and "," in f else "." if "." in f else None
            if mark is not None:
                marks.setdefault(mark, number_)
        if len(marks) > 1:
            raise InputError(f"{reading.source}:{number_}: decimal commas (line {marks[',']}) and decimal points "
                             f"(line {marks['.']}) in one file; write every number the same way")
        flat.extend(values)  # type: ignore[arg-type]
        widths.append(len(values))
        numbers.append(number_)
    reading.parts.append((np.asarray(flat, dtype=float), np.asarray(widths, dtype=np.int64),
                          np.asarray(numbers, dtype=np.int64)))


def _fast_chunk(reading: _Reading, chunk: str, first: int) -> bool:
    """Read a chunk of rows at numpy speed; False (nothing read) when any line of it needs the
    line-by-line reader: a character outside digits, signs, ``.eE`` and separators after the
    Unicode forms are made ASCII, a separator that is not the same on every line, an empty
    field, a field that is not a plain decimal number, a value that is not finite, a second
    decimal mark."""
    notes: dict[str, str] = {}
    body = _COMMENT.sub("", chunk) if "#" in chunk else chunk
    if not body.isascii():
        body = _normalised_text(body, notes, first)
        if not body.isascii():
            return False
    data = np.frombuffer(body.encode("ascii"), np.uint8)
    if not _FAST_BYTES[data].all():
        return False
    if (" " in body or "\t" in body) and _blank_line_edges(data):  # lines are stripped before they are split
        body = _EDGES.sub("", body)
        data = np.frombuffer(body.encode("ascii"), np.uint8)
    form = _canonical(body, data)
    if form is None:
        return False
    canon, decimal_comma, commas_split_on_blanks = form
    parsed = _parse(canon)
    if parsed is None:
        return False
    flat, counts = parsed
    marks = dict(reading.marks)
    if decimal_comma and "," in body:
        marks.setdefault(",", first + body.count("\n", 0, body.index(",")))
    if "." in body:
        marks.setdefault(".", first + body.count("\n", 0, body.index(".")))
    if len(marks) > 1 or (commas_split_on_blanks and np.any(_lines_with(data, ",") & (counts < 2))):
        return False
    reading.marks.update(marks)
    for key, note in sorted(notes.items(), key=lambda item: int(item[1].split(":")[0].split()[1])):
        reading.notes.setdefault(key, note)
    rows = counts > 0
    reading.parts.append((flat, counts[rows].astype(np.int64), first + np.flatnonzero(rows)))
    return True


def _normalised_text(body: str, notes: dict[str, str], first: int) -> str:
    """``_normalised`` of every line of a chunk at once (notes name the first line of each form)."""
    def line_of(index: int) -> int:
        return first + body.count("\n", 0, index)
    found = _GROUPED.search(body)
    if found:
        notes["group"] = f"line {line_of(found.start())}: read a no-break or thin space between digits as a thousands " \
                         "separator"
        body = _GROUPED.sub("", body)
    table = {ord(ch): "-" for ch in _MINUS} | {ord(ch): "+" for ch in _PLUS} | {ord(ch): " " for ch in _GROUP_SPACE}
    found = re.search(f"[{_MINUS}]", body)
    if found:
        ch = found.group()
        notes["minus"] = f"line {line_of(found.start())}: read U+{ord(ch):04X} ({unicodedata.name(ch, '?').lower()}) " \
                         "as a minus sign"
    found = _OTHER_DIGIT.search(body)
    if found:
        ch = found.group()
        notes["digits"] = f"line {line_of(found.start())}: read digits of another script " \
                          f"({unicodedata.name(ch, '?').lower()})"
        table |= {ord(d): str(unicodedata.digit(d)) for d in set(_OTHER_DIGIT.findall(body))}
    return body.translate(table)


def _canonical(body: str, data: np.ndarray) -> tuple[str, bool, bool] | None:
    """The chunk as numbers separated by blanks, whether its commas were decimal marks and whether
    they were so because blanks separate the fields (then a line with a comma needs two fields);
    None when a line would be split another way than the others."""
    has = {ch: ch in body for ch in ";\t, ."}
    if has[";"] or has["\t"]:
        sep = ";" if has[";"] else "\t"
        blanks = " \t" if sep == ";" else " "
        if has[","] and has["."]:
            return None
        canon = _fields_joined(body, data, sep, blanks)
        return None if canon is None else (canon.replace(",", "."), True, False)
    if not has[","]:
        return body, False, False
    if not has[" "]:
        canon = _fields_joined(body, data, ",", "")
        return None if canon is None else (canon, False, False)
    if has["."]:
        rows = _per_line(data, (data != 32) & (data != 10), np.logical_or)
        if not np.all(_lines_with(data, ".") | ~rows) or not np.all(_lines_with(data, ",") | ~rows):
            return None  # a line without a point could have decimal commas, one without a comma blanks
        canon = _fields_joined(body, data, ",", " ")
        return None if canon is None else (canon, False, False)
    return body.replace(",", "."), True, True


def _fields_joined(body: str, data: np.ndarray, sep: str, blanks: str) -> str | None:
    """The fields of lines that ``sep`` separates, joined by blanks; None when a line lacks the
    separator (it would be split on blanks) or a field is empty or holds a blank."""
    if blanks:  # (none only for commas in a chunk without blanks: a line without one is one field either way)
        blank_lines = ~_per_line(data, (data != 32) & (data != 9) & (data != 10), np.logical_or)
        if not np.all(_lines_with(data, sep) | blank_lines):
            return None
    if any(ch in body for ch in blanks):  # blanks around a separator (line edges are stripped)
        body = re.sub(f"[{blanks}]+(?={sep})|(?<={sep})[{blanks}]+", "", body)
        if any(ch in body for ch in blanks):
            return None
    if body.startswith(sep) or f"\n{sep}" in body:
        return None
    if body.endswith(sep) or f"{sep}\n" in body:  # separators that end a line end no field
        body = re.sub(f"{re.escape(sep)}+(?=\n|$)", "", body)
    if sep * 2 in body:
        return None
    return body.replace(sep, " ")


def _blank_line_edges(data: np.ndarray) -> bool:
    """Whether a line of the ASCII text ``data`` starts or ends with a blank."""
    blank = (data == 32) | (data == 9)
    ends = np.concatenate(([True], data == 10, [True]))
    return bool(np.any(blank & (ends[:-2] | ends[2:])))


def _lines_with(data: np.ndarray, chars: str) -> np.ndarray:
    """Per line of the ASCII text ``data``: whether it holds any of ``chars``."""
    table = np.zeros(256, bool)
    table[np.frombuffer(chars.encode("ascii"), np.uint8)] = True
    return _per_line(data, table[data], np.logical_or)


def _per_line(data: np.ndarray, mask: np.ndarray, reduce: np.ufunc) -> np.ndarray:
    """Per line of the ASCII text ``data``: ``reduce`` (logical_or, add) of ``mask`` over its
    characters (``mask`` is False at line breaks)."""
    starts = np.concatenate(([0], np.flatnonzero(data == 10) + 1))
    padded = np.concatenate((mask, [False]))  # the last line may be empty: its segment is the pad
    return reduce.reduceat(padded, starts, dtype=np.int64 if reduce is np.add else bool)


def _parse(canon: str) -> tuple[np.ndarray, np.ndarray] | None:
    """Every number of a text of plain decimal numbers separated by blanks and line breaks, and
    how many each line holds; None when a field is not a plain decimal number (numpy's reader
    refuses exactly what the module's pattern refuses, over these characters) or not finite."""
    data = np.frombuffer(canon.encode("ascii"), np.uint8)
    token = (data != 32) & (data != 10) & (data != 9)
    starts = token & ~np.concatenate(([False], token[:-1]))
    counts = _per_line(data, starts, np.add)
    total = int(counts.sum())
    if not total:
        return np.zeros(0), counts
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        try:
            flat = np.fromstring(canon, sep=" ")
        except (DeprecationWarning, ValueError):
            return None
    if len(flat) != total or not np.isfinite(flat).all():
        return None
    return flat, counts
