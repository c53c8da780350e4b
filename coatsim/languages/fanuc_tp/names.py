"""What coatsim may write into a Fanuc .LS file: program names and remark text.

A program name is upper-case letters, digits and '_', first a letter, at most 36 characters
(R-30iA and later controllers; an R-J3 keeps 8 and RoboDK's post cuts names to 10 — a name
longer than 8 loads only on the newer controllers). A remark ``! text ;`` holds at most
``REMARK_WIDTH`` characters of printable ASCII without ';' (which ends an instruction) on one line.
"""

from __future__ import annotations

import re

from coatsim.core.errors import InputError
from coatsim.languages.script.names import printable, upper_case_name

MAX_NAME_LENGTH = 36
REMARK_WIDTH = 32
_NAME = re.compile(r"[A-Z][A-Z0-9_]*\Z")


def clean_remark(text: str) -> str:
    """``text`` fit for a remark: printable ASCII, ';' as ','."""
    return printable(text.replace(";", ","))


def check_name(name: str, what: str = "program name") -> str:
    """``name`` if it is a valid Fanuc program name; InputError (one line) otherwise."""
    if not isinstance(name, str) or not _NAME.match(name) or len(name) > MAX_NAME_LENGTH:
        raise InputError(f"{what} {clean_remark(str(name))[:40]!r} is not a valid Fanuc program name: upper-case "
                         f"letters, digits and '_', first a letter, at most {MAX_NAME_LENGTH} characters",
                         parameters=(what,))
    return name


def program_name(text: str) -> str:
    """A valid program name from any text."""
    return upper_case_name(text, MAX_NAME_LENGTH)
