"""An .LS file: ``/PROG name``, ``/ATTR`` (and ``/APPL``: skipped), ``/MN`` (numbered instruction
lines ``n: instruction ;``; a circular move continues on a ``:`` line), ``/POS`` (the positions),
``/END``. Instructions are read into :mod:`.statements` values, positions into :mod:`.positions`.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field, replace
from typing import Mapping

from coatsim.core.errors import InputError
from coatsim.languages.fanuc_tp.positions import Position, parse_positions
from coatsim.languages.fanuc_tp.statements import Motion, Select, Statement, parse_instruction

_NUMBERED = re.compile(r"\s*(\d+)?\s*:(.*)\Z", re.S)
_CONTROL = re.compile(r"[\x00-\x08\x0a-\x1f\x7f]")  # a tab is text; a line holds no other control character
_SECTION = re.compile(r"\s*/(PROG|ATTR|APPL|MN|POS|END)\b(.*)\Z", re.I | re.S)


@dataclass(frozen=True, eq=False)
class LsProgram:
    name: str
    source: str
    statements: tuple[Statement, ...]
    positions: Mapping[int, Position] = field(default_factory=dict)
    line: int = 1  # the /PROG line


def _instructions(lines: list[tuple[int, str]], source: str) -> list[Statement]:
    """The statements of the ``/MN`` lines (file line number, text)."""
    out: list[Statement] = []
    pending, start = "", 0
    for number, raw in lines:
        match = _NUMBERED.match(raw)
        content = match.group(2) if match else raw
        if not pending:
            start = number
            if not content.strip():
                continue
        pending += " " + content
        if not pending.rstrip().endswith(";"):
            continue
        text = pending.rstrip()[:-1]
        pending = ""
        statement = parse_instruction(text, start, f"{source}:{start}")
        if statement is None:
            continue
        if isinstance(statement, Motion):
            statement = replace(statement, end_line=number)
        if isinstance(statement, Select) and statement.subject is None:
            if not out or not isinstance(out[-1], Select):
                raise InputError(f"{source}:{start}: a SELECT case line without a SELECT before it")
            out[-1] = replace(out[-1], cases=out[-1].cases + statement.cases)
            continue
        out.append(statement)
    if pending.strip():
        raise InputError(f"{source}:{start}: the instruction does not end with ';'")
    return out


def parse_ls(text: str, source: str) -> LsProgram:
    """The program of an .LS file; InputError naming file:line on any defect."""
    name, section, name_line = None, None, 1
    mn: list[tuple[int, str]] = []
    pos_lines: list[str] = []
    pos_start = 0
    for number, raw in enumerate(text.splitlines(), start=1):
        if _CONTROL.search(raw):
            raise InputError(f"{source}:{number}: a control character in the line; an .LS file is plain text")
        head = _SECTION.match(raw)
        if head:
            section = head.group(1).upper()
            if section == "PROG":
                words = head.group(2).split()
                if not words:
                    raise InputError(f"{source}:{number}: /PROG needs the program's name")
                name, name_line = words[0].upper(), number
            if section == "POS":
                pos_start = number + 1
            if section == "END":
                break
            continue
        if section == "MN":
            mn.append((number, raw))
        elif section == "POS":
            pos_lines.append(raw)
    if name is None:
        raise InputError(f"{source}: not a Fanuc .LS program (no /PROG line)")
    if section not in ("MN", "POS", "END") and not mn:
        raise InputError(f"{source}: the program has no /MN section (its instructions)")
    positions = parse_positions("\n".join(pos_lines), source, pos_start)
    return LsProgram(name, source, tuple(_instructions(mn, source)), positions, name_line)
