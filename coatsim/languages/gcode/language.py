"""G-code behind coatsim's language interface."""

from __future__ import annotations

import re
from pathlib import Path
from typing import TYPE_CHECKING, Sequence

from coatsim.core.errors import InputError
from coatsim.core.fileio import decode_text, read_program_file
from coatsim.languages.gcode.blocks import parse_blocks
from coatsim.languages.gcode.gun import GunCodes
from coatsim.languages.gcode.names import MAX_NAME_LENGTH, check_name, program_name
from coatsim.languages.gcode.writer import MAX_ARC_SWEEP_DEG, MAX_COORDINATE_MM, write_gcode
from coatsim.path.language import Capabilities, ReadOptions
from coatsim.path.plan import ProgramPlan
from coatsim.path.reading import Reading
from coatsim.path.toolpath import ToolPath

if TYPE_CHECKING:
    from coatsim.languages.gcode.interpreter import Interpreter

# A block of G or M words (an optional N number first), or a program's opening '%' line then one.
_OPENING = re.compile(r"^\s*(N\d+\s*)?[GM]\d", re.IGNORECASE | re.MULTILINE)


class GCode:
    """Writes and reads G-code programs (``.ngc``, ``.nc``, ``.gcode``, ``.tap``): arcs only in
    the principal planes, no tool orientation (the gun along −Z), the gun switched by an M-code
    pair (``gun``, M3/M5 by default)."""

    name = "gcode"
    title = "G-code (RS274/NGC)"
    suffixes = (".ngc", ".nc", ".gcode", ".tap")

    def __init__(self, gun: GunCodes = GunCodes()) -> None:
        self.gun = gun
        self.capabilities = Capabilities(arc_planes="principal", max_arc_sweep_deg=MAX_ARC_SWEEP_DEG,
                                         blend="G64 P tolerance (mm); G61 exact stop",
                                         max_name_length=MAX_NAME_LENGTH, max_coordinate_mm=MAX_COORDINATE_MM,
                                         rotation="none: the gun points along -Z of the work frame", motions="G1/G2/G3",
                                         tool_orientation=False)

    def write(self, plan: ProgramPlan) -> str:
        return write_gcode(plan, self.gun)

    def files(self, text: str) -> tuple[tuple[str, str], ...]:
        return ((self.suffixes[0], text),)

    def recognizes(self, text: str) -> bool:
        return _OPENING.search(text) is not None

    def read(self, files: Sequence[Path], options: ReadOptions) -> ToolPath:
        reading, interpreter = self._read(files, options)
        reading.require_complete()
        if options.needs_spray and not reading.toolpath.spray_moves:
            switched = ", ".join(dict.fromkeys(interpreter.switched)) or "no M-code of an output"
            raise InputError(f"{files[0]}: the gun ({self.gun.describe()}, or M62-M65 P{options.gun_signal}) is never on "
                             f"during a motion; the program switches {switched}", parameters=("gun_signal",))
        return reading.toolpath

    def reading(self, files: Sequence[Path], options: ReadOptions) -> Reading:
        return self._read(files, options)[0]

    def _read(self, files: Sequence[Path], options: ReadOptions) -> tuple[Reading, Interpreter]:
        if len(files) != 1:
            raise InputError(f"G-code reads one program file at a time, got {len(files)}")
        path = Path(files[0])
        blocks = parse_blocks(decode_text(read_program_file(path)), str(path))
        from coatsim.languages.gcode.interpreter import Interpreter  # the interpreter loads when a program is read

        interpreter = Interpreter(blocks, str(path), options, self.gun, path.stem)
        toolpath = interpreter.run()
        n_poses = sum(any(letter in "XYZ" for letter, _ in b.words) for b in blocks)
        return interpreter.builder.reading(toolpath, (str(path),), (str(path), 1), (toolpath.name,),
                                           interpreter.ended, len(blocks), n_poses,
                                           unknowns=interpreter.params.unknown.unknowns(),
                                           skipped=tuple(interpreter.params.unknown.skipped)), interpreter

    def check_name(self, name: str, what: str) -> str:
        return check_name(name, what)

    def program_name(self, text: str) -> str:
        return program_name(text)


GCODE = GCode()
