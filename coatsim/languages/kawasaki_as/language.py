"""Kawasaki AS behind coatsim's language interface."""

from __future__ import annotations

import re
from pathlib import Path
from typing import Sequence

from coatsim.core.errors import InputError
from coatsim.languages.kawasaki_as.convert_edit import edit_in_place
from coatsim.languages.kawasaki_as.files import read_program
from coatsim.languages.kawasaki_as.names import MAX_NAME_LENGTH, check_name, program_name
from coatsim.languages.kawasaki_as.reading import read_as
from coatsim.languages.kawasaki_as.writer import MAX_ARC_SWEEP_DEG, MAX_COORDINATE_MM, write_as
from coatsim.path.edit import FittedPath, InPlaceEdit
from coatsim.path.language import Capabilities, ReadOptions
from coatsim.path.plan import ProgramPlan
from coatsim.path.reading import Reading, gun_never_on
from coatsim.path.toolpath import ToolPath

# What an AS file opens with: a dot-section (.PROGRAM, .TRANS, ...) or a backup header line (.*).
_OPENING = re.compile(r"^\s*\.(PROGRAM|TRANS|JOINTS|REALS|STRINGS|\*)", re.IGNORECASE | re.MULTILINE)


class KawasakiAs:
    """Writes ``.as`` files (C1MOVE/C2MOVE arcs in any plane, split above ``max_arc_sweep_deg``)
    and reads the files real cells run (``.as``, ``.pg`` backups); edits them in place."""

    name = "kawasaki-as"
    title = "Kawasaki AS"
    suffixes = (".as", ".pg")

    def __init__(self, max_arc_sweep_deg: float = MAX_ARC_SWEEP_DEG) -> None:
        self.max_arc_sweep_deg = max_arc_sweep_deg
        self.capabilities = Capabilities(arc_planes="any", max_arc_sweep_deg=max_arc_sweep_deg,
                                         blend="ACCURACY mm (CP ON), a stop under CP OFF or BREAK",
                                         max_name_length=MAX_NAME_LENGTH, max_coordinate_mm=MAX_COORDINATE_MM,
                                         rotation="O-A-T (Z-Y-Z Euler, deg)", motions="LMOVE/C1MOVE/C2MOVE")

    def write(self, plan: ProgramPlan) -> str:
        return write_as(plan, self.max_arc_sweep_deg)

    def files(self, text: str) -> tuple[tuple[str, str], ...]:
        return ((self.suffixes[0], text),)

    def recognizes(self, text: str) -> bool:
        return _OPENING.search(text) is not None

    def read(self, files: Sequence[Path], options: ReadOptions) -> ToolPath:
        run = read_program(files, options.gun_signal, options.program, inputs=options.inputs,
                           kinematics=options.kinematics, variables=options.variables)
        if options.needs_spray and not run.toolpath.spray_moves:
            raise InputError(f"{gun_never_on(str(files[0]), options.gun_signal, run.outputs)}; give the output that "
                             "opens the gun as gun_signal", parameters=("gun_signal",))
        return run.toolpath

    def reading(self, files: Sequence[Path], options: ReadOptions) -> Reading:
        return read_as(files, options)

    def edit_in_place(self, files: Sequence[Path], options: ReadOptions, paths: Sequence[FittedPath],
                      tolerance_mm: float) -> InPlaceEdit:
        return edit_in_place(files, options, paths, tolerance_mm)

    def check_name(self, name: str, what: str) -> str:
        return check_name(name, what)

    def program_name(self, text: str) -> str:
        return program_name(text)


KAWASAKI_AS = KawasakiAs()
