"""A parsed AS file: its ``.PROGRAM`` blocks, its data sections (``.TRANS``, ``.JOINTS``,
``.REALS``, ``.STRINGS``) and every other section kept as raw lines."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Mapping

from coatsim.languages.kawasaki_as.ast_statements import Statement


@dataclass(frozen=True)
class Param:
    """A parameter of a ``.PROGRAM``: a local name, ``by_ref`` for ``.&x``."""

    name: str
    by_ref: bool


@dataclass(frozen=True)
class Program:
    """One ``.PROGRAM`` block; ``metadata`` from its ``; coatsim: key=value`` comments."""

    name: str
    params: tuple[Param, ...]
    line: int
    body: tuple[Statement, ...]
    metadata: tuple[tuple[str, str], ...]
    source: str
    end_line: int


@dataclass(frozen=True)
class TransDef:
    """A ``.TRANS`` line: x, y, z (mm), o, a, t (deg), then external axes if any."""

    name: str
    values: tuple[float, float, float, float, float, float]
    extra: tuple[float, ...]
    line: int


@dataclass(frozen=True)
class JointDef:
    """A ``.JOINTS`` line (deg, mm for linear axes)."""

    name: str
    values: tuple[float, ...]
    line: int


@dataclass(frozen=True)
class RealDef:
    """A ``.REALS`` line ``name = value``."""

    name: str
    value: float
    line: int


@dataclass(frozen=True)
class StringDef:
    """A ``.STRINGS`` line ``$name = "text"``."""

    name: str
    value: str
    line: int


@dataclass(frozen=True)
class RawSection:
    """A section coatsim keeps as written (controller data, or one unknown to it)."""

    name: str
    line: int
    lines: tuple[str, ...]


@dataclass(frozen=True)
class AsFile:
    """A parsed AS file. Variable keys are names as written (``p[3]`` for an array element)."""

    source: str
    programs: tuple[Program, ...]
    trans: Mapping[str, TransDef]
    joints: Mapping[str, JointDef]
    reals: Mapping[str, RealDef]
    strings: Mapping[str, StringDef]
    sections: tuple[RawSection, ...]
    n_lines: int

    @property
    def skipped(self) -> tuple[tuple[str, int], ...]:
        """(name, line) of the sections coatsim does not read."""
        return tuple((s.name, s.line) for s in self.sections)
