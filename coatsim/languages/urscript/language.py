"""Universal Robots URScript behind coatsim's language interface."""

from __future__ import annotations

import re
from pathlib import Path
from typing import TYPE_CHECKING, Sequence

from coatsim.core.errors import InputError
from coatsim.core.fileio import decode_text, read_program_file
from coatsim.languages.urscript.names import MAX_NAME_LENGTH, check_name, program_name
from coatsim.languages.urscript.parser import Statement, parse_script
from coatsim.languages.urscript.writer import MAX_ARC_SWEEP_DEG, MAX_COORDINATE_MM, write_urscript
from coatsim.path.language import Capabilities, ReadOptions
from coatsim.path.plan import ProgramPlan
from coatsim.path.reading import Reading
from coatsim.path.toolpath import ToolPath

if TYPE_CHECKING:
    from coatsim.languages.urscript.interpreter import UrRun

# A function definition ending in ':' (KRL's DEF has none) or a motion call on a pose literal.
_OPENING = re.compile(r"^\s*(def\s+\w+\s*\([^)]*\)\s*:|(movel|movej|movep)\s*\(\s*p\s*\[)", re.MULTILINE)


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
                                         rotation="rotation vector (rad), positions in m", motions="movel/movec")

    def write(self, plan: ProgramPlan) -> str:
        return write_urscript(plan)

    def files(self, text: str) -> tuple[tuple[str, str], ...]:
        return ((self.suffixes[0], text),)

    def recognizes(self, text: str) -> bool:
        return _OPENING.search(text) is not None

    def read(self, files: Sequence[Path], options: ReadOptions) -> ToolPath:
        reading, run = self._read(files, options)
        reading.require_complete()
        if options.needs_spray and not reading.toolpath.spray_moves:
            switched = ", ".join(dict.fromkeys(run.robot.switched)) or "no output"
            raise InputError(f"{files[0]}: the gun (digital output {options.gun_signal}) is never on during a motion; "
                             f"the program switches {switched}", parameters=("gun_signal",))
        return reading.toolpath

    def reading(self, files: Sequence[Path], options: ReadOptions) -> Reading:
        return self._read(files, options)[0]

    def _read(self, files: Sequence[Path], options: ReadOptions) -> tuple[Reading, UrRun]:
        if len(files) != 1:
            raise InputError(f"URScript reads one script file at a time (the controller runs one), got {len(files)}")
        path = Path(files[0])
        statements, comments = parse_script(decode_text(read_program_file(path)), str(path))
        from coatsim.languages.urscript.interpreter import UrRun  # the interpreter loads when a program is read

        run = UrRun(statements, comments, str(path), options, path.stem)
        toolpath = run.run()
        functions = tuple(st.name for st in statements if st.kind == "def")
        body = run.main.body if run.main is not None else statements
        return run.robot.builder.reading(toolpath, (str(path),), (str(path), run.main.line if run.main else 1),
                                         functions or (toolpath.name,), run.ended, _count(body),
                                         _poses(statements), unknowns=run.unknown.unknowns(),
                                         skipped=tuple(run.unknown.skipped)), run

    def check_name(self, name: str, what: str) -> str:
        return check_name(name, what)

    def program_name(self, text: str) -> str:
        return program_name(text)


URSCRIPT = UrScript()


def _count(body: Sequence[Statement]) -> int:
    """Statements of a body, those inside blocks included (function definitions not)."""
    return sum(0 if st.kind == "def" else 1 + _count(st.body) + sum(_count(b) for _, b in st.branches) for st in body)


def _poses(statements: Sequence[Statement]) -> int:
    """The pose literals ``p[...]`` of a script."""
    def walk(expr) -> int:
        if not isinstance(expr, tuple) or not expr:
            return 0
        if not isinstance(expr[0], str):  # a tuple of expressions (a call's arguments, a list's items)
            return sum(walk(item) for item in expr)
        return (expr[0] == "pose") + sum(walk(item) for item in expr[1:])

    return sum(walk(st.value) + walk(st.target) + sum(walk(a) for a in st.args)
               + sum(walk(c) for c, _ in st.branches) + _poses(st.body) + sum(_poses(b) for _, b in st.branches)
               + sum(walk(d) for d in st.defaults)
               for st in statements)
