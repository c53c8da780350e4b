"""Converting a program in its own file: what ``convert`` hands a language that can edit its
programs in place, and what it gets back.

Editing in place is a capability: a language that has it implements :class:`EditsInPlace`
(Kawasaki AS does); ``convert`` writes a standalone program in any language otherwise.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Optional, Protocol, Sequence, runtime_checkable

from coatsim.path.language import ReadOptions
from coatsim.path.placement import PlacedMove
from coatsim.path.process_path import PlaneFrame, ProcessPath


@dataclass(frozen=True, eq=False)
class FittedPath:
    """One process path and its fit: the moves it replaces (``path.moves``, indices into the
    reading's ToolPath), its plane (None: fitted in space), the fitted lines and arcs in the
    robot base frame, their counts, the fit's deviation, the source lines the path spans,
    notes."""

    path: ProcessPath
    plane: Optional[PlaneFrame]
    segments: tuple[PlacedMove, ...]
    n_arcs: int
    n_lines: int
    fit_deviation_mm: float
    lines: tuple[int, int]
    notes: tuple[str, ...]


@dataclass(frozen=True)
class InPlaceEdit:
    """A program file edited: its name as given (``source``), its new bytes (the original's
    encoding and line ends kept), how many moves each path became, the source lines each
    replaced."""

    source: str
    data: bytes
    counts: tuple[int, ...]
    ranges: tuple[tuple[int, int], ...]


@runtime_checkable
class EditsInPlace(Protocol):
    """A language that replaces the statements of process paths in the program's own file."""

    def edit_in_place(self, files: Sequence[Path], options: ReadOptions, paths: Sequence[FittedPath],
                      tolerance_mm: float) -> InPlaceEdit:
        """The file holding ``paths`` with each path's statements replaced by its fitted moves,
        every other byte kept; InputError (with the line and why) where a path cannot be
        replaced in place."""
        ...
