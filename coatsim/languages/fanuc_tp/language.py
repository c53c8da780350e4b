"""Fanuc TP behind coatsim's language interface."""

from __future__ import annotations

import re
from pathlib import Path
from typing import Sequence

from coatsim.core.errors import InputError
from coatsim.core.fileio import decode_text, read_program_file
from coatsim.languages.fanuc_tp.blend import DECEL_MM_S2
from coatsim.languages.fanuc_tp.names import MAX_NAME_LENGTH, check_name, program_name
from coatsim.languages.fanuc_tp.program import LsProgram, parse_ls
from coatsim.languages.fanuc_tp.writer import MAX_ARC_SWEEP_DEG, MAX_COORDINATE_MM, write_ls
from coatsim.path.language import Capabilities, ReadOptions
from coatsim.path.plan import ProgramPlan
from coatsim.path.reading import Reading
from coatsim.path.toolpath import ToolPath

_OPENING = re.compile(r"^\s*/PROG\s+\w+", re.IGNORECASE | re.MULTILINE)


class FanucTp:
    """Writes and reads Fanuc TP programs in their ASCII form (``.ls``; one program a file, CALLed
    programs from the other files read together). ``decel_mm_s2`` is the braking the CNT model
    assumes (:mod:`.blend`)."""

    name = "fanuc-tp"
    title = "Fanuc TP (.LS)"
    suffixes = (".ls",)

    def __init__(self, decel_mm_s2: float = DECEL_MM_S2) -> None:
        self.decel_mm_s2 = decel_mm_s2
        self.capabilities = Capabilities(arc_planes="any", max_arc_sweep_deg=MAX_ARC_SWEEP_DEG,
                                         blend="FINE, or CNT n (n % of the speed kept through the point)",
                                         max_name_length=MAX_NAME_LENGTH, max_coordinate_mm=MAX_COORDINATE_MM,
                                         rotation="W-P-R (fixed x-y-z, deg)", motions="L/C")

    def write(self, plan: ProgramPlan) -> str:
        return write_ls(plan, self.decel_mm_s2)

    def files(self, text: str) -> tuple[tuple[str, str], ...]:
        return ((self.suffixes[0], text),)

    def recognizes(self, text: str) -> bool:
        return _OPENING.search(text) is not None

    def read(self, files: Sequence[Path], options: ReadOptions) -> ToolPath:
        reading = self.reading(files, options)
        reading.require_complete()
        if options.needs_spray and not reading.toolpath.spray_moves:
            switched = ", ".join(f"DO[{n}]" for n in reading.outputs) or "no output"
            raise InputError(f"{files[0]}: the gun (DO[{options.gun_signal}]) is never on during a motion; the program "
                             f"switches {switched}", parameters=("gun_signal",))
        return reading.toolpath

    def reading(self, files: Sequence[Path], options: ReadOptions) -> Reading:
        if not files:
            raise InputError("no program file given")
        programs: dict[str, LsProgram] = {}
        for path in files:
            program = parse_ls(decode_text(read_program_file(path)), str(path))
            if program.name in programs:
                raise InputError(f"{path}: program {program.name} is also in {programs[program.name].source}")
            programs[program.name] = program
        main = options.program.upper() if options.program is not None else next(iter(programs))
        if main not in programs:
            raise InputError(f"program {options.program!r} is not among the files read ({', '.join(programs)})",
                             parameters=("program",))
        from coatsim.languages.fanuc_tp.interpreter import FanucRun  # the interpreter loads when a program is read

        run = FanucRun(programs, options, self.decel_mm_s2)
        toolpath = run.run(main)
        program = programs[main]
        problems = tuple(f"{p.source}:{p.line}: program name {p.name} is longer than {MAX_NAME_LENGTH} characters"
                         for p in programs.values() if len(p.name) > MAX_NAME_LENGTH)
        return run.builder.reading(toolpath, tuple(str(f) for f in files), (program.source, program.line),
                                   tuple(programs), run.ended, len(program.statements),
                                   sum(len(p.positions) for p in programs.values()), problems=problems,
                                   unknowns=run.data.unknown.unknowns(),
                                   skipped=tuple(run.data.unknown.skipped) + tuple(run.unsimulated),
                                   unsimulated=tuple(run.unsimulated))

    def check_name(self, name: str, what: str) -> str:
        return check_name(name, what)

    def program_name(self, text: str) -> str:
        return program_name(text)


FANUC_TP = FanucTp()
