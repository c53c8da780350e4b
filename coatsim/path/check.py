"""``coatsim check-program``: parse and interpret AS files and report what the program does.

A program that does not parse raises InputError (exit 2); one the twin cannot run raises
ExecutionError (exit 3). Reading is not spraying: a program that never opens the gun is read and
reported (``notes`` names the outputs it does switch), and what it reads that no file gives (a
variable of the controller's memory) is an unknown, named with its first line in ``unknowns``;
a statement that cannot run without a value is skipped and listed in ``skipped``. Anything legal
but suspicious is listed in ``problems``; what the interpreter does not simulate in
``warnings``. Every statement that switches outputs is listed with its line, and every stretch
the gun sprays with its lines and length.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Iterator, Mapping, Optional, Union

import numpy as np

from coatsim.core.errors import ExecutionError
from coatsim.languages.kawasaki_as.files import parse_files, Paths
from coatsim.geometry.space.primitives import arc_through
from coatsim.path.arcs import move_length
from coatsim.languages.kawasaki_as import ast, interpret_run
from coatsim.languages.kawasaki_as.names import MAX_NAME_LENGTH
from coatsim.languages.kawasaki_as.printer import expr_text
from coatsim.path.process import ProcessInfo
from coatsim.path.tool_frames import tool_mismatches
from coatsim.path.toolpath import CircularMove, JointMove, Kinematics, LinearMove, ToolPath

_LISTED = 5  # unused poses named before "and N more"


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


def walk(body: tuple[ast.Statement, ...]) -> Iterator[ast.Statement]:
    """Every statement of a body, blocks entered, in source order."""
    for st in body:
        yield st
        if isinstance(st, ast.If):
            for _, inner in st.branches:
                yield from walk(inner)
            yield from walk(st.orelse)
        elif isinstance(st, (ast.While, ast.DoUntil, ast.For)):
            yield from walk(st.body)
        elif isinstance(st, ast.Case):
            for _, inner, _ in st.branches:
                yield from walk(inner)
            yield from walk(st.default or ())


def used_names(e) -> Iterator[str]:
    """Base names (lower case, no index) of the variables an expression or statement uses."""
    if isinstance(e, ast.Name):
        yield e.name.lower()
        for i in e.index:
            yield from used_names(i)
    elif isinstance(e, tuple):
        for item in e:
            yield from used_names(item)
    elif e is not None and hasattr(e, "__dataclass_fields__") and not isinstance(e, (ast.Num, ast.Str)):
        for name in e.__dataclass_fields__:
            value = getattr(e, name)
            if isinstance(value, (tuple, ast.Name)) or hasattr(value, "__dataclass_fields__"):
                yield from used_names(value)


def _constant(e, reals: Mapping[str, float]) -> Optional[float]:
    """The value of a signal number written as a number or a .REALS variable (with a sign)."""
    if isinstance(e, ast.Num):
        return e.value
    if isinstance(e, ast.Name) and not e.index and not e.is_local:
        return reals.get(e.name.lower())
    if isinstance(e, ast.Unary) and e.op == "-":
        inner = _constant(e.operand, reals)
        return None if inner is None else -inner
    return None


def _signal_line(st: ast.Statement, gun: int, source: str, reals: Mapping[str, float]) -> Optional[str]:
    if isinstance(st, ast.Signal):
        text = "SIGNAL " + ", ".join(expr_text(e) for e in st.outputs)
        values = [_constant(e, reals) for e in st.outputs]
        gun_parts = ["gun on" if v > 0 else "gun off" for v in values if v is not None and abs(v) == gun]
        return f"{source}:{st.line}: {text}" + (f" ({', '.join(gun_parts)})" if gun_parts else "")
    if isinstance(st, ast.Pulse):
        return f"{source}:{st.line}: {st.op} {expr_text(st.signal)}" + \
            (f", {expr_text(st.seconds)}" if st.seconds is not None else "")
    if isinstance(st, ast.Bits):
        return f"{source}:{st.line}: BITS {expr_text(st.start)}, {expr_text(st.count)} = {expr_text(st.value)}"
    return None


def spray_runs(toolpath: ToolPath, sources: list[str]) -> tuple[SprayRun, ...]:
    """The stretches of consecutive moves the gun is on for; ``sources`` the file of each move."""
    runs, current = [], []
    for i, m in enumerate((*toolpath.moves, None)):
        if m is not None and m.spray:
            current.append(i)
            continue
        if current:
            moves = [toolpath.moves[k] for k in current]
            # a loop's moves come back to earlier lines: the span of the lines, in the first move's file
            lines = [toolpath.moves[k].line for k in current if sources[k] == sources[current[0]]]
            runs.append(SprayRun(min(lines), max(lines), float(sum(move_length(x) for x in moves)),
                                 len(moves), sources[current[0]]))
            current = []
    return tuple(runs)


def check_program(paths: Paths, gun_signal: int = 1, program: Optional[str] = None, *,
                  inputs: Optional[Mapping[int, bool]] = None, kinematics: Optional[Kinematics] = None,
                  gun_tcp: tuple[np.ndarray, np.ndarray] | None = None,
                  variables: Optional[Mapping[str, Union[str, float]]] = None) -> ProgramCheck:
    """Parse, interpret and inspect the main program of AS files loaded together; ``gun_tcp``
    (rotation, offset mm of the physical gun's TCP in the flange frame) makes every TOOL that
    differs from it a problem; ``variables`` gives variables values no file gives."""
    files = parse_files(paths)
    run = interpret_run(files, gun_signal, program, inputs=inputs, kinematics=kinematics, variables=variables)
    toolpath = run.toolpath
    main = run.programs[toolpath.name.lower()]
    if not toolpath.moves:
        ended = f"{run.stopped} ends it" if run.stopped else f"it ends at line {main.end_line}"
        others = [p.name for p in run.programs.values() if p is not main]
        hint = f"; choose another main program (loaded: {', '.join(others)})" if others else ""
        raise ExecutionError(f"{main.source}:{main.line}: program {main.name} has no motion ({ended} before any "
                             f"motion){hint}")
    problems: list[str] = []
    used: set[str] = set()
    signals: list[str] = []
    reals = {k: d.value for f in files for k, d in f.reals.items()}
    for p in run.programs.values():
        for st in walk(p.body):
            used.update(used_names(st))
            line = _signal_line(st, gun_signal, p.source, reals)
            if line is not None:
                signals.append(line)
            if isinstance(st, ast.Speed) and st.unit == "%":
                problems.append(f"{p.source}:{st.line}: SPEED in % depends on the robot's maximum speed; coatsim "
                                "assumes 100 % = 1000 mm/s")
        if len(p.name) > MAX_NAME_LENGTH:
            problems.append(f"{p.source}:{p.line}: program name '{p.name}' is longer than {MAX_NAME_LENGTH} characters")
    unused = []
    for f in files:
        for name, trans in f.trans.items():
            if len(trans.name) > MAX_NAME_LENGTH:
                problems.append(f"{f.source}:{trans.line}: pose name '{trans.name}' is longer than {MAX_NAME_LENGTH} "
                                "characters")
            if name.split("[")[0] not in used:
                unused.append(f"{f.source}:{trans.line}: pose '{trans.name}' is defined but never used")
    problems += unused[:_LISTED]
    if len(unused) > _LISTED:
        problems.append(f"... and {len(unused) - _LISTED} more poses defined but never used")
    sections = [f".{s.name} (line {s.line})" for f in files for s in f.sections]
    if sections:
        problems.append(f"sections not read (controller data): {', '.join(sections)}")
    for move, (name, _, _) in zip(toolpath.moves, run.move_origins):
        if isinstance(move, CircularMove):
            sweep = arc_through(move.start.translation_mm, move.via.translation_mm, move.end.translation_mm).sweep
            if sweep >= math.pi:
                problems.append(f"{run.programs[name.lower()].source}:{move.line}: arc sweeps {math.degrees(sweep):.1f} deg; keep one C1MOVE/C2MOVE "
                                "pair below 180 deg")
    if gun_tcp is not None:
        problems += [f"{main.source}:{line}: {text}" for line, text in tool_mismatches(toolpath, *gun_tcp)]
    notes: list[str] = []
    if not toolpath.spray_moves:
        notes.append(gun_never_on(files[0].source, gun_signal, run.outputs))
    elif run.gun_on_at_end:
        problems.append(f"the gun (output {gun_signal}) is still on at the end of the program")
    cartesian = [m for m in toolpath.moves if not isinstance(m, JointMove)]
    return ProgramCheck(
        source=", ".join(f.source for f in files),
        program=main.name,
        n_steps=sum(1 for st in walk(main.body) if not isinstance(st, ast.Label)),
        n_poses=sum(len(f.trans) for f in files),
        n_joint_moves=sum(isinstance(m, JointMove) for m in toolpath.moves),
        n_linear_moves=sum(isinstance(m, LinearMove) for m in toolpath.moves),
        n_arc_moves=sum(isinstance(m, CircularMove) for m in toolpath.moves),
        path_length_mm=float(np.sum([move_length(m) for m in cartesian])) if cartesian else 0.0,
        spray_length_mm=float(np.sum([move_length(m) for m in cartesian if m.spray])) if cartesian else 0.0,
        process=toolpath.process,
        problems=tuple(problems),
        signals=tuple(signals),
        spray_runs=spray_runs(toolpath, [run.programs[name.lower()].source for name, _, _ in run.move_origins]),
        warnings=toolpath.warnings,
        toolpath=toolpath,
        notes=tuple(notes),
        unknowns=tuple(u.note() for u in run.unknowns),
        skipped=run.skipped,
        outputs=run.outputs,
    )


def gun_never_on(source: str, gun_signal: int, outputs: tuple[int, ...]) -> str:
    """What to say of a program that never sprays: the outputs it switches instead."""
    switched = f"it switches output{'s' if len(outputs) > 1 else ''} {', '.join(map(str, outputs))}" if outputs \
        else "it switches no output"
    return f"{source}: the gun (output {gun_signal}) is never on during a motion; {switched}"
