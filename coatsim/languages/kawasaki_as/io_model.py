"""Signals as the twin sees them, what a program does with them, and the warnings of one run.

Numbering (Kawasaki): outputs 1..1000, inputs 1001..2000, internal signals 2001 and up. The
program sets outputs and internal signals; inputs come from the cell: the values given (a
scenario's ``inputs``, ``--inputs 1001,-1002``) or, for any other input, unknown. So is an
output or internal signal the program reads before it sets it (another task, a PC program or
the controller's memory sets it): a read of an unknown signal gives OFF and a warning, a wait for
one is taken as satisfied with a warning.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Mapping

from coatsim.core.errors import InputError

FIRST_INPUT, FIRST_INTERNAL = 1001, 2001
MAX_SIGNAL = 9999


def is_input(number: int) -> bool:
    return FIRST_INPUT <= number < FIRST_INTERNAL


def signal_name(number: int) -> str:
    """'input 1002', 'output 9', 'internal signal 2001'."""
    return f"input {number}" if is_input(number) else f"output {number}" if number < FIRST_INPUT else \
        f"internal signal {number}"


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


class SignalIO:
    """Signal reads and writes of a running program (a part of the interpreter, which provides
    ``signals``, ``gun``, ``controller``, ``outputs`` and its ``error``/``warn``)."""

    def sig(self, numbers: list[int]) -> float:
        result = True
        for n in numbers:
            if n == 0:
                raise self.error("signal number 0 does not exist")
            on, known = self.signals.state(abs(n))
            if not known:
                self.warn(f"input:{abs(n)}", f"{signal_name(abs(n))} is not given; taken as OFF (set it with --inputs "
                          "or the scenario's inputs)")
            result = result and (on == (n > 0))
        return -1.0 if result else 0.0

    def read_bits(self, start: int, count: int) -> int:
        if not 1 <= count <= 32:
            raise self.error(f"BITS count must be 1 to 32, got {count}")
        value = 0
        for i in range(count):
            on, known = self.signals.state(start + i)
            if not known:
                self.warn(f"input:{start + i}", f"{signal_name(start + i)} is not given; taken as OFF")
            value |= int(on) << i
        return value

    def set_signal(self, number: int, on: bool) -> None:
        if number == self.gun:
            self.controller.switch_gun(on)
        elif is_input(number):
            self.warn(f"set-input:{number}", f"signal {number} is an input; the program sets it here")
        if number < FIRST_INPUT:
            self.outputs.add(number)
        if self.signals.states.get(number) != on:
            self.changes += 1
        self.signals.set(number, on)


class Signals:
    """Output, internal and input signal states."""

    def __init__(self, inputs: Mapping[int, bool]) -> None:
        self.given = dict(inputs)
        self.states: dict[int, bool] = {}
        self.unknown_read = False  # an unknown input was read since the flag was last cleared
        self.unknown_reads = 0  # reads of unknown signals in the run

    def set(self, number: int, on: bool) -> None:
        self.states[number] = on

    def state(self, number: int) -> tuple[bool, bool]:
        """(on, known) of a signal: known when the program set it or the cell gives it (an input,
        or an output or internal signal another task sets); otherwise OFF and unknown."""
        if number in self.states:
            return self.states[number], True
        if number in self.given:
            return self.given[number], True
        self.unknown_read = True
        self.unknown_reads += 1
        return False, False
