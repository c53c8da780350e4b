"""Kawasaki AS behind the common dialect interface."""

from __future__ import annotations

from coatsim.languages.kawasaki_as.interpreter import interpret
from coatsim.languages.kawasaki_as.parser import parse_as
from coatsim.languages.kawasaki_as.writer import MAX_ARC_SWEEP_DEG, write_as
from coatsim.path.dialect import ProgramPlan
from coatsim.path.toolpath import ToolPath


class KawasakiAs:
    """Writes ``.as`` files (arcs split above ``max_arc_sweep_deg``) and reads them back."""

    name = "kawasaki-as"
    suffix = ".as"

    def __init__(self, max_arc_sweep_deg: float = MAX_ARC_SWEEP_DEG) -> None:
        self.max_arc_sweep_deg = max_arc_sweep_deg

    def write(self, plan: ProgramPlan) -> str:
        return write_as(plan, self.max_arc_sweep_deg)

    def read(self, text: str, source: str, gun_signal: int = 1) -> ToolPath:
        return interpret(parse_as(text, source), gun_signal=gun_signal)


KAWASAKI_AS = KawasakiAs()
