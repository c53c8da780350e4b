"""``coatsim check-program``: read program files in their language and report what they do.

A program that does not parse raises InputError (exit 2); one the twin cannot run raises
ExecutionError (exit 3). Reading is not spraying: a program that never opens the gun is read and
reported (``notes`` names the outputs it does switch), and what it reads that no file gives (a
variable of the controller's memory) is an unknown, named with its first line in ``unknowns``;
a statement that cannot run without a value is skipped and listed in ``skipped``. Anything legal
but suspicious is listed in ``problems``; what the interpreter does not simulate in
``warnings``. Every statement that switches outputs is listed with its line, and every stretch
the gun sprays with its lines and length. The language reads (:class:`~coatsim.path.reading.Reading`);
this module only reports.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Sequence

import numpy as np

from coatsim.core.errors import ExecutionError
from coatsim.path.arcs import move_length
from coatsim.path.language import Language, ReadOptions
from coatsim.path.process import ProcessInfo
from coatsim.path.reading import MoveSource, Reading, gun_never_on
from coatsim.path.tool_frames import tool_mismatches
from coatsim.path.toolpath import CircularMove, JointMove, LinearMove, ToolPath


@dataclass(frozen=True)
class SprayRun:
    """Consecutive moves with the gun on: source lines of the first and last (in ``source``,
    the file of the first), length in mm."""

    first_line: int
    last_line: int
    length_mm: float
    moves: int
    source: str


@dataclass(frozen=True, eq=False)
class ProgramCheck:
    """Counts and lengths of one program; lengths in mm (joint moves as chords); ``unknowns``
    the variables read that no file gives (name and first line), ``skipped`` the statements not
    run for want of a value, ``outputs`` the outputs the program switches."""

    source: str
    program: str
    n_steps: int
    n_poses: int
    n_joint_moves: int
    n_linear_moves: int
    n_arc_moves: int
    path_length_mm: float
    spray_length_mm: float
    process: ProcessInfo
    problems: tuple[str, ...]
    signals: tuple[str, ...]
    spray_runs: tuple[SprayRun, ...]
    warnings: tuple[str, ...]
    toolpath: ToolPath
    notes: tuple[str, ...] = ()
    unknowns: tuple[str, ...] = ()
    skipped: tuple[str, ...] = ()
    outputs: tuple[int, ...] = ()


def spray_runs(toolpath: ToolPath, sources: Sequence[MoveSource]) -> tuple[SprayRun, ...]:
    """The stretches of consecutive moves the gun is on for; ``sources`` where each move comes from."""
    runs, current = [], []
    for i, m in enumerate((*toolpath.moves, None)):
        if m is not None and m.spray:
            current.append(i)
            continue
        if current:
            moves = [toolpath.moves[k] for k in current]
            file = sources[current[0]].source
            # a loop's moves come back to earlier lines: the span of the lines, in the first move's file
            mine = [k for k in current if sources[k].source == file]
            first = min(toolpath.moves[k].line for k in mine)
            last = max(max(toolpath.moves[k].line, sources[k].last_line) for k in mine)  # an arc's end line
            runs.append(SprayRun(first, last, float(sum(move_length(x) for x in moves)), len(moves), file))
            current = []
    return tuple(runs)


def check_program(paths: Sequence[str | Path] | str | Path, language: Language, options: ReadOptions = ReadOptions(),
                  *, gun_tcp: tuple[np.ndarray, np.ndarray] | None = None) -> ProgramCheck:
    """Read the main program of files loaded together in ``language`` and inspect it;
    ``gun_tcp`` (rotation, offset mm of the physical gun's TCP in the flange frame) makes every
    tool that differs from it a problem."""
    items = [Path(paths)] if isinstance(paths, (str, Path)) else [Path(p) for p in paths]
    return check_reading(language.reading(items, options), options.gun_signal, gun_tcp)


def check_reading(reading: Reading, gun_signal: int, gun_tcp: tuple[np.ndarray, np.ndarray] | None = None) -> ProgramCheck:
    """The report of a program read (see :func:`check_program`)."""
    toolpath = reading.toolpath
    where = f"{reading.program_source}:{reading.program_line}: program {reading.program}"
    if not toolpath.moves and not reading.skipped:
        others = [p for p in reading.programs if p != reading.program]
        hint = f"; choose another main program (loaded: {', '.join(others)})" if others else ""
        unset = [w for w in toolpath.warnings if "is not given; taken as OFF" in w]
        hint += f"; on its way {unset[0]}" if unset else ""  # a guard on an input left it (IF NOT SIG(1001) ...)
        raise ExecutionError(f"{where} has no motion ({reading.ended} before any motion){hint}")
    problems = list(reading.problems)
    if gun_tcp is not None:
        problems += [f"{reading.program_source}:{line}: {text}" for line, text in tool_mismatches(toolpath, *gun_tcp)]
    notes = list(reading.notes)
    if not toolpath.moves and reading.unsimulated and len(reading.unsimulated) >= len(reading.skipped):
        problems.append(f"{where} makes no motion here: every motion of its run is in statements the twin does not "
                        "simulate (listed); no value given would read them")
    elif not toolpath.moves:  # read all the same: what it needs is listed, and NAME=VALUE gives it
        notes.append(f"{where} makes no motion here: every motion of its run is skipped for want of a value (the "
                     "statements skipped are listed); give the values as NAME=VALUE")
    elif not toolpath.spray_moves:
        notes.append(gun_never_on(reading.sources[0], gun_signal, reading.outputs, reading.unnumbered))
    elif reading.gun_on_at_end:
        problems.append(f"the gun (output {gun_signal}) is still on at the end of the program")
    return ProgramCheck(
        source=reading.source,
        program=reading.program,
        n_steps=reading.n_steps,
        n_poses=reading.n_poses,
        n_joint_moves=sum(isinstance(m, JointMove) for m in toolpath.moves),
        n_linear_moves=sum(isinstance(m, LinearMove) for m in toolpath.moves),
        n_arc_moves=sum(isinstance(m, CircularMove) for m in toolpath.moves),
        path_length_mm=float(sum(move_length(m) for m in toolpath.moves)),
        spray_length_mm=float(sum(move_length(m) for m in toolpath.moves if m.spray)),
        process=toolpath.process,
        problems=tuple(problems),
        signals=tuple(str(s) for s in reading.switches),
        spray_runs=spray_runs(toolpath, reading.move_sources),
        warnings=toolpath.warnings,
        toolpath=toolpath,
        notes=tuple(notes),
        unknowns=reading.unknowns,
        skipped=reading.skipped,
        outputs=reading.outputs,
    )
