"""What coatsim may write into G-code: the program name and comment text.

A program name is at most 16 characters (a Fanuc-style control shows a name of up to 16
characters after the program number), letters, digits, '_' and '-', first a letter, so that it
can stand in a comment. Comment text is printable ASCII without parentheses (a ``( )`` comment
cannot hold one) on one line.
"""

from __future__ import annotations

import re

from coatsim.core.errors import InputError
from coatsim.languages.script.names import printable, upper_case_name

MAX_NAME_LENGTH = 16
_NAME = re.compile(r"[A-Za-z][A-Za-z0-9_-]*\Z")


def clean_comment(text: str) -> str:
    """``text`` fit for a ``( )`` comment: printable ASCII, '(' and ')' as '[' and ']'."""
    return printable(text.replace("(", "[").replace(")", "]"))


def check_name(name: str, what: str = "program name") -> str:
    """``name`` if it is a valid G-code program name; InputError (one line) otherwise."""
    if not isinstance(name, str) or not _NAME.match(name) or len(name) > MAX_NAME_LENGTH:
        raise InputError(f"{what} {clean_comment(str(name))[:40]!r} is not a valid G-code program name: letters, "
                         f"digits, '_' and '-', first a letter, at most {MAX_NAME_LENGTH} characters",
                         parameters=(what,))
    return name


def program_name(text: str) -> str:
    """A valid program name from any text: upper-case letters, digits and '_', first a letter."""
    return upper_case_name(text, MAX_NAME_LENGTH)
