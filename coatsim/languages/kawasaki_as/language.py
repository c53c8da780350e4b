"""Kawasaki AS behind coatsim's language interface."""

from __future__ import annotations

from pathlib import Path
from typing import Sequence

from coatsim.core.errors import InputError
from coatsim.languages.kawasaki_as.files import read_program
from coatsim.languages.kawasaki_as.names import MAX_NAME_LENGTH, check_name, program_name
from coatsim.languages.kawasaki_as.writer import MAX_ARC_SWEEP_DEG, MAX_COORDINATE_MM, write_as
from coatsim.path.check import gun_never_on
from coatsim.path.language import Capabilities, ReadOptions
from coatsim.path.plan import ProgramPlan
from coatsim.path.toolpath import ToolPath


class KawasakiAs:
    """Writes ``.as`` files (C1MOVE/C2MOVE arcs in any plane, split above ``max_arc_sweep_deg``)
    and reads the files real cells run (``.as``, ``.pg`` backups)."""

    name = "kawasaki-as"
    title = "Kawasaki AS"
    suffixes = (".as", ".pg")

    def __init__(self, max_arc_sweep_deg: float = MAX_ARC_SWEEP_DEG) -> None:
        self.max_arc_sweep_deg = max_arc_sweep_deg
        self.capabilities = Capabilities(arc_planes="any", max_arc_sweep_deg=max_arc_sweep_deg,
                                         blend="ACCURACY mm (CP ON), a stop under CP OFF or BREAK",
                                         max_name_length=MAX_NAME_LENGTH, max_coordinate_mm=MAX_COORDINATE_MM,
                                         rotation="O-A-T (Z-Y-Z Euler, deg)")

    def write(self, plan: ProgramPlan) -> str:
        return write_as(plan, self.max_arc_sweep_deg)

    def read(self, files: Sequence[Path], options: ReadOptions) -> ToolPath:
        run = read_program(files, options.gun_signal, options.program, inputs=options.inputs,
                           kinematics=options.kinematics, variables=options.variables)
        if options.needs_spray and not run.toolpath.spray_moves:
            raise InputError(f"{gun_never_on(str(files[0]), options.gun_signal, run.outputs)}; give the output that "
                             "opens the gun as gun_signal", parameters=("gun_signal",))
        return run.toolpath

    def check_name(self, name: str, what: str) -> str:
        return check_name(name, what)

    def program_name(self, text: str) -> str:
        return program_name(text)


KAWASAKI_AS = KawasakiAs()
