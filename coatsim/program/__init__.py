"""Programs stage: placed tool paths, Kawasaki AS writing and reading, interpretation to a ToolPath."""

from __future__ import annotations

from pathlib import Path
from typing import Optional

from coatsim.errors import InputError
from coatsim.program.as_dialect import KAWASAKI_AS
from coatsim.program.as_parser import parse_as, parse_as_bytes
from coatsim.program.interpreter import interpret
from coatsim.program.dialect import Dialect
from coatsim.program.toolpath import ToolPath

# Robot languages by name; every dialect module is registered here.
DIALECTS: dict[str, Dialect] = {KAWASAKI_AS.name: KAWASAKI_AS}


def read_program_bytes(path: str | Path) -> bytes:
    """The bytes of a program file; InputError if it cannot be read."""
    try:
        return Path(path).read_bytes()
    except OSError as exc:
        raise InputError(f"{path}: cannot read program ({exc.strerror or exc})") from None


def read_toolpath(path: str | Path, gun_signal: int = 1, program: Optional[str] = None) -> ToolPath:
    """Parse and interpret an AS program file; InputError naming file:line on any defect,
    including poses the program uses but never defines."""
    return interpret(parse_as_bytes(read_program_bytes(path), str(path)), gun_signal=gun_signal, program=program)


__all__ = ["DIALECTS", "Dialect", "ToolPath", "interpret", "parse_as", "parse_as_bytes", "read_program_bytes", "read_toolpath"]
