"""KRL statement lines -> nested blocks: IF/ELSE/ENDIF, FOR/ENDFOR, WHILE/ENDWHILE,
LOOP/ENDLOOP, REPEAT/UNTIL, SWITCH/CASE/DEFAULT/ENDSWITCH; any other line is a simple statement."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

from coatsim.core.errors import InputError
from coatsim.languages.kuka_krl.parser import Line

_OPEN = {"IF": ("ENDIF",), "FOR": ("ENDFOR",), "WHILE": ("ENDWHILE",), "LOOP": ("ENDLOOP",), "REPEAT": ("UNTIL",),
         "SWITCH": ("ENDSWITCH",)}


@dataclass(frozen=True)
class Block:
    """``kind`` IF, FOR, WHILE, LOOP, REPEAT, SWITCH; ``head`` its opening line, ``parts`` the
    bodies with their opening lines (IF: THEN, ELSE; SWITCH: CASE.../DEFAULT), ``tail`` the
    closing line (REPEAT: its UNTIL)."""

    kind: str
    head: Line
    parts: tuple[tuple[Optional[Line], tuple], ...]
    tail: Line

    @property
    def line(self) -> int:
        return self.head.line


def build(lines: tuple[Line, ...], source: str) -> tuple:
    body, k = _block(lines, 0, (), source)
    return body


def _block(lines, k: int, ends: tuple[str, ...], source: str):
    out = []
    while k < len(lines):
        ln = lines[k]
        word = ln.word
        if word in ends or (word in ("ELSE", "CASE", "DEFAULT") and ends):
            return tuple(out), k
        if word in _OPEN:
            block, k = _open(lines, k, source)
            out.append(block)
            continue
        if word in ("ENDIF", "ENDFOR", "ENDWHILE", "ENDLOOP", "UNTIL", "ENDSWITCH", "ELSE", "CASE", "DEFAULT"):
            raise InputError(f"{source}:{ln.line}: {ln.tokens[0].text} without the statement that opens it")
        out.append(ln)
        k += 1
    if ends:
        start = lines[k - 1].line if lines else 0
        raise InputError(f"{source}:{start}: expected {' or '.join(ends)} before the end of the routine")
    return tuple(out), k


def _open(lines, k: int, source: str):
    head = lines[k]
    kind = head.word
    end = _OPEN[kind][0]
    parts = []
    if kind == "SWITCH":
        k += 1
        while k < len(lines) and lines[k].word in ("CASE", "DEFAULT"):
            opener = lines[k]
            body, k = _block(lines, k + 1, ("CASE", "DEFAULT", end), source)
            parts.append((opener, body))
        if k >= len(lines) or lines[k].word != end:
            raise InputError(f"{source}:{head.line}: SWITCH without {end}")
        return Block(kind, head, tuple(parts), lines[k]), k + 1
    body, k = _block(lines, k + 1, (end,) + (("ELSE",) if kind == "IF" else ()), source)
    parts.append((None, body))
    if kind == "IF" and k < len(lines) and lines[k].word == "ELSE":
        opener = lines[k]
        body, k = _block(lines, k + 1, (end,), source)
        parts.append((opener, body))
    if k >= len(lines) or lines[k].word != end:
        raise InputError(f"{source}:{head.line}: {kind} without {end}")
    return Block(kind, head, tuple(parts), lines[k]), k + 1
