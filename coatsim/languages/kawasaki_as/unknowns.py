"""What a program reads that no file gives: variables kept in the controller's memory (set by
another program, a PC task, the pendant), and what follows from them.

A real or a string read before any value is given reads as 0 or "" (the controller's memory is
not in the files); a pose or a joint value has no default: reading one raises :class:`Absent`.
The interpreter turns that into a note and goes on: a condition that depends on an unknown is
taken with its default (a pose's absence: false), a statement that cannot run without one is
skipped. Every unknown is named once with the line that first reads it; values given from
outside (``NAME=VALUE``) replace them.
"""

from __future__ import annotations

from dataclasses import dataclass, field


class Absent(Exception):
    """A value the run does not have: a pose or joint value never given, or a number that needs
    what the twin does not compute; ``reason`` says which, for the note."""

    def __init__(self, reason: str) -> None:
        super().__init__(reason)
        self.reason = reason


class NotSimulated(Absent):
    """What the twin does not simulate (a motion it cannot follow, a pose function it does not
    compute): the statement is skipped with a note, as for a missing value, but no value given
    from outside brings it back, and a simulation refuses it as a run it cannot execute."""


# The value a POINT / HERE target takes when its value is absent (reading it raises Absent again).
ABSENT = object()


@dataclass(frozen=True)
class UnknownRead:
    """A variable read before any value is given: its name (lower case, no index), kind
    ('real', 'string', 'pose', 'joint'), where it is first read ("file:line") and the element
    read there as written (``$cnt[0]``)."""

    name: str
    kind: str
    where: str
    shown: str

    def note(self) -> str:
        taken = {"real": "taken as 0 (a motion built from it is skipped)", "string": 'taken as ""'}.get(
            self.kind, "what needs it is skipped")
        if self.name.startswith("."):
            return f"{self.where}: the local {self.shown} ({self.kind}) is read before any value is given; {taken}"
        return (f"{self.where}: {self.shown} ({self.kind}) is read but no file gives it a value (a variable of "
                f"the controller's memory?); {taken}; give it one as {self.shown}=VALUE")


@dataclass
class Unknowns:
    """The unknowns of one run, the reads of them (for telling what depends on one), and the
    statements skipped for want of a value."""

    first: dict[str, UnknownRead] = field(default_factory=dict)
    reads: int = 0
    last: str = ""
    messages: int = 0  # messages received that the twin does not have (TCP_RECV, ...)
    skipped: list[str] = field(default_factory=list)
    unsimulated: list[str] = field(default_factory=list)  # the skipped ones the twin does not simulate

    def read(self, name: str, kind: str, where: str, shown: str) -> bool:
        """Count a read of the unknown ``name``; True when it is the first."""
        self.reads += 1
        self.last = shown
        if name in self.first:
            return False
        self.first[name] = UnknownRead(name, kind, where, shown)
        return True
