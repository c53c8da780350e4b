"""Values a program reads but never sets, for the readers that carry them as values (URScript,
G-code, Fanuc TP).

A real program reads what the controller keeps: a UR installation variable or feature, a G-code
parameter ``#100``, a Fanuc register ``R[5]`` or position register ``PR[2]``. Reading is not
running: such a read is not an error. It gives an :class:`Unset` value naming the unknowns it
comes from; arithmetic on it gives another, an assignment stores it. Only what needs the number
itself — a motion's target, a speed, a condition, a loop's count — raises :class:`DependsOn`,
and the statement is skipped and listed. Every unknown is named with the places that read it;
values given from outside (``NAME=VALUE``) replace them, and a simulation refuses a program with
a statement skipped (:func:`coatsim.path.reading.require_every_statement`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Iterable

MAX_PLACES_SHOWN = 5  # places an unknown is read, listed before "and n more"


@dataclass(frozen=True)
class Unset:
    """A value computed from unknowns: ``names`` the unknowns, as the program writes them."""

    names: tuple[str, ...]


class DependsOn(Exception):
    """What needs a number depends on the unknowns ``names``."""

    def __init__(self, names: tuple[str, ...]) -> None:
        super().__init__(", ".join(names))
        self.names = names


def unset_names(values: Iterable[object]) -> tuple[str, ...]:
    """The unknowns any of ``values`` (lists and tuples searched inside) depends on, in order."""
    found: dict[str, None] = {}
    for value in values:
        if isinstance(value, Unset):
            found.update(dict.fromkeys(value.names))
        elif isinstance(value, (list, tuple)):
            found.update(dict.fromkeys(unset_names(value)))
    return tuple(found)


def require_known(value: object) -> None:
    """DependsOn when ``value`` is, or holds, an Unset."""
    names = unset_names((value,))
    if names:
        raise DependsOn(names)


@dataclass
class UnknownLog:
    """The unknowns of one run and the statements skipped for want of them. ``kept`` says where
    such a value lives, for the note (``a register the controller keeps``)."""

    kept: str
    places: dict[str, list[str]] = field(default_factory=dict)
    shown: dict[str, str] = field(default_factory=dict)
    skipped: list[str] = field(default_factory=list)

    def read(self, name: str, where: str, key: str = "") -> Unset:
        """A read of the unknown ``name`` at ``where`` (``file:line``): its value. ``key`` tells
        names apart in a case-insensitive language (the name as first written is shown)."""
        key = key or name
        name = self.shown.setdefault(key, name)
        places = self.places.setdefault(key, [])
        if where not in places:
            places.append(where)
        return Unset((name,))

    def skip(self, where: str, what: str, names: tuple[str, ...]) -> None:
        """The statement ``what`` at ``where`` is skipped: it depends on ``names`` (a place each is used)."""
        for key, shown in self.shown.items():
            if shown in names and where not in self.places[key]:
                self.places[key].append(where)
        listed = ", ".join(names)
        self.skipped.append(f"{where}: {what} skipped: it depends on {listed}, which the program never sets")

    def unknowns(self) -> tuple[str, ...]:
        """One line per unknown: where it is first read, where else, and how to give it."""
        lines = []
        for key, places in self.places.items():
            name = self.shown[key]
            also = ""
            if len(places) > 1:
                shown = ", ".join(_short(place, places[0]) for place in places[1:1 + MAX_PLACES_SHOWN])
                more = len(places) - 1 - MAX_PLACES_SHOWN
                also = f"; also read at {shown}" + (f" and {more} more places" if more > 0 else "")
            lines.append(f"{places[0]}: {name} is read but the program never sets it ({self.kept}?){also}; "
                         f"give it as {name}=VALUE")
        return tuple(lines)


def _short(place: str, first: str) -> str:
    """``file:line`` as ``line N`` when the file is that of ``first``."""
    source, _, line = place.rpartition(":")
    return f"line {line}" if source == first.rpartition(":")[0] else place
