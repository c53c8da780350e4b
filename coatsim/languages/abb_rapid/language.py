"""ABB RAPID behind coatsim's language interface."""

from __future__ import annotations

import re
from pathlib import Path
from typing import Sequence

from coatsim.languages.abb_rapid.names import MAX_NAME_LENGTH, check_name, program_name
from coatsim.languages.abb_rapid.writer import MAX_ARC_SWEEP_DEG, MAX_COORDINATE_MM, write_rapid
from coatsim.path.language import Capabilities, ReadOptions
from coatsim.path.plan import ProgramPlan
from coatsim.path.reading import Reading
from coatsim.path.toolpath import ToolPath

_OPENING = re.compile(r"^\s*(%%%|MODULE\s+\w+)", re.IGNORECASE | re.MULTILINE)


class AbbRapid:
    """Writes one RAPID module (``.mod``: MoveL/MoveC in a work object, zonedata for blending)
    and reads modules as RobotStudio and people write them (``.mod``, ``.modx``, ``.prg``, ``.sys``)."""

    name = "abb-rapid"
    title = "ABB RAPID"
    suffixes = (".mod", ".modx", ".prg", ".sys")

    def __init__(self, max_arc_sweep_deg: float = MAX_ARC_SWEEP_DEG) -> None:
        self.max_arc_sweep_deg = max_arc_sweep_deg
        self.capabilities = Capabilities(arc_planes="any", max_arc_sweep_deg=max_arc_sweep_deg,
                                         blend="zonedata pzone_tcp mm (fly-by), fine a stop point",
                                         max_name_length=MAX_NAME_LENGTH, max_coordinate_mm=MAX_COORDINATE_MM,
                                         rotation="quaternion [q1 q2 q3 q4] = [w x y z], q1 >= 0",
                                         motions="MoveL/MoveC")

    def write(self, plan: ProgramPlan) -> str:
        return write_rapid(plan, self.max_arc_sweep_deg)

    def files(self, text: str) -> tuple[tuple[str, str], ...]:
        return ((self.suffixes[0], text),)

    def recognizes(self, text: str) -> bool:
        return _OPENING.search(text) is not None

    def read(self, files: Sequence[Path], options: ReadOptions) -> ToolPath:
        return self.reading(files, options).toolpath_to_run(options.gun_signal, options.needs_spray, str(files[0]))

    def reading(self, files: Sequence[Path], options: ReadOptions) -> Reading:
        from coatsim.languages.abb_rapid.reading import read_rapid  # the interpreter loads when a program is read

        return read_rapid(files, options)

    def check_name(self, name: str, what: str) -> str:
        return check_name(name, what)

    def program_name(self, text: str) -> str:
        return program_name(text)


ABB_RAPID = AbbRapid()
