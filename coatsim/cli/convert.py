"""``coatsim convert``: a user's program in, the same process path sprayed with arcs out."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Optional

import typer

from coatsim.cli.common import LANGUAGE_HELP, SET_HELP
from coatsim.cli.flags import fail, speaking_flags
from coatsim.core import defaults

FLAGS = {"tolerance_mm": "--tol", "gun_signal": "--gun", "lines": "--lines", "program": "--program",
         "approach_mm": "--approach", "name": "--name", "corner_deg": "--corner-deg", "standalone": "--standalone",
         "inputs": "--inputs", "language": "--language", "target": "--to", "angle_tol_deg": "--angle-tol"}


def convert(
    paths: list[Path] = typer.Argument(..., help="Program file(s) loaded together: programs, then data such as poses."),
    tol: float = typer.Option(..., "--tol", help="Tolerance sigma: largest deviation from the original path, mm."),
    output: Optional[Path] = typer.Option(None, "-o", "--output", help="Program file to write [default: the text goes to stdout]."),
    gun: int = typer.Option(defaults.GUN_SIGNAL, "--gun", help="Gun output signal number: its sprayed moves are the process path."),
    standalone: bool = typer.Option(False, "--standalone", help="A clean program of the path alone instead of the edited original."),
    lines: Optional[str] = typer.Option(None, "--lines", help="FIRST-LAST: the moves of these source lines instead of the sprayed ones."),
    main: Optional[str] = typer.Option(None, "--program", help="Main program [default: the first of the first file that no loaded program calls, PC programs *.pc skipped; a note names it]."),
    inputs: Optional[str] = typer.Option(None, "--inputs", help="Input signals the cell sets, e.g. 1001,-1002 (minus: off)."),
    settings: Optional[list[str]] = typer.Option(None, "--set", help=SET_HELP),
    model: Optional[Path] = typer.Option(None, "--model", help="Cell MJCF for joint poses and HOME [default: the shipped coating_cell.xml]."),
    corner_deg: float = typer.Option(defaults.CORNER_DEG, "--corner-deg", help="Turn within a short length that counts as a true corner, deg."),
    angle_tol: float = typer.Option(defaults.ANGLE_TOL_DEG, "--angle-tol", help="Largest angle the new program's tool may turn away from the original's along the path, deg (poses are added where it would)."),
    name: Optional[str] = typer.Option(None, "--name", help="Name of the standalone program [default: the original's]."),
    language: Optional[str] = typer.Option(None, "--language", help=LANGUAGE_HELP),
    to: Optional[str] = typer.Option(None, "--to", help="Language of the converted program (another one writes a standalone program) [default: the original's]."),
) -> None:
    """Rewrite the process path of an existing program with arcs within a tolerance, in place or
    as a standalone program in any language (--to)."""
    from coatsim.cli.common import input_states, variables
    from coatsim.core.fileio import write_bytes
    from coatsim.core.outputs_guard import check_distinct
    from coatsim.languages.registry import language as language_named, language_of
    from coatsim.path.convert import ConvertOptions, conversion_summary, convert_program
    from coatsim.path.edit import EditsInPlace
    from coatsim.path.program_files import program_paths, write_program
    from coatsim.robot.kinematics import LazyKinematics

    with speaking_flags(FLAGS):
        source = language_of(paths, language)
        target = language_named(to) if to is not None else source
        # a language named with --to that cannot be edited in place gets a standalone program
        standalone = standalone or (to is not None and (target is not source or not isinstance(source, EditsInPlace)))
        written = program_paths(target, output) if output is not None and standalone else (output,)
        check_distinct([*(("the program", p) for p in paths), ("--model", model)], [("-o", p) for p in written])
        if name is None and output is not None and target.capabilities.named_by_file:
            name = target.program_name(output.stem)  # the controller loads a program by its file's name
        options = ConvertOptions(tolerance_mm=tol, gun_signal=gun, program=main, lines=_line_range(lines),
                                 standalone=standalone, corner_deg=corner_deg, name=name, angle_tol_deg=angle_tol)
        result = convert_program(paths, options, language=source, target=target, inputs=input_states(inputs) or None,
                                 kinematics=LazyKinematics(model), variables=variables(settings))
    if not result.written:  # nothing gained: no file written, nothing on stdout, the input untouched
        typer.echo(conversion_summary(result), err=output is None)
        return
    if output is not None and result.replaces is None:
        write_program(target, result.text, output)
    elif output is not None:
        write_bytes(output, result.data)  # the original's bytes: encoding and line ends kept
    else:
        sys.stdout.flush()
        sys.stdout.buffer.write(result.data)
        sys.stdout.buffer.flush()
    typer.echo(conversion_summary(result) + (f"\nwrote {output}" if output else ""), err=output is None)


def _line_range(lines: Optional[str]) -> Optional[tuple[int, int]]:
    """--lines FIRST-LAST as two line numbers."""
    if lines is None:
        return None
    first, sep, last = lines.partition("-")
    if not (sep and first.strip().isdigit() and last.strip().isdigit() and int(first) <= int(last)):
        fail(f"--lines {lines!r}: expected FIRST-LAST source line numbers, as in 12-1911")
    return int(first), int(last)
