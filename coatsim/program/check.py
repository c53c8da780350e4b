"""``coatsim check-program``: parse and interpret an AS file and report what it does.

A program that does not parse, or moves to a pose it never defines, raises InputError
(exit 2). Anything legal but suspicious is listed in ``problems``; the ones that make the
program useless for coating (the gun never opens) are also in ``errors``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from coatsim.program import as_ast as ast
from coatsim.program.arcs import circle_through, move_length
from coatsim.program.as_parser import parse_as_bytes
from coatsim.program.as_writer import MAX_NAME_LENGTH
from coatsim.program.interpreter import interpret
from coatsim.program.tool_frames import tool_mismatches
from coatsim.program.toolpath import CircularMove, JointMove, LinearMove
from coatsim.program import read_program_bytes


@dataclass(frozen=True)
class ProgramCheck:
    """Counts and lengths of one program; lengths in mm (joint moves not included)."""

    source: str
    program: str
    n_steps: int
    n_poses: int
    n_joint_moves: int
    n_linear_moves: int
    n_arc_moves: int
    path_length_mm: float
    spray_length_mm: float
    metadata: tuple[tuple[str, str], ...]
    problems: tuple[str, ...]
    errors: tuple[str, ...] = ()


def _used_names(expr: ast.PoseExpr) -> set[str]:
    if isinstance(expr, ast.PoseName):
        return {expr.name}
    if isinstance(expr, ast.Shift):
        return _used_names(expr.base)
    if isinstance(expr, ast.Compose):
        return _used_names(expr.left) | _used_names(expr.right)
    return set()


def check_program(path: str | Path, gun_signal: int = 1,
                  gun_tcp: tuple[np.ndarray, np.ndarray] | None = None) -> ProgramCheck:
    """Parse, interpret and inspect the first program of an AS file; ``gun_tcp`` (rotation,
    offset mm of the physical gun's TCP in the flange frame) makes every TOOL that differs from
    it a problem."""
    source = str(path)
    file = parse_as_bytes(read_program_bytes(path), source)
    toolpath = interpret(file, gun_signal=gun_signal)
    program = file.programs[0]
    problems: list[str] = []
    used: set[str] = set()
    for st in program.statements:
        target = getattr(st, "target", None) or getattr(st, "pose", None)
        if target is not None:
            used |= _used_names(target)
        if isinstance(st, ast.Speed) and st.unit == "%":
            problems.append(f"{source}:{st.line}: SPEED in % depends on the robot's maximum speed; coatsim assumes 100 % = 1000 mm/s")
    for name, trans in file.trans.items():
        if len(name) > MAX_NAME_LENGTH:
            problems.append(f"{source}:{trans.line}: pose name '{name}' is longer than {MAX_NAME_LENGTH} characters")
        if name not in used and len(file.programs) == 1:
            problems.append(f"{source}:{trans.line}: pose '{name}' is defined but never used")
    if len(program.name) > MAX_NAME_LENGTH:
        problems.append(f"{source}:{program.line}: program name '{program.name}' is longer than {MAX_NAME_LENGTH} characters")
    for section, line in file.skipped:
        problems.append(f"{source}:{line}: section .{section} skipped")
    for move in toolpath.moves:
        if isinstance(move, CircularMove):
            sweep = circle_through(move.start.position, move.via.position, move.end.position).sweep
            if sweep >= math.pi:
                problems.append(f"{source}:{move.line}: arc sweeps {math.degrees(sweep):.1f} deg; keep one C1MOVE/C2MOVE pair below 180 deg")
    if gun_tcp is not None:
        for line, text in tool_mismatches(toolpath, *gun_tcp):
            problems.append(f"{source}:{line}: {text}")
    errors: list[str] = []
    if not toolpath.spray_moves:
        errors.append(f"{source}: the gun (output {gun_signal}) is never on during a motion")
        problems.append(errors[-1])
    elif toolpath.moves[-1].spray:
        problems.append(f"{source}: the gun (output {gun_signal}) is still on at the end of the program")
    cartesian = [m for m in toolpath.moves if not isinstance(m, JointMove)]
    return ProgramCheck(
        source=source,
        program=program.name,
        n_steps=len(program.statements),
        n_poses=len(file.trans),
        n_joint_moves=sum(isinstance(m, JointMove) for m in toolpath.moves),
        n_linear_moves=sum(isinstance(m, LinearMove) for m in toolpath.moves),
        n_arc_moves=sum(isinstance(m, CircularMove) for m in toolpath.moves),
        path_length_mm=float(np.sum([move_length(m) for m in cartesian])) if cartesian else 0.0,
        spray_length_mm=float(np.sum([move_length(m) for m in cartesian if m.spray])) if cartesian else 0.0,
        metadata=tuple(toolpath.metadata.items()),
        problems=tuple(problems),
        errors=tuple(errors),
    )
