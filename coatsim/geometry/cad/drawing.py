"""A read drawing: its pieces in the workpiece plane (mm) and what was left out; what the DXF
and SVG readers share."""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass
from pathlib import Path
from typing import Sequence

from coatsim.core.errors import InputError
from coatsim.geometry.cad.pieces import Piece

DRAWING_SUFFIXES = (".dxf", ".svg")


@dataclass(frozen=True, eq=False)
class Drawing:
    """Pieces in drawing order (mm, y up), the unit conversion applied, and notes on what
    was ignored (one line each)."""

    source: str
    pieces: tuple[Piece, ...]
    units: str
    notes: tuple[str, ...] = ()


def is_drawing(spec: str | Path) -> bool:
    """Whether ``spec`` names a DXF or SVG file (by its suffix)."""
    return Path(str(spec)).suffix.lower() in DRAWING_SUFFIXES


def count_note(what: str, counts: Counter, why: str) -> str:
    """"ignored 3 TEXT, 1 HATCH (not geometry)" from a Counter of kinds."""
    listed = ", ".join(f"{n} {kind}" for kind, n in sorted(counts.items(), key=lambda kv: (-kv[1], kv[0])))
    return f"{what} {listed} ({why})"


def check_layers(source: str, wanted: Sequence[str] | None, known: Sequence[str]) -> tuple[str, ...] | None:
    """The layer names asked for, each of which must exist (compared case-insensitively)."""
    if not wanted:
        return None
    lower = {k.lower() for k in known}
    for name in wanted:
        if name.lower() not in lower:
            listed = ", ".join(repr(k) for k in known) or "none"
            raise InputError(f"{source}: layer {name!r} (--layer): no such layer (layers: {listed})")
    return tuple(name.lower() for name in wanted)
