"""What coatsim may write into a URScript file: function names and comment text.

A program is a function: its name an identifier (letters, digits, '_', first a letter or '_') that
is not a keyword. The URScript manual states no length limit; coatsim keeps names within
``MAX_NAME_LENGTH``. A ``#`` comment runs to the end of its line: comment text is printable ASCII.
"""

from __future__ import annotations

import re

from coatsim.core.errors import InputError
from coatsim.languages.urscript.parser import KEYWORDS

MAX_NAME_LENGTH = 31
_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")


def clean_comment(text: str) -> str:
    return "".join(ch if 32 <= ord(ch) < 127 else "?" for ch in text)


def check_name(name: str, what: str = "program name") -> str:
    """``name`` if it is a valid URScript function name; InputError (one line) otherwise."""
    if not isinstance(name, str) or not _NAME.match(name) or name in KEYWORDS or len(name) > MAX_NAME_LENGTH:
        raise InputError(f"{what} {clean_comment(str(name))[:40]!r} is not a valid URScript name: letters, digits "
                         f"and '_', not first a digit, not a keyword, at most {MAX_NAME_LENGTH} characters",
                         parameters=(what,))
    return name


def program_name(text: str) -> str:
    """A valid program name from any text (lower case)."""
    name = re.sub(r"[^a-z0-9_]+", "_", text.lower()).strip("_")
    if not name or name[0].isdigit():
        name = "p_" + name
    name = name[:MAX_NAME_LENGTH].rstrip("_") or "coat"
    return name + "_prog" if name in KEYWORDS else name
