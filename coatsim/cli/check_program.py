"""``coatsim check-program``: read robot programs and report what they do and what looks wrong."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Optional

import typer

from coatsim.cli.common import LANGUAGE_HELP, SET_HELP
from coatsim.cli.flags import speaking_flags
from coatsim.core import defaults

if TYPE_CHECKING:
    from coatsim.path.check import ProgramCheck

FLAGS = {"gun_signal": "--gun", "program": "--program", "inputs": "--inputs", "language": "--language"}


def check_program(
    paths: list[Path] = typer.Argument(..., help="Program file(s) loaded together: programs, then data such as poses."),
    gun: int = typer.Option(defaults.GUN_SIGNAL, "--gun", help="Gun output signal number."),
    main: Optional[str] = typer.Option(None, "--program", help="Main program [default: the first of the first file that no loaded program calls, PC programs *.pc skipped; a note names it]."),
    inputs: Optional[str] = typer.Option(None, "--inputs", help="Input signals the cell sets, e.g. 1001,-1002 (minus: off)."),
    settings: Optional[list[str]] = typer.Option(None, "--set", help=SET_HELP),
    model: Optional[Path] = typer.Option(None, "--model", help="Cell MJCF for joint poses, HOME and the gun the TOOL is checked against [default: the shipped coating_cell.xml]."),
    language: Optional[str] = typer.Option(None, "--language", help=LANGUAGE_HELP),
) -> None:
    """Parse and interpret robot programs; report steps, poses, signals, sprayed path, the variables
    no file gives (--set gives them) and problems. Reading is not spraying: a program that never
    opens the gun is read (exit 0), and the outputs it switches are named (--gun picks one)."""
    from coatsim.cli.common import input_states, variables
    from coatsim.languages.registry import language_of
    from coatsim.path.check import check_program as check
    from coatsim.path.language import ReadOptions
    from coatsim.robot.cell import load_cell
    from coatsim.robot.kinematics import CellKinematics
    from coatsim.robot.sampling import plan_pieces

    cell = load_cell(model)
    with speaking_flags(FLAGS):
        options = ReadOptions(gun_signal=gun, program=main, inputs=input_states(inputs), kinematics=CellKinematics(cell),
                              variables=variables(settings))
        result = check(paths, language_of(paths, language), options, gun_tcp=(cell.gun_rotation, cell.gun_offset_mm))
        if result.toolpath.moves:
            plan_pieces(result.toolpath)  # what the robot stage would reject before any simulation
    never = bool(result.toolpath.moves) and not result.toolpath.spray_moves
    typer.echo(check_summary(result) + ("\nnote: --gun N picks the process signal" if never else ""))


def check_summary(check: ProgramCheck) -> str:
    """The report of ``coatsim check-program``: counts, lengths, then one line per problem."""
    lines = [
        f"{check.source}: program {check.program}: {check.n_steps} steps, {check.n_poses} poses; moves: "
        f"{check.n_joint_moves} joint, {check.n_linear_moves} linear, {check.n_arc_moves} arc",
        f"path length {check.path_length_mm:.3f} mm (sprayed {check.spray_length_mm:.3f} mm)",
    ]
    lines += [f"signal: {s}" for s in check.signals]
    lines += [f"sprayed: lines {r.first_line}-{r.last_line} of {r.source}, {r.moves} move{'' if r.moves == 1 else 's'}, {r.length_mm:.3f} mm"
              for r in check.spray_runs]
    lines += [f"warning: {w}" for w in check.warnings]
    lines += [f"note: {n}" for n in check.notes]
    lines += [f"unknown: {u}" for u in check.unknowns if u not in check.warnings]
    lines += [f"skipped: {s}" for s in check.skipped if s not in check.warnings]
    lines += [f"problem: {p}" for p in check.problems] or ["no problems found"]
    if check.unknowns or check.skipped:
        lines.append(f"read with {len(check.unknowns)} unknown variable{'' if len(check.unknowns) == 1 else 's'} "
                     f"and {len(check.skipped)} statement{'' if len(check.skipped) == 1 else 's'} skipped"
                     + ("; give values as --set NAME=VALUE" if check.unknowns else ""))
    return "\n".join(lines)
