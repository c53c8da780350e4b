"""Universal Robots URScript behind coatsim's language interface."""

from __future__ import annotations

from pathlib import Path
from typing import Sequence

from coatsim.core.errors import InputError
from coatsim.core.fileio import decode_text, read_input_bytes
from coatsim.languages.urscript.interpreter import UrRun
from coatsim.languages.urscript.names import MAX_NAME_LENGTH, check_name, program_name
from coatsim.languages.urscript.parser import parse_script
from coatsim.languages.urscript.writer import MAX_ARC_SWEEP_DEG, MAX_COORDINATE_MM, write_urscript
from coatsim.path.language import Capabilities, ReadOptions
from coatsim.path.plan import ProgramPlan
from coatsim.path.toolpath import ToolPath


class UrScript:
    """Writes and reads URScript (``.script``): movel/movec/movej with blend radii, poses in metres
    and rotation vectors. Several files read together are one script, in the order given."""

    name = "urscript"
    title = "Universal Robots URScript"
    suffixes = (".script", ".urscript")

    def __init__(self) -> None:
        self.capabilities = Capabilities(arc_planes="any", max_arc_sweep_deg=MAX_ARC_SWEEP_DEG,
                                         blend="blend radius r (m); r=0 stops",
                                         max_name_length=MAX_NAME_LENGTH, max_coordinate_mm=MAX_COORDINATE_MM,
                                         rotation="rotation vector (rad), positions in m")

    def write(self, plan: ProgramPlan) -> str:
        return write_urscript(plan)

    def read(self, files: Sequence[Path], options: ReadOptions) -> ToolPath:
        if not files:
            raise InputError("no program file given")
        statements, comments = [], []
        for path in files:
            body, notes = parse_script(decode_text(read_input_bytes(path, "program")), str(path))
            statements += body
            comments += notes
        run = UrRun(tuple(statements), comments, str(files[0]), options, Path(files[0]).stem)
        toolpath = run.run()
        if options.needs_spray and not toolpath.spray_moves:
            switched = ", ".join(dict.fromkeys(run.robot.switched)) or "no output"
            raise InputError(f"{files[0]}: the gun (digital output {options.gun_signal}) is never on during a motion; "
                             f"the program switches {switched}", parameters=("gun_signal",))
        return toolpath

    def check_name(self, name: str, what: str) -> str:
        return check_name(name, what)

    def program_name(self, text: str) -> str:
        return program_name(text)


URSCRIPT = UrScript()
