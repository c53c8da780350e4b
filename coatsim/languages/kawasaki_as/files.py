"""Reading Kawasaki AS files: parse one file or several loaded together, interpret them to a ToolPath."""

from __future__ import annotations

from pathlib import Path
from typing import Mapping, Optional, Sequence, Union

from coatsim.core.errors import InputError
from coatsim.core.fileio import read_program_file
from coatsim.languages.kawasaki_as.interpreter import Run, interpret_run
from coatsim.languages.kawasaki_as.parser import parse_as_bytes
from coatsim.languages.kawasaki_as.ast import AsFile
from coatsim.path.toolpath import Kinematics, ToolPath

Paths = Union[str, Path, Sequence[Union[str, Path]]]


def parse_files(paths: Paths) -> tuple[AsFile, ...]:
    """Parse one AS file or several loaded together (programs in one, poses in another)."""
    items = [paths] if isinstance(paths, (str, Path)) else list(paths)
    if not items:
        raise InputError("no program file given")
    return tuple(parse_as_bytes(read_program_file(p), str(p)) for p in items)


def read_program(paths: Paths, gun_signal: int = 1, program: Optional[str] = None, *,
                 inputs: Optional[Mapping[int, bool]] = None, kinematics: Optional[Kinematics] = None,
                 variables: Optional[Mapping[str, Union[str, float]]] = None) -> Run:
    """Parse and interpret AS files; the run with the origin of every move. What simulates the
    program needs all of it: InputError naming the first statement skipped for want of a value
    (a pose no file gives, ...); ``variables`` gives such values."""
    run = interpret_run(parse_files(paths), gun_signal, program, inputs=inputs, kinematics=kinematics,
                        variables=variables)
    run.require_complete()
    return run


def read_toolpath(paths: Paths, gun_signal: int = 1, program: Optional[str] = None, *,
                  inputs: Optional[Mapping[int, bool]] = None, kinematics: Optional[Kinematics] = None,
                  variables: Optional[Mapping[str, Union[str, float]]] = None) -> ToolPath:
    """Parse and interpret AS files; InputError naming file:line on any defect, including
    poses the program uses but no file gives (unless ``variables`` gives them)."""
    return read_program(paths, gun_signal, program, inputs=inputs, kinematics=kinematics,
                        variables=variables).toolpath

