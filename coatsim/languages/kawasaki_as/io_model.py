"""Signals as the twin sees them, and the warnings of one run.

Numbering (Kawasaki): outputs 1..1000, inputs 1001..2000, internal signals 2001 and up. The
program sets outputs and internal signals; inputs come from the cell: the values given (a
scenario's ``inputs``, ``--inputs 1001,-1002``) or, for any other input, unknown: a read of an
unknown input gives OFF and a warning, a wait for one is taken as satisfied with a warning.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Mapping

from coatsim.core.errors import InputError

FIRST_INPUT, FIRST_INTERNAL = 1001, 2001
MAX_SIGNAL = 9999


def is_input(number: int) -> bool:
    return FIRST_INPUT <= number < FIRST_INTERNAL


def parse_inputs(text: str, what: str = "--inputs") -> dict[int, bool]:
    """``"1001,-1002"`` (n on, -n off) -> {1001: True, 1002: False}; InputError naming ``what``."""
    states: dict[int, bool] = {}
    for part in (p.strip() for p in text.split(",")):
        if not part:
            continue
        try:
            number = int(part)
        except ValueError:
            raise InputError(f"{what}: expected signal numbers like 1001,-1002 (minus: off), got {part!r}") from None
        if not 1 <= abs(number) <= MAX_SIGNAL:
            raise InputError(f"{what}: signal {part} out of range 1..{MAX_SIGNAL}")
        states[abs(number)] = number > 0
    return states


@dataclass
class Warnings:
    """One line per distinct thing the twin does not simulate, in the order met."""

    lines: list[str] = field(default_factory=list)
    seen: set[str] = field(default_factory=set)

    def add(self, key: str, message: str) -> None:
        if key not in self.seen:
            self.seen.add(key)
            self.lines.append(message)


class Signals:
    """Output, internal and input signal states."""

    def __init__(self, inputs: Mapping[int, bool]) -> None:
        self.given = dict(inputs)
        self.states: dict[int, bool] = {}
        self.unknown_read = False  # an unknown input was read since the flag was last cleared

    def set(self, number: int, on: bool) -> None:
        self.states[number] = on

    def state(self, number: int) -> tuple[bool, bool]:
        """(on, known) of a signal."""
        if is_input(number) and number not in self.states:
            if number in self.given:
                return self.given[number], True
            self.unknown_read = True
            return False, False
        return self.states.get(number, False), True
