"""The M-codes that switch the gun of a G-code program (a language option)."""

from __future__ import annotations

from dataclasses import dataclass

from coatsim.core.errors import InputError


@dataclass(frozen=True)
class GunCodes:
    """The M-code that opens the gun and the one that closes it: ``M3``/``M5`` by default (a
    plasma table's torch on the spindle codes), ``M7``/``M9`` or ``M8``/``M9`` on a control that
    switches it as coolant."""

    on: int = 3
    off: int = 5

    def __post_init__(self) -> None:
        if self.on == self.off or not (0 <= self.on <= 199 and 0 <= self.off <= 199):
            raise InputError(f"gun codes M{self.on}/M{self.off}: two different M-codes from M0 to M199")

    def describe(self) -> str:
        return f"M{self.on}/M{self.off}"
