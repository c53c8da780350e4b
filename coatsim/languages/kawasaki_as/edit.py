"""Edit an AS file as text: replace ranges of lines and append a ``.TRANS`` section, every
other byte kept as it was (encoding, byte-order mark, line ends, comments)."""

from __future__ import annotations

import re
from collections import Counter
from typing import Sequence

from coatsim.core.fileio import UTF8_BOM as _BOM

_BREAK = re.compile(r"(\r\n|\r|\n)")


def _decode(data: bytes) -> tuple[str, str, bool]:
    bom = data.startswith(_BOM)
    body = data[len(_BOM):] if bom else data
    try:
        return body.decode("utf-8"), "utf-8", bom
    except UnicodeDecodeError:
        return body.decode("latin-1"), "latin-1", bom


def edit_lines(data: bytes, replacements: Sequence[tuple[int, int, Sequence[str]]], appended: Sequence[str]) -> bytes:
    """``data`` with lines ``first``..``last`` (1-based, inclusive) replaced by new lines for
    each (first, last, lines) (ranges must not overlap), and ``appended`` lines at the end; new
    lines take the file's most common line end."""
    text, codec, bom = _decode(data)
    parts = _BREAK.split(text)
    lines, ends = parts[0::2], parts[1::2]
    if len(ends) < len(lines):
        ends.append("")
    if lines and lines[-1] == "" and ends[-1] == "":
        lines.pop()
        ends.pop()
    newline = Counter(e for e in ends if e).most_common(1)[0][0] if any(ends) else "\n"
    for first, last, new in sorted(replacements, key=lambda r: r[0], reverse=True):
        tail_end = ends[last - 1]
        lines[first - 1:last] = list(new)
        ends[first - 1:last] = [newline] * (len(new) - 1) + [tail_end or newline] if new else []
    if appended:
        if ends and not ends[-1]:
            ends[-1] = newline
        lines += list(appended)
        ends += [newline] * len(appended)
    out = "".join(line + end for line, end in zip(lines, ends))
    return (_BOM if bom else b"") + out.encode(codec)


def indentation(data: bytes, line: int) -> str:
    """The leading blanks of a line (1-based)."""
    text = _decode(data)[0]
    lines = _BREAK.split(text)[0::2]
    current = lines[line - 1] if 0 < line <= len(lines) else ""
    return current[:len(current) - len(current.lstrip(" \t"))]
